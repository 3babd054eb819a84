// Fuzz targets: the volume loaders (refmodel/volume/loaders.hpp) on arbitrary
// files. The loaders take paths, so each input is written to a per-process
// temporary folder first.
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz/targets/targets.hpp"
#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::fuzz {
namespace {

namespace fs = std::filesystem;

// One folder per process (mkdtemp), removed at exit.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "voxcast-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw Finding("cannot create a temporary folder");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

const fs::path& scratch() {
  static const ScratchDir dir;
  return dir.path();
}

std::string write_file(const fs::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw Finding("cannot write " + path.string());
  return path.string();
}

void check_volume(const ref::Volume& v, const std::string& what) {
  // A loader's promise (loaders.hpp): a validated Volume, one value per voxel.
  const std::size_t n = static_cast<std::size_t>(v.dims[0]) * static_cast<std::size_t>(v.dims[1]) *
                        static_cast<std::size_t>(v.dims[2]);
  if (v.dims[0] < 1 || v.dims[1] < 1 || v.dims[2] < 1 || v.data.size() != n)
    throw Finding(what + " returned a volume whose data do not match its dims");
}

}  // namespace

void nifti(const std::uint8_t* data, std::size_t size) {
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  const fs::path file = scratch() / (gz ? "input.nii.gz" : "input.nii");
  check_volume(ref::load_nifti(write_file(file, data, size)), "load_nifti");
}

void raw(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kSpecBytes = 8;
  if (size < kSpecBytes) return;
  ref::RawSpec spec;
  // Dims as signed 16-bit values, so zero and negative sizes are reachable.
  for (int a = 0; a < 3; ++a)
    spec.dims[static_cast<std::size_t>(a)] =
        static_cast<std::int16_t>(data[2 * a] | (data[2 * a + 1] << 8));
  static constexpr std::array<ref::RawType, 3> kTypes{ref::RawType::U8, ref::RawType::U16,
                                                      ref::RawType::I16};
  spec.type = kTypes[data[6] % 3];
  spec.big_endian = (data[7] & 1) != 0;
  // Spacing from the flags: 1, anisotropic 1:10, zero or negative (must be rejected).
  static constexpr std::array<double, 4> kSpacing{1.0, 0.1, 10.0, 0.0};
  spec.spacing = {kSpacing[(data[7] >> 1) & 3], kSpacing[(data[7] >> 3) & 3],
                  (data[7] & 0x20) != 0 ? -0.5 : 1.0};
  const fs::path file = scratch() / "input.raw";
  check_volume(ref::load_raw(write_file(file, data + kSpecBytes, size - kSpecBytes), spec),
               "load_raw");
}

void dicom(const std::uint8_t* data, std::size_t size) {
  // GDCM runs in a child process (refmodel/volume/child_process.hpp): its
  // aborts, crashes and hangs are clean rejections. The timeout is below the
  // fuzzer's -timeout (10 s in .ci/run), so a hang in GDCM is the loader's
  // error, not a libFuzzer timeout.
  constexpr std::chrono::milliseconds kParseTimeout{5000};
  const fs::path folder = scratch() / "series";
  std::error_code ec;
  fs::create_directories(folder, ec);
  write_file(folder / "slice0001.dcm", data, size);
  try {
    check_volume(ref::load_dicom_series(folder.string(), {.parse_timeout = kParseTimeout}),
                 "load_dicom_series");
  } catch (const Error& e) {
    // A child that exits on its own (not by a signal) has printed a sanitizer
    // report: a bug in our code that runs there, never a clean rejection.
    if (std::string(e.what()).find("child process ended with") != std::string::npos)
      throw Finding(e.what());
    throw;
  }
}

}  // namespace voxcast::fuzz
