// The fuzz targets' bodies (docs/extremes.md, "Fuzzing"). Each takes one input
// and either returns (accepted), throws voxcast::Error (rejected with a
// message), or reports a finding: throws Finding (a differential mismatch or a
// broken invariant). Crashes, sanitizer reports and any other exception are
// findings too. fuzz/entry.cpp runs them under libFuzzer;
// tests/fuzz_regress/ replays saved inputs through them with any compiler.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace voxcast::fuzz {

// Not a voxcast::Error: a finding must never be mistaken for a clean rejection.
class Finding : public std::logic_error {
 public:
  explicit Finding(const std::string& what) : std::logic_error("fuzz finding: " + what) {}
};

// The scene parser (refmodel/scene/scene_toml.cpp): the input is a scene file's
// text. An accepted scene must survive scene_to_toml -> parse_scene unchanged.
void scene_toml(const std::uint8_t* data, std::size_t size);

// load_nifti on the input written to a temporary .nii (.nii.gz when the input
// starts with the gzip magic).
void nifti(const std::uint8_t* data, std::size_t size);

// load_raw: the first 8 bytes are the RawSpec (3 x uint16 dims, type, flags),
// the rest is the file.
void raw(const std::uint8_t* data, std::size_t size);

// load_dicom_series on a temporary folder holding the input as its one slice.
void dicom(const std::uint8_t* data, std::size_t size);

// hls/fixed_point.hpp against an independent long-double model of
// /work/shared/fixed-point-semantics.md sections 2, 3, 5 and 9, and against the
// bit-true model's double quantizers (refmodel/bittrue/quantize.hpp).
void fixed_point(const std::uint8_t* data, std::size_t size);

}  // namespace voxcast::fuzz
