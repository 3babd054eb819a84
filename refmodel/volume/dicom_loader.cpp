// DICOM series through GDCM. GDCM's headers stay in this translation unit
// (they clash with OpenImageIO's, see BUILD-NOTES.md).
//
// One folder = one series: every regular file in the folder (not recursive) is
// tried; files that are not DICOM (README, LICENSE) and DICOM files without
// pixel data (DICOMDIR) are skipped. Slices are ordered by their position along
// the slice normal, ImagePositionPatient . (row x column of ImageOrientationPatient).
// A gantry-tilted or unevenly spaced series is resampled onto a regular grid
// (slice_resample.hpp; docs/volumes.md, rule 7) unless options.resample is false.
//
// Before GDCM parses a file, its data element structure is walked here: Debian's
// GDCM 3.0 aborts the process on an assertion for many truncated files, and
// reads a file cut inside its pixel data without complaint. GDCM itself runs in
// a child process per file (child_process.hpp), because the walk cannot foresee
// every assertion: an abort, crash or hang there is an Error naming the file.

// GDCM 3.0's headers use C casts (and are not on a SYSTEM include path).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#include <gdcmAttribute.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmTrace.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/child_process.hpp"
#include "refmodel/volume/loaders.hpp"
#include "refmodel/volume/slice_resample.hpp"

namespace voxcast::ref {
namespace {

namespace fs = std::filesystem;

constexpr double kUnevenTolerance = 0.01;  // relative deviation of a slice gap from the median
constexpr double kSamePositionMm = 1e-3;   // two slices closer than this are duplicates
constexpr double kOrientationTolerance = 1e-4;

struct Slice {
  std::string name;  // file name, for messages
  std::string series_uid;
  int columns = 0, rows = 0;
  std::array<double, 3> position{};     // ImagePositionPatient, mm
  std::array<double, 6> orientation{};  // ImageOrientationPatient
  double spacing_x = 1.0, spacing_y = 1.0;
  double thickness = 0.0;
  double slope = 1.0, intercept = 0.0;
  bool is_signed = false;
  int bits_allocated = 16;
  std::vector<std::uint16_t> words;  // raw stored values, x fastest (two's complement if signed)
  double along_normal = 0.0;         // position . normal, set when sorting
};

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && s[b] == ' ') ++b;
  return s.substr(b);
}

