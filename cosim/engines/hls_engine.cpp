// The hls engine on the host: loads the frame state from the shared set-up,
// runs the synthesizable kernels (hls/vizard2_top.hpp) over row ranges on the
// machine's cores, and traces single rays for mismatch reports.
#include <memory>
#include <type_traits>

#include "cosim/engines/engines.hpp"
#include "hls/host_frame.hpp"
#include "hls/host_march.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"

namespace voxcast::cosim {
namespace {

template <class P>
std::array<std::uint32_t, 4> to_array(const hls::OutputPixel<P>& px) {
  return {static_cast<std::uint32_t>(px.ch[0].to_uint64()),
          static_cast<std::uint32_t>(px.ch[1].to_uint64()),
          static_cast<std::uint32_t>(px.ch[2].to_uint64()),
          static_cast<std::uint32_t>(px.ch[3].to_uint64())};
}

template <class P>
ref::QuantImage render(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory,
                       int threads, ref::FrameStats* stats) {
  const auto frame = hls::host::load_frame_state<P>(fs, "hls engine");
  const auto empty = hls::host::empty_blocks<P>(fs, memory);  // hls/host_march.hpp
  const auto packed = hls::host::engine_packed_words<P>(memory);
  const int w = fs.regs.width, h = fs.regs.height;
  std::vector<hls::OutputPixel<P>> fb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  std::vector<hls::RowStats> rows(static_cast<std::size_t>(h));
  ref::parallel_for(
      h,
      [&](int y) {
        // Counted on this thread's stack, then stored: rows[y] and rows[y + 1] share a
        // cache line, and the other thread is rendering row y + 1.
        hls::RowStats row;
        hls::host::EngineBanks<P> banks(memory, packed ? packed->data() : nullptr);
        banks.blocks = empty.get();
        banks.skipped = &row.samples;
        hls::render_rows<P>(*frame, banks, w, y, y + 1, fb.data(), &row);
        rows[static_cast<std::size_t>(y)] = row;
      },
      threads);
  ref::QuantImage img(w, h, P::out_bits);
  for (std::size_t i = 0; i < fb.size(); ++i) img.pixels[i] = to_array<P>(fb[i]);
  if (stats) {
    *stats = ref::FrameStats{};
    stats->rays = fb.size();
    for (const hls::RowStats& r : rows) {
      stats->samples += r.samples;
      stats->samples_skipped += r.samples_skipped;
      stats->rays_hit += r.rays_hit;
      stats->rays_terminated_early += r.rays_terminated_early;
    }
  }
  return img;
}

// Records every unit's output as doubles, in bittrue::RayTrace's layout, so a
// trace compares field by field with the bit-true engine's.
template <class P>
struct Recorder {
  bittrue::RayTrace& out;

  void ray(const hls::RaySetup<P>& r) {
    out.hit = r.hit;
    out.samples = r.hit ? r.n.to_uint64() : 0;
    for (int a = 0; a < 3; ++a) {
      out.p0[static_cast<std::size_t>(a)] = r.hit ? r.p0[a].to_double() : 0.0;
      out.step[static_cast<std::size_t>(a)] = r.hit ? r.s[a].to_double() : 0.0;
    }
  }
  template <class Pos>
  bittrue::SampleTrace base(const Pos& p, const hls::Sample<P>& s) {
    bittrue::SampleTrace t;
    for (std::size_t a = 0; a < 3; ++a) {
      t.position[a] = p[a].to_double();
      t.gradient[a] = s.g[a].to_double();
    }
    t.value = s.value.to_double();
    return t;
  }
  void skip(std::uint64_t) {}  // skipped samples leave no trace, as in the bit-true engine
  void ert(std::uint64_t) {}   // the trace ends at the terminating sample
  // MIP sample.
  template <class Pos, class M>
  void sample(const Pos& p, const hls::Sample<P>& s, const M& peak) {
    bittrue::SampleTrace t = base(p, s);
    t.accumulator[0] = peak.to_double();
    out.trace.push_back(t);
  }
  // Compositing sample.
  template <class Pos>
  void sample(const Pos& p, const hls::Sample<P>& s, const hls::ClassEntry<P>& e,
              const hls::Reflect<P>& r, const hls::ShadedColor<P>& c,
              const hls::Accumulator<P>& acc) {
    bittrue::SampleTrace t = base(p, s);
    t.class_address = static_cast<int>(hls::class_address<P>(s.value).to_uint64());
    t.alpha = e.alpha.to_double();
    if (e.alpha != 0) {
      t.diffuse = r.D.to_double();
      t.specular = r.S.to_double();
      for (std::size_t k = 0; k < 3; ++k) t.shaded[k] = c.c[k].to_double();
    }
    t.accumulator = {acc.C[0].to_double(), acc.C[1].to_double(), acc.C[2].to_double(),
                     acc.A.to_double()};
    out.trace.push_back(t);
  }
};

template <class P>
bittrue::RayTrace trace(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory, int px,
                        int py) {
  const auto frame = hls::host::load_frame_state<P>(fs, "hls engine");
  const hls::host::BitTrueBanks<P> banks(memory);
  bittrue::RayTrace t;
  Recorder<P> rec{t};
  std::uint64_t n = 0;
  t.out = to_array<P>(hls::cast_ray<P>(*frame, banks, px, py, n, rec));
  return t;
}

template <class Fn>
void with_profile(const PrecisionProfile& p, Fn&& fn) {
  if (!hls::host::dispatch_profile(p, fn))
    throw Error(std::string("this precision profile is not compiled into the hls engine (") +
                hls::host::kCompiledProfileNames + ")");
}

}  // namespace

bool hls_supports(const PrecisionProfile& p) {
  return hls::host::dispatch_profile(p, []<class>() {});
}

std::string hls_supported_profiles() { return hls::host::kCompiledProfileNames; }

ref::QuantImage hls_render_image(const bittrue::FrameSetup& setup,
                                 const bittrue::VoxelMemory& memory, int threads,
                                 ref::FrameStats* stats) {
  ref::QuantImage img;
  with_profile(setup.profile, [&]<class P>() {
    img = render<P>(setup, memory, threads, stats);
  });
  return img;
}

bittrue::RayTrace hls_trace_ray(const bittrue::FrameSetup& setup,
                                const bittrue::VoxelMemory& memory, int px, int py) {
  bittrue::RayTrace t;
  with_profile(setup.profile, [&]<class P>() { t = trace<P>(setup, memory, px, py); });
  return t;
}

}  // namespace voxcast::cosim
