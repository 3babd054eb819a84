// Single-frame DICOM Part 10 files (explicit VR little endian, CT image storage,
// 16-bit signed pixels) written byte by byte, the same layout as the fuzz
// seeds of fuzz/make_corpus.py, so that tests can build whole series with any
// geometry: gantry tilt, uneven or repeated positions. Used by the loader tests
// (tests/refmodel/test_loaders.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace voxcast::test {

struct DicomSlice {
  int columns = 1, rows = 1;
  std::array<double, 3> position{0.0, 0.0, 0.0};                    // ImagePositionPatient
  std::array<double, 6> orientation{1.0, 0.0, 0.0, 0.0, 1.0, 0.0};  // ImageOrientationPatient
  std::array<double, 2> pixel_spacing{1.0, 1.0};  // PixelSpacing: row spacing (y), column (x)
  double thickness = 1.0, slope = 1.0, intercept = 0.0;
  std::string series_uid = "1.2.826.0.1.3680043.9.7.1";
  int instance = 1;                  // InstanceNumber, also makes the SOPInstanceUID unique
  std::vector<std::int16_t> pixels;  // columns x rows, x fastest
};

namespace dicom_detail {

inline void put16(std::vector<unsigned char>& out, std::uint32_t v) {
  out.push_back(static_cast<unsigned char>(v & 0xFF));
  out.push_back(static_cast<unsigned char>((v >> 8) & 0xFF));
}

inline void put32(std::vector<unsigned char>& out, std::uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

// One element, its value padded to an even length (UI with NUL, text with space).
inline void element(std::vector<unsigned char>& out, std::uint32_t group, std::uint32_t elem,
                    const char* vr, std::vector<unsigned char> value) {
  const std::string v(vr);
  if (value.size() % 2) value.push_back(v == "UI" || v == "OB" ? 0 : ' ');
  put16(out, group);
  put16(out, elem);
  out.push_back(static_cast<unsigned char>(vr[0]));
  out.push_back(static_cast<unsigned char>(vr[1]));
  if (v == "OB" || v == "OW" || v == "SQ" || v == "UN" || v == "UT") {
    put16(out, 0);
    put32(out, static_cast<std::uint32_t>(value.size()));
  } else {
    put16(out, static_cast<std::uint32_t>(value.size()));
  }
  out.insert(out.end(), value.begin(), value.end());
}

inline std::vector<unsigned char> text(const std::string& s) { return {s.begin(), s.end()}; }

inline std::vector<unsigned char> us(std::uint32_t v) {
  std::vector<unsigned char> out;
  put16(out, v);
  return out;
}

// A decimal string (DS) of values, each at most 16 characters.
template <std::size_t N>
std::vector<unsigned char> ds(const std::array<double, N>& values) {
  std::string s;
  for (std::size_t k = 0; k < N; ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", values[k]);
    s += (k ? "\\" : "") + std::string(buf);
  }
  return text(s);
}

}  // namespace dicom_detail

inline std::vector<unsigned char> dicom_slice_bytes(const DicomSlice& s) {
  using namespace dicom_detail;
  const std::string sop_class = "1.2.840.10008.5.1.4.1.1.2";  // CT image storage
  const std::string sop_instance = s.series_uid + "." + std::to_string(s.instance);
  std::vector<unsigned char> meta;
  element(meta, 0x0002, 0x0001, "OB", {0, 1});
  element(meta, 0x0002, 0x0002, "UI", text(sop_class));
  element(meta, 0x0002, 0x0003, "UI", text(sop_instance));
  element(meta, 0x0002, 0x0010, "UI", text("1.2.840.10008.1.2.1"));
  std::vector<unsigned char> out(128, 0);
  for (char c : std::string("DICM")) out.push_back(static_cast<unsigned char>(c));
  std::vector<unsigned char> length;
  put32(length, static_cast<std::uint32_t>(meta.size()));
  element(out, 0x0002, 0x0000, "UL", length);
  out.insert(out.end(), meta.begin(), meta.end());

  std::vector<unsigned char> pixels;
  for (std::int16_t p : s.pixels) put16(pixels, static_cast<std::uint16_t>(p));
  element(out, 0x0008, 0x0016, "UI", text(sop_class));
  element(out, 0x0008, 0x0018, "UI", text(sop_instance));
  element(out, 0x0008, 0x0060, "CS", text("CT"));
  element(out, 0x0018, 0x0050, "DS", ds(std::array<double, 1>{s.thickness}));
  element(out, 0x0020, 0x000D, "UI", text("1.2.826.0.1.3680043.9.7"));
  element(out, 0x0020, 0x000E, "UI", text(s.series_uid));
  element(out, 0x0020, 0x0013, "IS", text(std::to_string(s.instance)));
  element(out, 0x0020, 0x0032, "DS", ds(s.position));
  element(out, 0x0020, 0x0037, "DS", ds(s.orientation));
  element(out, 0x0028, 0x0002, "US", us(1));
  element(out, 0x0028, 0x0004, "CS", text("MONOCHROME2"));
  element(out, 0x0028, 0x0010, "US", us(static_cast<std::uint32_t>(s.rows)));
  element(out, 0x0028, 0x0011, "US", us(static_cast<std::uint32_t>(s.columns)));
  element(out, 0x0028, 0x0030, "DS", ds(s.pixel_spacing));
  element(out, 0x0028, 0x0100, "US", us(16));
  element(out, 0x0028, 0x0101, "US", us(16));
  element(out, 0x0028, 0x0102, "US", us(15));
  element(out, 0x0028, 0x0103, "US", us(1));
  element(out, 0x0028, 0x1052, "DS", ds(std::array<double, 1>{s.intercept}));
  element(out, 0x0028, 0x1053, "DS", ds(std::array<double, 1>{s.slope}));
  element(out, 0x7FE0, 0x0010, "OW", pixels);
  return out;
}

}  // namespace voxcast::test