std::string num(double v, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// --- DICOM element structure (PS3.5 section 7) ------------------------------------
// Walks the data elements of a whole file in memory, into sequences and items,
// checking that every element's value lies inside the file. Values are not
// interpreted; only the file meta group's TransferSyntaxUID is read, to choose
// the encoding of the data set.
class StructureWalk {
 public:
  explicit StructureWalk(const std::string& bytes) : b_(bytes) {}

  // Empty if the structure is complete; else what is wrong, for a message.
  std::string check(bool has_preamble) {
    try {
      pos_ = has_preamble ? 132 : 0;
      std::string syntax;
      if (has_preamble) {
        syntax = read_meta_group();
        if (syntax.empty()) throw Broken{"no TransferSyntaxUID (0002,0010) in the file meta group"};
        if (pos_ >= b_.size()) throw Broken{"no data set after the file meta group"};
      }
      if (syntax == "1.2.840.10008.1.2.1.99") return "";  // deflated: GDCM inflates and checks
      explicit_vr_ = syntax != "1.2.840.10008.1.2";
      big_endian_ = syntax == "1.2.840.10008.1.2.2";
      if (!has_preamble) explicit_vr_ = looks_like_vr(4);
      walk_elements(b_.size(), false, 0);
      return "";
    } catch (const Broken& e) {
      return e.what;
    }
  }

 private:
  struct Broken {
    std::string what;
  };
  static constexpr std::uint32_t kUndefinedLength = 0xFFFFFFFF;

  std::uint32_t u16(std::size_t p, bool big) const {
    const auto c0 = static_cast<unsigned char>(b_[p]), c1 = static_cast<unsigned char>(b_[p + 1]);
    return big ? (std::uint32_t{c0} << 8 | c1) : (std::uint32_t{c1} << 8 | c0);
  }
  std::uint32_t u32(std::size_t p, bool big) const {
    const std::uint32_t lo = u16(p, big), hi = u16(p + 2, big);
    return big ? (lo << 16 | hi) : (hi << 16 | lo);
  }
  bool looks_like_vr(std::size_t offset) const {
    return pos_ + offset + 2 <= b_.size() &&
           std::isupper(static_cast<unsigned char>(b_[pos_ + offset])) &&
           std::isupper(static_cast<unsigned char>(b_[pos_ + offset + 1]));
  }
  void need(std::uint64_t n, std::uint32_t group, std::uint32_t element) const {
    if (pos_ + n > b_.size()) {
      char tag[16];
      std::snprintf(tag, sizeof tag, "(%04X,%04X)", group, element);
      throw Broken{"element " + std::string(tag) + " at byte " + std::to_string(pos_) + " needs " +
                   std::to_string(n) + " bytes, the file ends at byte " +
                   std::to_string(b_.size())};
    }
  }
  static bool long_length_vr(const char* vr) {
    static const char* const kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                        "SV", "UC", "UN", "UR", "UT", "UV"};
    for (const char* l : kLong)
      if (vr[0] == l[0] && vr[1] == l[1]) return true;
    return false;
  }

  // The value representations of DICOM PS3.5 table 6.2-1.
  static bool known_vr(const char* vr) {
    static const char* const kVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD",
                                       "IS", "LO", "LT", "OB", "OD", "OF", "OL", "OV", "OW",
                                       "PN", "SH", "SL", "SQ", "SS", "ST", "SV", "TM", "UC",
                                       "UI", "UL", "UN", "UR", "US", "UT", "UV"};
    for (const char* k : kVrs)
      if (vr[0] == k[0] && vr[1] == k[1]) return true;
    return false;
  }

  // The file meta group (0002,xxxx): explicit VR little endian. Returns the
  // TransferSyntaxUID.
  std::string read_meta_group() {
    std::string syntax;
    while (pos_ + 8 <= b_.size() && u16(pos_, false) == 0x0002) {
      const std::uint32_t element = u16(pos_ + 2, false);
      const char vr[2] = {b_[pos_ + 4], b_[pos_ + 5]};
      // GDCM aborts (an assert) on an unknown VR in the meta group (fuzz finding
      // tests/fuzz_regress/data/dicom/meta_group_bad_vr.dcm).
      if (!known_vr(vr)) {
        char tag[16];
        std::snprintf(tag, sizeof tag, "(0002,%04X)", element);
        throw Broken{"element " + std::string(tag) + " at byte " + std::to_string(pos_) +
                     " has no valid VR"};
      }
      std::uint32_t length;
      if (long_length_vr(vr)) {
        need(12, 0x0002, element);
        length = u32(pos_ + 8, false);
        pos_ += 12;
      } else {
        length = u16(pos_ + 6, false);
        pos_ += 8;
      }
      need(length, 0x0002, element);
      if (element == 0x0010) {
        syntax = b_.substr(pos_, length);
        while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' '))
          syntax.pop_back();
      }
      pos_ += length;
    }
    return syntax;
  }

  // Elements up to `end`, or up to an item delimiter if `in_item`.
  void walk_elements(std::size_t end, bool in_item, int depth) {
    if (depth > 64) throw Broken{"sequences nested deeper than 64 levels"};
    while (pos_ < end) {
      // Top-level padding shorter than an element header: accept zeros only.
      if (!in_item && end - pos_ < 8 &&
          std::all_of(b_.begin() + static_cast<std::ptrdiff_t>(pos_), b_.end(),
                      [](char c) { return c == 0; }))
        return;
      need(8, 0, 0);
      const std::uint32_t group = u16(pos_, big_endian_), element = u16(pos_ + 2, big_endian_);
      if (group == 0xFFFE) {
        pos_ += 8;
        if (element == 0xE00D && in_item) return;
        throw Broken{"unexpected item delimiter at byte " + std::to_string(pos_ - 8)};
      }
      std::uint32_t length;
      bool implicit_items = !explicit_vr_;
      if (explicit_vr_) {
        const char vr[2] = {b_[pos_ + 4], b_[pos_ + 5]};
        // GDCM re-reads an element with an unknown VR as implicit VR, taking
        // VR and length as a 32-bit length: gigabytes to allocate for a small
        // file (fuzz finding tests/fuzz_regress/data/dicom/data_set_bad_vr.dcm).
        if (!known_vr(vr)) {
          char tag[16];
          std::snprintf(tag, sizeof tag, "(%04X,%04X)", group, element);
          throw Broken{"element " + std::string(tag) + " at byte " + std::to_string(pos_) +
                       " has no valid VR"};
        }
        if (long_length_vr(vr)) {
          need(12, group, element);
          length = u32(pos_ + 8, big_endian_);
          pos_ += 12;
        } else {
          length = u16(pos_ + 6, big_endian_);
          pos_ += 8;
        }
        implicit_items = vr[0] == 'U' && vr[1] == 'N';  // UN of undefined length: implicit VR
      } else {
        length = u32(pos_ + 4, big_endian_);
        pos_ += 8;
      }
      if (length == kUndefinedLength) {
        const bool saved = explicit_vr_;
        if (implicit_items) explicit_vr_ = false;
        walk_items(depth + 1);
        explicit_vr_ = saved;
        continue;
      }
      need(length, group, element);
      pos_ += length;
    }
    if (in_item) throw Broken{"an item of undefined length has no delimiter"};
  }

  // Items of a sequence (or fragments of encapsulated pixel data) up to the
  // sequence delimiter.
  void walk_items(int depth) {
    for (;;) {
      need(8, 0xFFFE, 0);
      const std::uint32_t group = u16(pos_, big_endian_), element = u16(pos_ + 2, big_endian_);
      const std::uint32_t length = u32(pos_ + 4, big_endian_);
      if (group != 0xFFFE || (element != 0xE000 && element != 0xE0DD))
        throw Broken{"expected a sequence item at byte " + std::to_string(pos_)};
      pos_ += 8;
      if (element == 0xE0DD) return;
      if (length == kUndefinedLength) {
        walk_elements(b_.size(), true, depth + 1);
      } else {
        need(length, group, element);
        pos_ += length;
      }
    }
  }

  const std::string& b_;
  std::size_t pos_ = 0;
  bool explicit_vr_ = true;
  bool big_endian_ = false;
};

