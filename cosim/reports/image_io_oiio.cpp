// The image module (libvoxcast_image_io.so): image files through OpenImageIO,
// behind the plain interface of image_io_module.hpp. voxcast loads it on the
// first image it writes or reads (image_io.cpp); nothing else links
// OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <array>
#include <memory>

#include "cosim/reports/image_io_module.hpp"

namespace voxcast::cosim::image_module {
namespace {

OIIO::TypeDesc type_of(PixelType t) {
  return t == PixelType::UInt8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
}

OIIO::ImageSpec spec_of(const Raster& r) {
  OIIO::ImageSpec spec(r.width, r.height, static_cast<int>(r.channels.size()), type_of(r.type));
  spec.channelnames = r.channels;
  return spec;
}

std::string message(const std::string& what) { return what.empty() ? "unknown error" : what; }

std::string write(const std::string& path, const Raster& raster) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "cannot write images of this type (" + message(OIIO::geterror()) + ")";
  OIIO::ImageSpec spec = spec_of(raster);
  if (extension_of(path) == ".exr") {
    spec.attribute("compression", "zip");
    // OpenImageIO stamps an EXR with the time of writing (a DateTime
    // attribute, OpenEXR's capDate) unless the spec names one; an empty
    // DateTime writes none.
    spec.attribute("DateTime", "");
  }
  if (!out->open(path, spec) || !out->write_image(spec.format, raster.data) || !out->close())
    return message(out->geterror());
  return "";
}

std::string write_gif(const std::string& path, const std::vector<Raster>& frames,
                      int frames_per_second) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->supports("multiimage"))
    return "this OpenImageIO cannot write animated GIF (" + message(OIIO::geterror()) + ")";
  std::vector<OIIO::ImageSpec> specs;
  for (const Raster& f : frames) {
    OIIO::ImageSpec spec = spec_of(f);
    spec.attribute("FramesPerSecond", OIIO::TypeRational,
                   std::array<int, 2>{frames_per_second, 1}.data());
    spec.attribute("oiio:LoopCount", 0);  // loop forever
    specs.push_back(spec);
  }
  if (!out->open(path, static_cast<int>(specs.size()), specs.data()))
    return message(out->geterror());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && !out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage))
      return "frame " + std::to_string(i) + ": " + message(out->geterror());
    if (!out->write_image(OIIO::TypeDesc::UINT8, frames[i].data))
      return "frame " + std::to_string(i) + ": " + message(out->geterror());
  }
  if (!out->close()) return message(out->geterror());
  return "";
}

std::string read_float(const std::string& path, int* width, int* height, int* nchannels,
                       std::vector<float>* data) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read image (" + message(OIIO::geterror()) + ")";
  const OIIO::ImageSpec& spec = in->spec();
  data->assign(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels, 0.0f);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data->data()))
    return message(in->geterror());
  *width = spec.width;
  *height = spec.height;
  *nchannels = spec.nchannels;
  return "";
}

std::string info(const std::string& path, FileInfo* out) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read image (" + message(OIIO::geterror()) + ")";
  const OIIO::ImageSpec& spec = in->spec();
  out->width = spec.width;
  out->height = spec.height;
  out->channels = spec.nchannels;
  out->attributes.clear();
  for (const OIIO::ParamValue& p : spec.extra_attribs) out->attributes.push_back(p.name().string());
  int subimages = 1;
  while (in->seek_subimage(subimages, 0)) ++subimages;
  out->subimages = subimages;
  return "";
}

const Api kApi{kAbiVersion, write, write_gif, read_float, info};

}  // namespace
}  // namespace voxcast::cosim::image_module

extern "C" __attribute__((visibility("default"))) const voxcast::cosim::image_module::Api*
voxcast_image_io_api() {
  return &voxcast::cosim::image_module::kApi;
}
