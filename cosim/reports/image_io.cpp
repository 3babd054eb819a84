#include "cosim/reports/image_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "refmodel/error.hpp"

namespace voxcast::cosim {
namespace {

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void write_pixels(const std::string& path, const OIIO::ImageSpec& spec, const void* data) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw Error(path + ": cannot write images of this type (" + OIIO::geterror() + ")");
  if (!out->open(path, spec) || !out->write_image(spec.format, data) || !out->close())
    throw Error(path + ": " + out->geterror());
}

// Same inputs, same bytes: OpenImageIO stamps an EXR with the time of writing
// (a DateTime attribute, OpenEXR's capDate) unless the spec names one; an
// empty DateTime writes none.
void unstamped(OIIO::ImageSpec& spec) { spec.attribute("DateTime", ""); }

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
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    unstamped(spec);
    write_pixels(path, spec, rgba.data());
  } else if (ext == ".png") {
    const std::vector<std::uint8_t> rgb = to_rgb8(image, background);
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    write_pixels(path, spec, rgb.data());
  } else {
    check_image_path(path);
  }
}

void write_exr_layers(const std::string& path, const std::vector<Layer>& layers) {
  if (layers.empty()) throw Error(path + ": no layers to write");
  const int w = layers.front().image->width, h = layers.front().image->height;
  const int nch = 4 * static_cast<int>(layers.size());
  OIIO::ImageSpec spec(w, h, nch, OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  for (const Layer& l : layers)
    for (const char* c : {"R", "G", "B", "A"}) spec.channelnames.push_back(l.name + "." + c);
  spec.attribute("compression", "zip");
  unstamped(spec);
  std::vector<float> data(static_cast<std::size_t>(w) * h * nch);
  for (std::size_t li = 0; li < layers.size(); ++li) {
    const ref::Image& img = *layers[li].image;
    if (img.width != w || img.height != h) throw Error(path + ": layers differ in size");
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 4; ++c)
        data[i * nch + 4 * li + c] = static_cast<float>(img.pixels[i][c]);
  }
  write_pixels(path, spec, data.data());
}

void write_animation(const std::string& path, const std::vector<ref::Image>& frames,
                     const glm::dvec3& background, int frames_per_second) {
  if (extension_of(path) != ".gif")
    throw Error(path + ": unsupported animation type (use .gif)");
  if (frames.empty()) throw Error(path + ": no frames to write");
  if (frames_per_second < 1 || frames_per_second > 100)
    throw Error(path + ": animation rate " + std::to_string(frames_per_second) +
                " frames/s is outside 1..100");
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->supports("multiimage"))
    throw Error(path + ": this OpenImageIO cannot write animated GIF (" + OIIO::geterror() + ")");
  std::vector<OIIO::ImageSpec> specs;
  for (const ref::Image& f : frames) {
    if (f.width != frames.front().width || f.height != frames.front().height)
      throw Error(path + ": animation frames differ in size");
    OIIO::ImageSpec spec(f.width, f.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("FramesPerSecond", OIIO::TypeRational, std::array<int, 2>{frames_per_second, 1}.data());
    spec.attribute("oiio:LoopCount", 0);  // loop forever
    specs.push_back(spec);
  }
  if (!out->open(path, static_cast<int>(specs.size()), specs.data()))
    throw Error(path + ": " + out->geterror());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && !out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage))
      throw Error(path + ": frame " + std::to_string(i) + ": " + out->geterror());
    const std::vector<std::uint8_t> rgb = to_rgb8(frames[i], background);
    if (!out->write_image(OIIO::TypeDesc::UINT8, rgb.data()))
      throw Error(path + ": frame " + std::to_string(i) + ": " + out->geterror());
  }
  if (!out->close()) throw Error(path + ": " + out->geterror());
}

ref::Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot read image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> data(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw Error(path + ": " + in->geterror());
  ref::Image img(spec.width, spec.height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      img.pixels[i][c] = c < spec.nchannels ? data[i * spec.nchannels + c] : 1.0;
  return img;
}

}  // namespace voxcast::cosim