// The whole file; empty if it cannot be read (an empty file is not DICOM either).
std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::string content(static_cast<std::size_t>(std::max<std::streamoff>(in.tellg(), 0)), '\0');
  in.seekg(0);
  if (!in.read(content.data(), static_cast<std::streamsize>(content.size()))) return {};
  return content;
}

void quiet_gdcm() {
  static std::once_flag once;
  std::call_once(once, [] {
    gdcm::Trace::DebugOff();
    gdcm::Trace::WarningOff();
    gdcm::Trace::ErrorOff();
  });
}

// --- What GDCM makes of one file (decoded in a child process) -----------------------
// GDCM runs only in a child (child_process.hpp): Debian's GDCM 3.0 aborts on
// assertions for some malformed files (fuzz finding
// tests/fuzz_regress/data/dicom/vr16_read_pre_value_assert.dcm). The child sends
// back the header fields and the decoded pixels; every check on them is made here
// in the parent.
struct Decoded {
  enum Kind : std::uint8_t { kSkip, kRefused, kImage };
  Kind kind = kSkip;
  std::string refusal;  // kRefused: why, without the file name
  std::string series_uid;
  std::uint32_t frames = 1, columns = 0, rows = 0;
  std::uint16_t samples_per_pixel = 1;
  std::uint8_t scalar = 0;  // 1 UINT8, 2 INT8, 3 UINT16, 4 INT16, 0 anything else
  std::string scalar_name;
  std::uint16_t pixel_representation = 0, bits_allocated = 0, bits_stored = 0, high_bit = 0;
  std::uint8_t has_position = 0, has_orientation = 0, has_spacing = 0, has_thickness = 0;
  std::array<double, 3> position{};
  std::array<double, 6> orientation{};
  std::array<double, 2> spacing{};  // PixelSpacing: row spacing (y), column spacing (x)
  double thickness = 0.0, slope = 1.0, intercept = 0.0;
  std::uint8_t slope_element_zero = 0;  // RescaleSlope (0028,1053) is present and 0
  std::int64_t native_length = -1;      // bytes of unencapsulated pixel data; -1 encapsulated
  std::uint8_t pixels_decoded = 0;      // GetBuffer ran and succeeded
  std::string pixels;                   // GDCM's buffer, native byte order
};

// The child's result through the pipe: the fields in order, memcpy'd (the
// parent is the same program), strings with their length first.
class Packer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    out_ += s;
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& in) : in_(in) {}
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::memcpy(&v, take(sizeof v), sizeof v);
  }
  void get(std::string& s) {
    std::uint64_t n = 0;
    get(n);
    s.assign(take(n), n);
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  const char* take(std::uint64_t n) {
    if (n > in_.size() - pos_) throw Error("the DICOM parser's child process sent a short result");
    const char* p = in_.data() + pos_;
    pos_ += n;
    return p;
  }
  const std::string& in_;
  std::size_t pos_ = 0;
};

// Packing and unpacking list the fields once, here.
template <class F>
void for_each_field(Decoded& d, F&& f) {
  f(d.kind), f(d.refusal), f(d.series_uid), f(d.frames), f(d.columns), f(d.rows);
  f(d.samples_per_pixel), f(d.scalar), f(d.scalar_name), f(d.pixel_representation);
  f(d.bits_allocated), f(d.bits_stored), f(d.high_bit);
  f(d.has_position), f(d.has_orientation), f(d.has_spacing), f(d.has_thickness);
  f(d.position), f(d.orientation), f(d.spacing), f(d.thickness);
  f(d.slope), f(d.intercept), f(d.slope_element_zero);
  f(d.native_length), f(d.pixels_decoded), f(d.pixels);
}

std::string pack(Decoded& d) {
  Packer p;
  for_each_field(d, [&](auto& v) { p.put(v); });
  return p.take();
}

Decoded unpack(const std::string& bytes) {
  Decoded d;
  Unpacker u(bytes);
  for_each_field(d, [&](auto& v) { u.get(v); });
  if (!u.at_end() || d.kind > Decoded::kImage)
    throw Error("the DICOM parser's child process sent a malformed result");
  return d;
}

Decoded refused(std::string why) {
  Decoded d;
  d.kind = Decoded::kRefused;
  d.refusal = std::move(why);
  return d;
}

// GDCM's image reader aborts (an assert) on SamplesPerPixel > 4: the element
// is checked on a plain parse first, for a clear message (fuzz finding
// tests/fuzz_regress/data/dicom/samples_per_pixel_huge.dcm).
std::string samples_per_pixel_refusal(const std::string& content) {
  std::istringstream pre(content);
  gdcm::Reader plain;
  plain.SetStream(pre);
  // Up to the pixel data: the header is all this needs.
  if (!plain.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010))) return "";
  const gdcm::DataSet& pds = plain.GetFile().GetDataSet();
  if (!pds.FindDataElement(gdcm::Tag(0x0028, 0x0002))) return "";
  const gdcm::ByteValue* spp = pds.GetDataElement(gdcm::Tag(0x0028, 0x0002)).GetByteValue();
  if (!spp) return "";
  std::uint16_t value = 0;
  if (spp->GetLength() == 2) std::memcpy(&value, spp->GetPointer(), 2);
  if (value == 1) return "";
  return "SamplesPerPixel = " + std::to_string(value) + "; only greyscale slices are supported";
}

