// Single-file NIfTI-1 images written byte by byte from the standard's header
// struct (nifti1.h, self-contained), so that tests can also express broken
// headers: absurd or negative dims, a bad vox_offset, non-finite scaling, the
// other byte order. Used by the loader tests (tests/refmodel/test_loaders.cpp)
// and the command-line bad-input cases (tests/extremes/test_bad_input.cpp).
#pragma once

#include <nifti/nifti1.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <vector>

namespace voxcast::test {

static_assert(sizeof(nifti_1_header) == 348, "the NIfTI-1 header is 348 bytes");

struct NiftiSpec {
  std::array<short, 8> dim{3, 1, 1, 1, 1, 1, 1, 1};
  short datatype = DT_UINT8;
  short bitpix = 8;
  std::array<float, 3> pixdim{1.0f, 1.0f, 1.0f};
  float vox_offset = 352.0f;  // the header's value; the data are written at byte 352
  float scl_slope = 0.0f, scl_inter = 0.0f;
  char xyzt_units = NIFTI_UNITS_MM;
  bool big_endian = false;  // header and data in big-endian byte order
};

template <typename T>
void swap_bytes(T& v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  std::reverse(b, b + sizeof(T));
  std::memcpy(&v, b, sizeof(T));
}

// The file: the 348-byte header, the 4-byte extension flag (no extensions),
// the data from byte 352 (in the spec's byte order, words of bitpix bits).
inline std::vector<unsigned char> nifti_bytes(const NiftiSpec& s, std::vector<unsigned char> data) {
  nifti_1_header h{};
  h.sizeof_hdr = 348;
  std::copy(s.dim.begin(), s.dim.end(), h.dim);
  h.datatype = s.datatype;
  h.bitpix = s.bitpix;
  h.pixdim[0] = 1.0f;
  for (std::size_t a = 0; a < 3; ++a) h.pixdim[a + 1] = s.pixdim[a];
  h.vox_offset = s.vox_offset;
  h.scl_slope = s.scl_slope;
  h.scl_inter = s.scl_inter;
  h.xyzt_units = s.xyzt_units;
  std::memcpy(h.magic, "n+1", 4);
  if (s.big_endian) {
    swap_bytes(h.sizeof_hdr);
    for (short& d : h.dim) swap_bytes(d);
    swap_bytes(h.datatype);
    swap_bytes(h.bitpix);
    for (float& d : h.pixdim) swap_bytes(d);
    swap_bytes(h.vox_offset);
    swap_bytes(h.scl_slope);
    swap_bytes(h.scl_inter);
    const std::size_t width = static_cast<std::size_t>(s.bitpix / 8);
    for (std::size_t i = 0; width > 1 && i + width <= data.size(); i += width)
      std::reverse(data.begin() + static_cast<std::ptrdiff_t>(i),
                   data.begin() + static_cast<std::ptrdiff_t>(i + width));
  }
  // One allocation and two copies (GCC 12 at -O3 reports a false -Warray-bounds
  // on appending to a 352-byte vector).
  std::vector<unsigned char> file(352 + data.size(), 0);
  std::memcpy(file.data(), &h, sizeof h);
  if (!data.empty()) std::memcpy(file.data() + 352, data.data(), data.size());
  return file;
}

}  // namespace voxcast::test
