#include "cosim/reports/image_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include <dlfcn.h>

#include "cosim/reports/image_io_module.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim {
namespace {

namespace im = image_module;
using im::extension_of;

// --- The module (image_io_module.hpp) ----------------------------------------
// Where libvoxcast_image_io.so is looked for, in order: VOXCAST_IMAGE_IO_MODULE
// alone when it is set; beside the running program as installed
// (VOXCAST_IMAGE_IO_FROM_BINDIR: bin/../LIBDIR/voxcast); the build tree's own
// path.
std::vector<std::string> module_candidates() {
  if (const char* env = std::getenv("VOXCAST_IMAGE_IO_MODULE"); env && *env) return {env};
  std::vector<std::string> paths;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back((exe.parent_path() / VOXCAST_IMAGE_IO_FROM_BINDIR).lexically_normal());
  paths.push_back(VOXCAST_IMAGE_IO_BUILD_PATH);
  return paths;
}

const im::Api& load_module() {
  std::string tried;
  for (const std::string& path : module_candidates()) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      tried += "\n  " + path + ": " + (why ? why : "cannot load");
      continue;
    }
    using Entry = const im::Api* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "voxcast_image_io_api"));
    const im::Api* api = entry ? entry() : nullptr;
    if (api && api->abi_version == im::kAbiVersion) return *api;  // stays loaded
    tried += "\n  " + path + ": " +
             (api ? "a module of another voxcast build (interface " +
                        std::to_string(api->abi_version) + ", this one reads " +
                        std::to_string(im::kAbiVersion) + ")"
                  : std::string("not voxcast's image module (no voxcast_image_io_api)"));
    dlclose(handle);
  }
  throw Error("image files need voxcast's image module (libvoxcast_image_io.so, OpenImageIO); "
              "none could be loaded:" + tried +
              "\nInstall voxcast with `cmake --install`, or name the module's path in "
              "VOXCAST_IMAGE_IO_MODULE.");
}

// Loaded once, on the first image, by whichever thread gets there first; a
// failure is thrown to each caller again.
const im::Api& image_api() {
  static std::mutex m;
  static const im::Api* api = nullptr;
  const std::lock_guard<std::mutex> lock(m);
  if (!api) api = &load_module();
  return *api;
}

void check(const std::string& path, const std::string& error) {
  if (!error.empty()) throw Error(path + ": " + error);
}

im::Raster raster(int width, int height, std::vector<std::string> channels, im::PixelType type,
                  const void* data) {
  im::Raster r;
  r.width = width;
  r.height = height;
  r.channels = std::move(channels);
  r.type = type;
  r.data = data;
  return r;
}

std::uint8_t to_8bit(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

// 8-bit RGB for people: the premultiplied image composited over the background.
std::vector<std::uint8_t> to_rgb8(const ref::Image& image, const glm::dvec3& background) {
  std::vector<std::uint8_t> rgb(3 * image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::dvec4& p = image.pixels[i];
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = to_8bit(p[c] + (1.0 - p.a) * background[c]);
  }
  return rgb;
}

}  // namespace

void check_image_path(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".png" && ext != ".exr")
    throw Error(path + ": unsupported image type \"" + ext + "\" (use .exr or .png)");
}

void write_image(const std::string& path, const ref::Image& image, const glm::dvec3& background) {
  const std::string ext = extension_of(path);
  const std::size_t n = image.pixels.size();
  if (ext == ".exr") {
    std::vector<float> rgba(4 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c) rgba[4 * i + c] = static_cast<float>(image.pixels[i][c]);
    check(path, image_api().write(path, raster(image.width, image.height, {"R", "G", "B", "A"},
                                                im::PixelType::Float, rgba.data())));
  } else if (ext == ".png") {
    const std::vector<std::uint8_t> rgb = to_rgb8(image, background);
    check(path, image_api().write(path, raster(image.width, image.height, {"R", "G", "B"},
                                                im::PixelType::UInt8, rgb.data())));
  } else {
    check_image_path(path);
  }
}

void write_exr_layers(const std::string& path, const std::vector<Layer>& layers) {
  if (layers.empty()) throw Error(path + ": no layers to write");
  const int w = layers.front().image->width, h = layers.front().image->height;
  const int nch = 4 * static_cast<int>(layers.size());
  std::vector<std::string> channels;
  for (const Layer& l : layers)
    for (const char* c : {"R", "G", "B", "A"}) channels.push_back(l.name + "." + c);
  std::vector<float> data(static_cast<std::size_t>(w) * h * nch);
  for (std::size_t li = 0; li < layers.size(); ++li) {
    const ref::Image& img = *layers[li].image;
    if (img.width != w || img.height != h) throw Error(path + ": layers differ in size");
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 4; ++c)
        data[i * nch + 4 * li + c] = static_cast<float>(img.pixels[i][c]);
  }
  check(path, image_api().write(path, raster(w, h, std::move(channels), im::PixelType::Float,
                                              data.data())));
}

void write_animation(const std::string& path, const std::vector<ref::Image>& frames,
                     const glm::dvec3& background, int frames_per_second) {
  if (extension_of(path) != ".gif")
    throw Error(path + ": unsupported animation type (use .gif)");
  if (frames.empty()) throw Error(path + ": no frames to write");
  if (frames_per_second < 1 || frames_per_second > 100)
    throw Error(path + ": animation rate " + std::to_string(frames_per_second) +
                " frames/s is outside 1..100");
  std::vector<std::vector<std::uint8_t>> rgb;
  std::vector<im::Raster> rasters;
  rgb.reserve(frames.size());
  for (const ref::Image& f : frames) {
    if (f.width != frames.front().width || f.height != frames.front().height)
      throw Error(path + ": animation frames differ in size");
    rgb.push_back(to_rgb8(f, background));
    rasters.push_back(
        raster(f.width, f.height, {"R", "G", "B"}, im::PixelType::UInt8, rgb.back().data()));
  }
  check(path, image_api().write_gif(path, rasters, frames_per_second));
}

ref::Image read_image(const std::string& path) {
  int width = 0, height = 0, nch = 0;
  std::vector<float> data;
  check(path, image_api().read_float(path, &width, &height, &nch, &data));
  ref::Image img(width, height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      img.pixels[i][c] = c < nch ? data[i * static_cast<std::size_t>(nch) + static_cast<std::size_t>(c)] : 1.0;
  return img;
}

ImageFileInfo read_image_info(const std::string& path) {
  im::FileInfo i;
  check(path, image_api().info(path, &i));
  return {i.width, i.height, i.channels, i.subimages, std::move(i.attributes)};
}

}  // namespace voxcast::cosim