// The image reader failed: a DICOM file without an image is skipped.
Decoded unreadable_image(const std::string& content, bool part10) {
  std::istringstream again(content);
  gdcm::Reader plain;
  plain.SetStream(again);
  if (plain.Read()) {
    if (!plain.GetFile().GetDataSet().FindDataElement(gdcm::Tag(0x7fe0, 0x0010)))
      return Decoded{};  // DICOM without an image (DICOMDIR, report, ...)
    return refused("GDCM cannot decode its pixel data");
  }
  if (part10) return refused("corrupt DICOM file (GDCM cannot parse it)");
  return Decoded{};  // not DICOM
}

std::uint8_t scalar_code(gdcm::PixelFormat::ScalarType st) {
  switch (st) {
    case gdcm::PixelFormat::UINT8: return 1;
    case gdcm::PixelFormat::INT8: return 2;
    case gdcm::PixelFormat::UINT16: return 3;
    case gdcm::PixelFormat::INT16: return 4;
    default: return 0;
  }
}

void read_geometry(const gdcm::DataSet& ds, Decoded& d) {
  d.has_position = ds.FindDataElement(gdcm::Tag(0x0020, 0x0032));
  d.has_orientation = ds.FindDataElement(gdcm::Tag(0x0020, 0x0037));
  d.has_spacing = ds.FindDataElement(gdcm::Tag(0x0028, 0x0030));
  d.has_thickness = ds.FindDataElement(gdcm::Tag(0x0018, 0x0050));
  if (d.has_position) {
    gdcm::Attribute<0x0020, 0x0032> ipp;
    ipp.SetFromDataSet(ds);
    for (unsigned k = 0; k < 3; ++k) d.position[k] = ipp.GetValue(k);
  }
  if (d.has_orientation) {
    gdcm::Attribute<0x0020, 0x0037> iop;
    iop.SetFromDataSet(ds);
    for (unsigned k = 0; k < 6; ++k) d.orientation[k] = iop.GetValue(k);
  }
  if (d.has_spacing) {
    gdcm::Attribute<0x0028, 0x0030> pixel_spacing;
    pixel_spacing.SetFromDataSet(ds);
    d.spacing = {pixel_spacing.GetValue(0), pixel_spacing.GetValue(1)};
  }
  if (d.has_thickness) {
    gdcm::Attribute<0x0018, 0x0050> thickness;
    thickness.SetFromDataSet(ds);
    d.thickness = thickness.GetValue();
  }
}

// Decodes the pixels only when the header makes that safe and useful: one
// frame of at most kMaxLoadVoxels pixels, and native pixel data that hold them
// (GDCM's buffer has the size the header promises; a huge Rows x Columns
// would be allocated whole). The parent rejects the other cases by name.
void read_pixels(const gdcm::Image& image, const gdcm::DataSet& ds, Decoded& d) {
  if (const gdcm::ByteValue* native = ds.GetDataElement(gdcm::Tag(0x7fe0, 0x0010)).GetByteValue())
    d.native_length = native->GetLength();
  const std::uint64_t count = std::uint64_t{d.columns} * d.rows;
  const std::uint64_t bytes = d.bits_allocated == 8 ? 1 : 2;
  if (d.frames != 1 || d.samples_per_pixel != 1 || d.scalar == 0 || count == 0 ||
      count > kMaxLoadVoxels)
    return;
  if (d.native_length >= 0 && static_cast<std::uint64_t>(d.native_length) < count * bytes) return;
  d.pixels.resize(image.GetBufferLength());
  d.pixels_decoded = image.GetBuffer(d.pixels.data());
  if (!d.pixels_decoded) d.pixels.clear();
}

// The child's work: everything GDCM does with one file.
Decoded decode_with_gdcm(const std::string& content, bool part10) {
  if (std::string why = samples_per_pixel_refusal(content); !why.empty())
    return refused(std::move(why));
  std::istringstream stream(content);
  gdcm::ImageReader reader;
  reader.SetStream(stream);
  if (!reader.Read()) return unreadable_image(content, part10);
  const gdcm::Image& image = reader.GetImage();
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  Decoded d;
  d.kind = Decoded::kImage;
  gdcm::Attribute<0x0020, 0x000e> series;
  series.SetFromDataSet(ds);
  d.series_uid = std::string(series.GetValue());
  d.frames = image.GetNumberOfDimensions() > 2 ? image.GetDimension(2) : 1;
  d.columns = image.GetDimension(0);
  d.rows = image.GetDimension(1);
  const gdcm::PixelFormat& pf = image.GetPixelFormat();
  d.samples_per_pixel = pf.GetSamplesPerPixel();
  d.scalar = scalar_code(pf.GetScalarType());
  d.scalar_name = pf.GetScalarTypeAsString();
  d.pixel_representation = pf.GetPixelRepresentation();
  d.bits_allocated = pf.GetBitsAllocated();
  d.bits_stored = pf.GetBitsStored();
  d.high_bit = pf.GetHighBit();
  read_geometry(ds, d);
  d.slope = image.GetSlope();
  if (ds.FindDataElement(gdcm::Tag(0x0028, 0x1053))) {
    gdcm::Attribute<0x0028, 0x1053> slope;
    slope.SetFromDataSet(ds);
    d.slope_element_zero = slope.GetValue() == 0.0;
  }
  d.intercept = image.GetIntercept();
  read_pixels(image, ds, d);
  return d;
}

// A file GDCM is to parse.
struct Candidate {
  fs::path file;
  std::string where;  // folder/name, for messages
  bool part10 = false;
};

