// Image output. `.exr`: 32-bit float RGBA, premultiplied, the volume alone (the
// background is not composited, so the alpha channel stays meaningful for
// analysis and compositing). `.png`: 8-bit RGB for people, composited over the
// scene's background. Written through OpenImageIO, which voxcast loads on the
// first image it writes or reads (image_io_module.hpp: a program that writes
// none starts without it); when it cannot be loaded, these throw
// voxcast::Error naming the paths tried.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "refmodel/render/image.hpp"

namespace voxcast::cosim {

// Throws voxcast::Error unless `path` ends in .png or .exr (checked before a
// render starts, so a typo does not cost a whole render).
void check_image_path(const std::string& path);

void write_image(const std::string& path, const ref::Image& image, const glm::dvec3& background);

// A multi-layer OpenEXR file: each named layer's RGBA as channels
// "NAME.R", "NAME.G", "NAME.B", "NAME.A" (all layers the same size).
struct Layer {
  std::string name;
  const ref::Image* image;
};
void write_exr_layers(const std::string& path, const std::vector<Layer>& layers);

// An animated GIF (OpenImageIO's GIF writer; 256-colour palette per frame,
// composited over the background like PNG), looping forever.
void write_animation(const std::string& path, const std::vector<ref::Image>& frames,
                     const glm::dvec3& background, int frames_per_second);

// Reads an image written by write_image (any format OpenImageIO reads) as RGBA.
ref::Image read_image(const std::string& path);

// What a file holds, without its pixels: size, channels, subimages (frames of
// an animation) and the names of its metadata attributes.
struct ImageFileInfo {
  int width = 0;
  int height = 0;
  int channels = 0;
  int subimages = 0;
  std::vector<std::string> attributes;
};
ImageFileInfo read_image_info(const std::string& path);

}  // namespace voxcast::cosim
