// The interface between voxcast and its image module (libvoxcast_image_io.so,
// cosim/reports/image_io_oiio.cpp): the one place OpenImageIO is linked.
//
// Why a module: OpenImageIO 2.4 as Debian builds it brings about 250 shared
// libraries (codecs, OpenCV, OpenVDB, ...). Linked into voxcast, the dynamic
// loader resolved them at every start: 0.3 s of CPU and 130 MB before main(),
// for `voxcast --help` as for each of the test suite's 800 processes, most of
// which never touch an image. cosim/reports/image_io.cpp loads the module with
// dlopen the first time a file is written or read; a run that writes no image
// never loads OpenImageIO (docs/building.md, "Start-up").
//
// Plain buffers cross the boundary and errors come back as text: the module
// and voxcast are built together (same compiler and standard library), and the
// caller turns a message into voxcast::Error with its own context.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace voxcast::cosim::image_module {

// Bumped whenever Api or the types below change: a module of another build is
// refused by name instead of called with the wrong layout.
inline constexpr int kAbiVersion = 1;

enum class PixelType { UInt8, Float };

// Interleaved pixels, top row first, `channels.size()` per pixel.
struct Raster {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // names: "R", "G", "B", "A" or "layer.R", ...
  PixelType type = PixelType::Float;
  const void* data = nullptr;
};

struct FileInfo {
  int width = 0;
  int height = 0;
  int channels = 0;
  int subimages = 0;                    // frames of an animation, 1 for a still
  std::vector<std::string> attributes;  // names of the first subimage's metadata
};

// Every function returns "" on success or what went wrong (without the path,
// which the caller adds).
struct Api {
  int abi_version;
  // One still image; the format follows the extension. An .exr is ZIP-
  // compressed and carries no time stamp (same inputs, same bytes).
  std::string (*write)(const std::string& path, const Raster& raster);
  // An animated GIF of 8-bit RGB frames of one size, looping forever.
  std::string (*write_gif)(const std::string& path, const std::vector<Raster>& frames,
                           int frames_per_second);
  // The first subimage as float, `nchannels` per pixel.
  std::string (*read_float)(const std::string& path, int* width, int* height, int* nchannels,
                            std::vector<float>* data);
  std::string (*info)(const std::string& path, FileInfo* info);
};

// A file's extension in lower case ("x.EXR" -> ".exr"): what both sides read
// the format from.
inline std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace voxcast::cosim::image_module

// The module's one exported symbol.
extern "C" const voxcast::cosim::image_module::Api* voxcast_image_io_api();