// The Error for the file the child was parsing when it aborted, crashed, hung
// or threw.
Error child_failure(const ChildResult& r, const std::string& where) {
  using O = ChildResult::Outcome;
  switch (r.outcome) {
    case O::Threw: return Error(where + ": GDCM failed while parsing (" + r.detail + ")");
    case O::Signalled:
      return Error(where + ": GDCM " + (r.detail == "SIGABRT" ? "aborted" : "crashed") +
                   " while parsing (" + r.detail + ")");
    case O::TimedOut: return Error(where + ": GDCM did not finish parsing (" + r.detail + ")");
    case O::Exited:
    case O::Done: break;
  }
  return Error(where + ": the DICOM parser's child process ended with " + r.detail +
               " while parsing");
}

// GDCM's view of every candidate, in order, from one child process (the child
// reads each file again: the parent keeps no file contents). If the child
// fails, the result is shorter than `candidates` and `failure` holds its
// outcome: the next candidate is the file at fault.
std::vector<Decoded> decode_isolated(const std::vector<Candidate>& candidates,
                                     std::chrono::milliseconds timeout, ChildResult& failure) {
  std::vector<Decoded> decoded;
  decoded.reserve(candidates.size());
  failure = run_in_child(
      [&](const ChildSend& send) {
        for (const Candidate& c : candidates) {
          const std::string content = read_file(c.file);
          Decoded d = content.empty() ? refused("cannot open for reading")
                                      : decode_with_gdcm(content, c.part10);
          send(pack(d));
        }
      },
      [&](std::string&& bytes) { decoded.push_back(unpack(bytes)); }, timeout);
  if (failure.outcome == ChildResult::Outcome::Done && decoded.size() != candidates.size()) {
    failure.outcome = ChildResult::Outcome::Exited;
    failure.detail = "status 0 after " + std::to_string(decoded.size()) + " of " +
                     std::to_string(candidates.size()) + " files";
  }
  return decoded;
}

// The checks on GDCM's fields, in the order a reader would meet the problems.
void check_format(const Decoded& d, const std::string& where) {
  if (d.frames > 1)
    throw Error(where + ": a multi-frame image (" + std::to_string(d.frames) +
                " frames); only series of single-frame slices are supported");
  if (d.samples_per_pixel != 1)
    throw Error(where + ": SamplesPerPixel = " + std::to_string(d.samples_per_pixel) +
                "; only greyscale slices are supported");
  if (d.scalar == 0)
    throw Error(where + ": pixel type " + d.scalar_name +
                " is not supported (8 or 16 bits allocated)");
  if (d.columns < 1 || d.rows < 1) throw Error(where + ": empty image");
  if (std::uint64_t{d.columns} * d.rows > kMaxLoadVoxels)
    throw Error(where + ": " + std::to_string(d.columns) + "x" + std::to_string(d.rows) +
                " pixels, more than the limit of 2^31 voxels");
  if (!d.has_position)
    throw Error(where + ": no ImagePositionPatient (0020,0032); cannot order the slices");
  if (!d.has_orientation)
    throw Error(where + ": no ImageOrientationPatient (0020,0037); cannot order the slices");
  if (!d.has_spacing) throw Error(where + ": no PixelSpacing (0028,0030)");
}

void check_rescale(Slice& s, const Decoded& d, const std::string& where) {
  s.slope = d.slope;
  // GDCM reports a RescaleSlope of 0 as 1 (a silent reinterpretation: every
  // voxel would be the intercept); the element itself decides (fuzz seed
  // fuzz/corpus/dicom/broken_zero_slope.dcm).
  if (d.slope_element_zero) s.slope = 0.0;
  s.intercept = d.intercept;
  if (!std::isfinite(s.slope) || s.slope == 0.0 || !std::isfinite(s.intercept))
    throw Error(where + ": RescaleSlope " + num(s.slope) + " / RescaleIntercept " +
                num(s.intercept) + " are not usable");
}

// Pixel values: GDCM decodes the transfer syntax; the value is the low
// BitsStored bits of each allocated word (signed: two's complement of that
// width), so any bits above HighBit (old overlay planes) are dropped here.
void convert_pixels(Slice& s, const Decoded& d, const std::string& where) {
  const int bits_stored = d.bits_stored;
  if (d.high_bit != bits_stored - 1 || bits_stored < 1 || bits_stored > s.bits_allocated)
    throw Error(where + ": BitsStored " + std::to_string(bits_stored) + " / HighBit " +
                std::to_string(d.high_bit) + " is not supported (need HighBit = BitsStored - 1)");
  const std::uint32_t value_mask = (std::uint32_t{1} << bits_stored) - 1;
  const std::uint32_t sign_bit = std::uint32_t{1} << (bits_stored - 1);
  const std::size_t count = static_cast<std::size_t>(s.columns) * static_cast<std::size_t>(s.rows);
  const std::size_t bytes = s.bits_allocated == 8 ? 1 : 2;
  // Native (unencapsulated) pixel data shorter than Rows x Columns: GDCM's
  // buffer has the size the header promises and GetBuffer still succeeds, so
  // the missing pixels would be silently made up (fuzz finding
  // tests/fuzz_regress/data/dicom/short_pixel_data.dcm).
  if (d.native_length >= 0 && static_cast<std::size_t>(d.native_length) < count * bytes)
    throw Error(where + ": pixel data hold " + std::to_string(d.native_length) + " bytes, " +
                std::to_string(s.columns) + "x" + std::to_string(s.rows) + " pixels need " +
                std::to_string(count * bytes));
  if (!d.pixels_decoded) throw Error(where + ": GDCM cannot decode its pixel data");
  if (d.pixels.size() < count * bytes)
    throw Error(where + ": pixel data hold " + std::to_string(d.pixels.size()) + " bytes, " +
                std::to_string(s.columns) + "x" + std::to_string(s.rows) + " pixels need " +
                std::to_string(count * bytes));
  s.words.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t word;
    if (bytes == 1) {
      word = static_cast<unsigned char>(d.pixels[k]);
    } else {
      std::uint16_t w;
      std::memcpy(&w, &d.pixels[2 * k], 2);  // GDCM returns native byte order
      word = w;
    }
    word &= value_mask;
    // Signed: sign-extend from BitsStored into the 16-bit two's complement word.
    if (s.is_signed && (word & sign_bit) != 0) word |= ~value_mask;
    s.words[k] = static_cast<std::uint16_t>(word);
  }
}

