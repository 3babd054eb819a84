// Volume input: NIfTI-1 files, raw files, DICOM series and built-in phantoms.
//
// Every loader returns a validated Volume (see volume.hpp) or throws
// voxcast::Error with a one-line message naming the file and the field at
// fault ("head.nii.gz: dim[2] = -4 is not a valid size").
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>

#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

enum class RawType { U8, U16, I16 };

// The largest volume any loader accepts: 2^31 voxels (a larger header is
// refused with an Error before anything is allocated).
inline constexpr std::uint64_t kMaxLoadVoxels = std::uint64_t{1} << 31;

struct RawSpec {
  std::array<int, 3> dims{0, 0, 0};
  RawType type = RawType::U8;
  glm::dvec3 spacing{1.0, 1.0, 1.0};
  bool big_endian = false;
};

// NIfTI-1 (.nii, .nii.gz) through niftilib. scl_slope/scl_inter are honoured:
// integer data keep their integer values (shifted to be unsigned) and record
// slope/intercept; float data are quantised to 16 bits over their range.
Volume load_nifti(const std::string& path);

// Headerless raw voxels, x fastest, little-endian unless spec.big_endian.
// Signed data are shifted to unsigned (intercept records the shift).
Volume load_raw(const std::string& path, const RawSpec& spec);

// A folder holding the slices of one DICOM series (GDCM). CT slices are
// converted to Hounsfield units through Rescale Slope/Intercept. GDCM parses
// each file in a child process (refmodel/volume/child_process.hpp): if it
// aborts, crashes or takes longer than `parse_timeout`, the Error names the
// file and the cause. A gantry-tilted series or one with uneven gaps is
// resampled onto a regular grid (docs/volumes.md, "DICOM series", rule 7) and
// one line saying so goes to `notices`; with `resample` false it is refused.
inline constexpr std::chrono::milliseconds kDicomParseTimeout{30000};
struct DicomOptions {
  bool resample = true;  // the scene's volume.resample
  std::chrono::milliseconds parse_timeout = kDicomParseTimeout;
  std::ostream* notices = nullptr;  // the resampling notice; nullptr = std::cerr
};
Volume load_dicom_series(const std::string& folder, const DicomOptions& options = {});

// Built-in phantoms, generated in code: "shepp-logan", "shells", "tube", "box".
// `size` is the edge length in voxels (cubic grid). `aa` > 1 gives partial
// volume: each voxel is the mean of aa^3 point samples inside it (what a
// scanner's finite voxel integrates); aa = 1 samples the voxel centre, the
// closed forms the tests rely on.
Volume make_phantom(const std::string& name, int size, int aa = 1);

// Resolves a scene's `volume.source`: "phantom:NAME[?size=N]", a NIfTI path, a
// raw path (needs `raw`), or a folder of DICOM slices (read with `dicom`).
// `base_dir` resolves relative paths (the scene file's folder).
Volume load_volume(const std::string& source, const std::string& base_dir, const RawSpec* raw,
                   const DicomOptions& dicom = {});

}  // namespace voxcast::ref
