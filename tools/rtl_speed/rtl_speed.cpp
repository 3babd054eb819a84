// voxcast_rtl_speed SCENE [--set KEY=VALUE]... [--repeat N] [--quiet]
//
// Renders the scene's first view on the rtl cycle model N times (default 1)
// and prints, for the last run, every statistic of the frame (RtlStats'
// operator<<: cycles, stalls, row outcomes, activates per bank, FIFO
// occupancies) and an FNV-1a hash of the image's channel values, then the
// simulation's CPU time of each run (this thread's CPU clock, the set-up of
// the volume excluded) as M samples and M card cycles per CPU second.
// --quiet leaves out the statistics (timing only). The statistics part is
// what tools/rtl_identity.sh compares; the timing lines start with "cpu".
#include <time.h>

#include <cstdint>
#include <cstdlib>
#include <exception>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::uint64_t image_hash(const voxcast::ref::QuantImage& image) {
  std::uint64_t h = 1469598103934665603ull;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (std::uint32_t c : image.at(x, y)) {
        h ^= c;
        h *= 1099511628211ull;
      }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace voxcast;
  try {
    std::string path;
    ref::Overrides sets;
    int repeat = 1;
    bool quiet = false;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--set" && i + 1 < argc) {
        sets.push_back(argv[++i]);
      } else if (a == "--repeat" && i + 1 < argc) {
        repeat = std::max(1, std::atoi(argv[++i]));
      } else if (a == "--quiet") {
        quiet = true;
      } else if (path.empty() && a.rfind("--", 0) != 0) {
        path = a;
      } else {
        std::cerr << "usage: voxcast_rtl_speed SCENE [--set KEY=VALUE]... [--repeat N] [--quiet]\n";
        return 64;
      }
    }
    if (path.empty()) {
      std::cerr << "usage: voxcast_rtl_speed SCENE [--set KEY=VALUE]... [--repeat N] [--quiet]\n";
      return 64;
    }
    const ref::Scene s = ref::load_scene_file(path, sets);
    const ref::Volume volume =
        ref::load_volume(s.volume.source, s.base_dir, s.volume.raw ? &*s.volume.raw : nullptr);
    ref::validate_against_volume(s, volume);  // as voxcast render: the crop inside the volume
    const ref::GradientField gradients = ref::compute_gradients(volume, s.volume.gradient);
    const ref::CameraPose pose = ref::frame_poses(s.camera, 1).front();
    const ref::RenderInputs in = ref::make_render_inputs(s, volume, gradients, pose);
    const bittrue::FrameSetup setup = bittrue::make_frame_setup(s.precision, s, in);
    const bittrue::VoxelMemory memory = bittrue::make_voxel_memory(s.precision, volume, gradients);
    const rtl::RtlConfig config = rtl::rtl_config(s.rtl);

    rtl::RtlResult r;
    std::vector<double> cpu;
    for (int k = 0; k < repeat; ++k) {
      const double c0 = thread_cpu_seconds();
      r = rtl::rtl_render(setup, memory, config);
      cpu.push_back(thread_cpu_seconds() - c0);
    }
    if (!quiet) {
      std::cout << "config: " << config << "\n" << r.stats;
      std::cout << "image " << r.image.width << "x" << r.image.height << " fnv1a "
                << std::hex << image_hash(r.image) << std::dec << "\n";
    }
    std::cout << std::fixed << std::setprecision(3);
    for (double c : cpu)
      std::cout << "cpu " << c << " s: " << static_cast<double>(r.stats.samples) / c / 1e6
                << " M samples/CPU s, " << static_cast<double>(r.stats.cycles) / c / 1e6
                << " M cycles/CPU s (" << r.stats.samples << " samples, " << r.stats.cycles
                << " cycles)\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "voxcast_rtl_speed: " << e.what() << "\n";
    return 1;
  }
}