// A Slice from GDCM's fields, or an Error naming the field at fault.
void slice_from(const Decoded& d, const std::string& where, Slice& s) {
  s.series_uid = trim(d.series_uid);
  check_format(d, where);
  s.is_signed = d.pixel_representation != 0;
  s.bits_allocated = d.bits_allocated;
  s.columns = static_cast<int>(d.columns);
  s.rows = static_cast<int>(d.rows);
  s.position = d.position;
  s.orientation = d.orientation;
  s.spacing_y = d.spacing[0];
  s.spacing_x = d.spacing[1];
  s.thickness = d.has_thickness ? d.thickness : 0.0;
  check_rescale(s, d, where);
  convert_pixels(s, d, where);
}

// What the parent decides about a file before GDCM sees it.
struct Screened {
  enum Kind { kSkip, kBroken, kParse } kind = kSkip;
  std::string broken;  // kBroken: the message
  bool part10 = false;
};

// Reads one file and walks its element structure (our code, in the parent, so
// the fuzzer sees its coverage). Files that are not DICOM are skipped.
Screened screen_file(const fs::path& file, const std::string& where) {
  Screened r;
  std::error_code ec;
  const std::string content = read_file(file);
  if (content.empty() && fs::file_size(file, ec) != 0) {
    r.kind = Screened::kBroken;
    r.broken = where + ": cannot open for reading";
    return r;
  }
  // DICOM Part 10 files carry "DICM" after a 128-byte preamble. A file without
  // it is taken as a bare DICOM data set only if it starts with an element of
  // group 0002 or 0008 and its whole element structure parses.
  r.part10 = content.size() >= 132 && content.compare(128, 4, "DICM") == 0;
  if (!r.part10) {
    const bool plausible =
        content.size() >= 8 && (content.compare(0, 2, std::string("\x02\x00", 2)) == 0 ||
                                content.compare(0, 2, std::string("\x08\x00", 2)) == 0);
    if (!plausible) return r;  // not DICOM
  }
  const std::string broken = StructureWalk(content).check(r.part10);
  if (!broken.empty()) {
    if (!r.part10) return r;  // not DICOM
    r.kind = Screened::kBroken;
    r.broken = where + ": truncated or corrupt DICOM file (" + broken + ")";
    return r;
  }
  r.kind = Screened::kParse;
  return r;
}

// Every file of the folder, in name order: the slices, and the names of the
// files skipped (not DICOM, or DICOM without pixel data). The first file in
// name order that cannot be used throws.
std::vector<Slice> read_slices(const std::vector<fs::path>& files, const std::string& folder,
                               std::chrono::milliseconds timeout,
                               std::vector<std::string>& skipped) {
  std::vector<Screened> screened;
  std::vector<Candidate> candidates;
  for (const fs::path& f : files) {
    const std::string where = folder + "/" + f.filename().string();
    screened.push_back(screen_file(f, where));
    if (screened.back().kind == Screened::kBroken) break;  // nothing after it is reached
    if (screened.back().kind == Screened::kParse)
      candidates.push_back({f, where, screened.back().part10});
  }
  ChildResult failure;
  const std::vector<Decoded> decoded =
      candidates.empty() ? std::vector<Decoded>{} : decode_isolated(candidates, timeout, failure);
  std::vector<Slice> slices;
  std::size_t next = 0;  // the next candidate
  for (std::size_t k = 0; k < screened.size(); ++k) {
    const Screened& sc = screened[k];
    if (sc.kind == Screened::kBroken) throw Error(sc.broken);
    if (sc.kind == Screened::kSkip) {
      skipped.push_back(files[k].filename().string());
      continue;
    }
    const Candidate& c = candidates[next];
    if (next >= decoded.size()) throw child_failure(failure, c.where);
    const Decoded& d = decoded[next++];
    if (d.kind == Decoded::kSkip) {
      skipped.push_back(files[k].filename().string());
      continue;
    }
    if (d.kind == Decoded::kRefused) throw Error(c.where + ": " + d.refusal);
    Slice s;
    s.name = files[k].filename().string();
    slice_from(d, c.where, s);
    slices.push_back(std::move(s));
  }
  return slices;
}

std::int32_t raw_value(const Slice& s, std::size_t k) {
  const std::uint16_t w = s.words[k];
  return s.is_signed ? static_cast<std::int32_t>(static_cast<std::int16_t>(w)) : w;
}

bool near(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance; }

// Step 5 (rule 7): `v` holds the slices in order along the normal; it becomes
// their resampling onto a regular grid, and a line on `options.notices` says so.
void resample(Volume& v, const std::vector<Slice>& slices, std::uint16_t fill, bool tilted,
              const DicomOptions& options) {
  const std::array<double, 6>& o = slices.front().orientation;
  const double row_len = std::hypot(o[0], o[1], o[2]), column_len = std::hypot(o[3], o[4], o[5]);
  const StackLayout layout{v.dims[0], v.dims[1], v.spacing.x, v.spacing.y};
  const std::size_t per_slice = slices.front().words.size();
  std::vector<StackSlice> stack;
  for (std::size_t z = 0; z < slices.size(); ++z) {
    const std::array<double, 3>& p = slices[z].position;
    stack.push_back({slices[z].name, v.data.data() + z * per_slice,
                     (p[0] * o[0] + p[1] * o[1] + p[2] * o[2]) / row_len,
                     (p[0] * o[3] + p[1] * o[4] + p[2] * o[5]) / column_len,
                     slices[z].along_normal});
  }
  const RegularGrid grid = plan_regular_grid(stack, layout, v.source);
  std::vector<std::uint16_t> data = resample_stack(stack, layout, grid, fill);
  v.data = std::move(data);
  v.dims[2] = grid.slices;
  v.spacing.z = grid.spacing_z;
  v.bits = bits_for(*std::max_element(v.data.begin(), v.data.end()));

  std::string what;
  if (tilted) what = "gantry tilt " + num(grid.tilt_deg, "%.1f") + " deg";
  if (grid.uneven_gaps > 0)
    what += (what.empty() ? "" : " and ") + std::to_string(grid.uneven_gaps) +
            (grid.uneven_gaps == 1 ? " uneven gap" : " uneven gaps");
  std::ostream& out = options.notices != nullptr ? *options.notices : std::cerr;
  out << "voxcast: " << v.source << ": " << what << " resampled onto " << v.dims[0] << "x"
      << v.dims[1] << "x" << v.dims[2] << " at " << num(v.spacing.x, "%.4g") << "x"
      << num(v.spacing.y, "%.4g") << "x" << num(v.spacing.z, "%.4g") << " mm (linear)\n";
}

}  // namespace

Volume load_dicom_series(const std::string& folder, const DicomOptions& options) {
  quiet_gdcm();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error(folder + ": no such folder");

  // Step 1: read every slice in the folder, in file-name order (for stable messages).
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file()) files.push_back(e.path());
  if (ec) throw Error(folder + ": cannot list the folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  std::vector<std::string> skipped;
  std::vector<Slice> slices = read_slices(files, folder, options.parse_timeout, skipped);
  if (slices.empty()) {
    std::string list;
    for (const std::string& n : skipped) list += (list.empty() ? "" : ", ") + n;
    throw Error(folder + ": no DICOM image slices found" +
                (skipped.empty() ? std::string(" (the folder is empty)")
                                 : " (skipped non-image files: " + list + ")"));
  }

  // Step 2: exactly one series, and slices that agree on geometry and format.
  std::map<std::string, int> series;
  for (const Slice& s : slices) ++series[s.series_uid];
  if (series.size() > 1) {
    std::string list;
    for (const auto& [uid, n] : series)
      list += (list.empty() ? "" : "; ") + (uid.empty() ? "<no SeriesInstanceUID>" : uid) + " (" +
              std::to_string(n) + (n == 1 ? " file)" : " files)");
    throw Error(folder + ": holds " + std::to_string(series.size()) +
                " series, expected one: " + list);
  }
  const Slice& first = slices.front();
  for (const Slice& s : slices) {
    const std::string where = folder + "/" + s.name;
    if (s.columns != first.columns || s.rows != first.rows)
      throw Error(where + ": " + std::to_string(s.columns) + "x" + std::to_string(s.rows) +
                  " pixels, but " + first.name + " has " + std::to_string(first.columns) + "x" +
                  std::to_string(first.rows));
    for (int k = 0; k < 6; ++k)
      if (!near(s.orientation[k], first.orientation[k], kOrientationTolerance))
        throw Error(where + ": ImageOrientationPatient differs from " + first.name + "'s");
    if (!near(s.spacing_x, first.spacing_x, 1e-4 * first.spacing_x) ||
        !near(s.spacing_y, first.spacing_y, 1e-4 * first.spacing_y))
      throw Error(where + ": PixelSpacing differs from " + first.name + "'s");
    if (s.slope != first.slope || s.intercept != first.intercept)
      throw Error(where + ": RescaleSlope/Intercept " + num(s.slope) + "/" + num(s.intercept) +
                  " differ from " + first.name + "'s " + num(first.slope) + "/" +
                  num(first.intercept));
    if (s.is_signed != first.is_signed || s.bits_allocated != first.bits_allocated)
      throw Error(where + ": pixel format differs from " + first.name + "'s");
  }
  if (!(first.spacing_x > 0.0) || !(first.spacing_y > 0.0) || !std::isfinite(first.spacing_x) ||
      !std::isfinite(first.spacing_y))
    throw Error(folder + "/" + first.name + ": PixelSpacing " + num(first.spacing_y) + "\\" +
                num(first.spacing_x) + " is not usable");
  const std::uint64_t voxels = static_cast<std::uint64_t>(first.columns) *
                               static_cast<std::uint64_t>(first.rows) * slices.size();
  if (voxels > kMaxLoadVoxels)
    throw Error(folder + ": " + std::to_string(voxels) + " voxels, more than the limit of 2^31");

  // Step 3: order along the slice normal; positions distinct. Uneven gaps and
  // positions off the normal (gantry tilt) are resampled in step 5, or refused.
  const std::array<double, 6>& o = first.orientation;
  const std::array<double, 3> normal{o[1] * o[5] - o[2] * o[4], o[2] * o[3] - o[0] * o[5],
                                     o[0] * o[4] - o[1] * o[3]};
  const double normal_len = std::hypot(normal[0], normal[1], normal[2]);
  if (!(normal_len > 0.5))
    throw Error(folder + "/" + first.name + ": ImageOrientationPatient has no valid normal");
  for (Slice& s : slices)
    s.along_normal =
        (s.position[0] * normal[0] + s.position[1] * normal[1] + s.position[2] * normal[2]) /
        normal_len;
  std::stable_sort(slices.begin(), slices.end(),
                   [](const Slice& a, const Slice& b) { return a.along_normal < b.along_normal; });
  double spacing_z = first.thickness > 0.0 ? first.thickness : 1.0;
  std::string uneven, tilted;  // the first irregularity of each kind, as refused without resampling
  if (slices.size() > 1) {
    const std::size_t n = slices.size();
    for (std::size_t k = 0; k + 1 < n; ++k)
      if (slices[k + 1].along_normal - slices[k].along_normal < kSamePositionMm)
        throw Error(folder + ": " + slices[k].name + " and " + slices[k + 1].name +
                    " are both at slice position " + num(slices[k].along_normal) +
                    " mm (duplicate slice)");
    // Each gap is compared with the median gap, so that one missing slice is
    // reported where it is missing.
    std::vector<double> gaps(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k)
      gaps[k] = slices[k + 1].along_normal - slices[k].along_normal;
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t k = 0; k + 1 < n && uneven.empty(); ++k)
      if (std::abs(gaps[k] - median) > kUnevenTolerance * median)
        uneven = folder + ": the gap between " + slices[k].name + " and " + slices[k + 1].name +
                 " is " + num(gaps[k]) + " mm, the series' median is " + num(median) +
                 " mm (slices unevenly spaced by more than 1%: a slice missing or extra?)";
    spacing_z = (slices[n - 1].along_normal - slices[0].along_normal) / static_cast<double>(n - 1);
    // The positions must move along the normal (no gantry tilt / shear).
    for (std::size_t k = 1; k < n && tilted.empty(); ++k) {
      std::array<double, 3> d{};
      for (int a = 0; a < 3; ++a) d[a] = slices[k].position[a] - slices[0].position[a];
      const double along = slices[k].along_normal - slices[0].along_normal;
      double lateral2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double l = d[a] - along * normal[a] / normal_len;
        lateral2 += l * l;
      }
      if (std::sqrt(lateral2) > kUnevenTolerance * along + 1e-3)
        tilted = folder + ": " + slices[k].name + " is offset " + num(std::sqrt(lateral2)) +
                 " mm sideways from the slice normal through " + slices[0].name +
                 " (gantry tilt or sheared series: not supported)";
    }
    if (!options.resample && !uneven.empty()) throw Error(uneven);
    if (!options.resample && !tilted.empty()) throw Error(tilted);
  }

  // Step 4: values. physical = slope * raw + intercept; raw values are shifted
  // up by -min if min < 0, and the intercept absorbs the shift.
  std::int32_t lo = raw_value(slices[0], 0), hi = lo;
  for (const Slice& s : slices)
    for (std::size_t k = 0; k < s.words.size(); ++k) {
      lo = std::min(lo, raw_value(s, k));
      hi = std::max(hi, raw_value(s, k));
    }
  const std::int32_t shift = std::min(lo, 0);
  if (hi - shift > 0xFFFF)
    throw Error(folder + ": values span " + std::to_string(lo) + ".." + std::to_string(hi) +
                ", wider than 16 bits");
  Volume v;
  v.source = folder;
  v.dims = {first.columns, first.rows, static_cast<int>(slices.size())};
  v.spacing = glm::dvec3(first.spacing_x, first.spacing_y, spacing_z);
  v.slope = first.slope;
  v.intercept = first.intercept + first.slope * static_cast<double>(shift);
  v.bits = bits_for(static_cast<std::uint32_t>(hi - shift));
  v.data.resize(v.voxel_count());
  const std::size_t per_slice = slices[0].words.size();
  for (std::size_t z = 0; z < slices.size(); ++z)
    for (std::size_t k = 0; k < per_slice; ++k)
      v.data[z * per_slice + k] = static_cast<std::uint16_t>(raw_value(slices[z], k) - shift);
  // Step 5: an irregular series onto a regular grid (rule 7).
  if (!uneven.empty() || !tilted.empty())
    resample(v, slices, static_cast<std::uint16_t>(lo - shift), !tilted.empty(), options);
  validate(v, folder);
  return v;
}

}  // namespace voxcast::ref
