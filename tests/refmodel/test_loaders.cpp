// Volume loaders: NIfTI-1, raw, DICOM series and volume.source resolution.
//
// NIfTI files are written here in two ways: byte by byte from the standard's
// header struct (nifti1.h, self-contained), which can also express broken
// headers, and with niftilib's own writer where its headers are on the include
// path (nifti_make_new_nim / nifti_image_write).
#include <gtest/gtest.h>
#include <nifti/nifti1.h>
#include <zlib.h>

#if __has_include(<nifti1_io.h>)
#include <nifti1_io.h>
#define VOXCAST_TEST_HAVE_NIFTILIB 1
#endif

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"
#include "tests/common/dicom_bytes.hpp"
#include "tests/common/error_of.hpp"
#include "tests/common/nifti_bytes.hpp"

namespace voxcast::ref {
namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

// A fresh folder under the test temp dir, removed with its contents.
class ScratchDir {
 public:
  ScratchDir() {
    static std::atomic<int> counter{0};
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(testing::TempDir()) /
            ("voxcast_" + std::string(info ? info->name() : "test") + "_" +
             std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

using test::error_of;

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "message: " << (haystack) << "\nexpected to contain: " << (needle)

void write_bytes(const fs::path& p, const std::vector<unsigned char>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << p;
}

template <typename T>
std::vector<unsigned char> as_bytes(const std::vector<T>& values) {
  std::vector<unsigned char> out(values.size() * sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// --- NIfTI files written byte by byte ----------------------------------------------


struct NiftiSpec : test::NiftiSpec {
  bool gzip = false;  // write a .nii.gz
};

// Single-file NIfTI-1 (tests/common/nifti_bytes.hpp), gzip-compressed if s.gzip.
void write_nifti(const fs::path& p, const NiftiSpec& s, std::vector<unsigned char> data) {
  const std::vector<unsigned char> file = test::nifti_bytes(s, std::move(data));
  if (s.gzip) {
    gzFile gz = gzopen(p.c_str(), "wb");
    ASSERT_NE(gz, nullptr) << p;
    ASSERT_EQ(gzwrite(gz, file.data(), static_cast<unsigned>(file.size())),
              static_cast<int>(file.size()));
    ASSERT_EQ(gzclose(gz), Z_OK);
  } else {
    write_bytes(p, file);
  }
}

NiftiSpec spec_3d(short nx, short ny, short nz, short datatype, short bitpix) {
  NiftiSpec s;
  s.dim = {3, nx, ny, nz, 1, 1, 1, 1};
  s.datatype = datatype;
  s.bitpix = bitpix;
  return s;
}

TEST(NiftiLoader, Int16KeepsIntegersShiftedAndHonoursScaling) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(5, 4, 3, DT_INT16, 16);
  s.pixdim = {0.5f, 0.75f, 2.0f};
  s.scl_slope = 2.5f;
  s.scl_inter = -7.0f;
  std::vector<std::int16_t> raw(60);
  for (int i = 0; i < 60; ++i) raw[static_cast<std::size_t>(i)] = static_cast<std::int16_t>(i - 20);
  write_nifti(dir / "a.nii", s, as_bytes(raw));

  const Volume v = load_nifti((dir / "a.nii").string());
  EXPECT_EQ(v.dims, (std::array<int, 3>{5, 4, 3}));
  EXPECT_EQ(v.spacing.x, 0.5);
  EXPECT_EQ(v.spacing.y, 0.75);
  EXPECT_EQ(v.spacing.z, 2.0);
  EXPECT_EQ(v.bits, 6);  // stored 0..59
  EXPECT_EQ(v.slope, 2.5);
  EXPECT_EQ(v.intercept, -7.0 + 2.5 * -20.0);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    EXPECT_EQ(v.data[i], raw[i] + 20);
    EXPECT_EQ(v.to_physical(v.data[i]), 2.5 * raw[i] - 7.0);
  }
  EXPECT_EQ(v.source, (dir / "a.nii").string());
}

TEST(NiftiLoader, ZeroSlopeMeansNoScaling) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(4, 2, 2, DT_UINT8, 8);
  s.scl_slope = 0.0f;
  s.scl_inter = 9.0f;  // ignored when scl_slope = 0 (NIfTI-1)
  s.gzip = true;
  std::vector<std::uint8_t> raw(16);
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<std::uint8_t>(10 * i);
  write_nifti(dir / "b.nii.gz", s, as_bytes(raw));
  const Volume v = load_nifti((dir / "b.nii.gz").string());
  EXPECT_EQ(v.slope, 1.0);
  EXPECT_EQ(v.intercept, 0.0);
  EXPECT_EQ(v.bits, 8);  // max 150
  EXPECT_EQ(v.data, std::vector<std::uint16_t>(raw.begin(), raw.end()));
}

TEST(NiftiLoader, BigEndianFileIsSwapped) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(3, 1, 1, DT_UINT16, 16);
  s.big_endian = true;
  s.pixdim = {1.5f, 1.0f, 1.0f};
  write_nifti(dir / "be.nii", s, as_bytes(std::vector<std::uint16_t>{1, 258, 65535}));
  const Volume v = load_nifti((dir / "be.nii").string());
  EXPECT_EQ(v.data, (std::vector<std::uint16_t>{1, 258, 65535}));
  EXPECT_EQ(v.bits, 16);
  EXPECT_EQ(v.spacing.x, 1.5);
}

TEST(NiftiLoader, SignedAndWideIntegerTypes) {
  ScratchDir dir;
  {
    write_nifti(dir / "i8.nii", spec_3d(3, 1, 1, DT_INT8, 8),
                as_bytes(std::vector<std::int8_t>{-128, 0, 127}));
    const Volume v = load_nifti((dir / "i8.nii").string());
    EXPECT_EQ(v.data, (std::vector<std::uint16_t>{0, 128, 255}));
    EXPECT_EQ(v.intercept, -128.0);
    EXPECT_EQ(v.bits, 8);
  }
  {
    write_nifti(dir / "u32.nii", spec_3d(2, 1, 1, DT_UINT32, 32),
                as_bytes(std::vector<std::uint32_t>{0, 1000}));
    const Volume v = load_nifti((dir / "u32.nii").string());
    EXPECT_EQ(v.data, (std::vector<std::uint16_t>{0, 1000}));
    EXPECT_EQ(v.bits, 10);
  }
  {
    // Span 60000 fits 16 bits after the shift.
    write_nifti(dir / "i32.nii", spec_3d(3, 1, 1, DT_INT32, 32),
                as_bytes(std::vector<std::int32_t>{-40000, 0, 20000}));
    const Volume v = load_nifti((dir / "i32.nii").string());
    EXPECT_EQ(v.data, (std::vector<std::uint16_t>{0, 40000, 60000}));
    EXPECT_EQ(v.intercept, -40000.0);
    EXPECT_EQ(v.bits, 16);
  }
  {
    write_nifti(dir / "wide.nii", spec_3d(2, 1, 1, DT_INT32, 32),
                as_bytes(std::vector<std::int32_t>{0, 70000}));
    const std::string msg = error_of([&] { load_nifti((dir / "wide.nii").string()); });
    EXPECT_CONTAINS(msg, "wide.nii");
    EXPECT_CONTAINS(msg, "wider than 16 bits");
  }
}

TEST(NiftiLoader, FloatsAreQuantisedTo16BitsOverTheirRange) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(6, 2, 2, DT_FLOAT32, 32);
  s.scl_slope = 2.0f;
  s.scl_inter = 1.0f;
  std::vector<float> raw(24);
  for (std::size_t k = 0; k < raw.size(); ++k) raw[k] = -1.5f + 0.25f * static_cast<float>(k);
  write_nifti(dir / "f.nii", s, as_bytes(raw));
  const Volume v = load_nifti((dir / "f.nii").string());
  EXPECT_EQ(v.bits, 16);
  EXPECT_EQ(v.data.front(), 0);
  EXPECT_EQ(v.data.back(), 65535);
  const double step = v.slope;  // physical units per stored step
  EXPECT_NEAR(step, 2.0 * (raw.back() - raw.front()) / 65535.0, 1e-15);
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const double physical = 2.0 * raw[k] + 1.0;
    EXPECT_NEAR(v.to_physical(v.data[k]), physical, step / 2 + 1e-12) << "voxel " << k;
    if (k > 0) {
      EXPECT_GT(v.data[k], v.data[k - 1]);
    }
  }
  // The range ends are exact.
  EXPECT_NEAR(v.to_physical(0), 2.0 * raw.front() + 1.0, 1e-12);
  EXPECT_NEAR(v.to_physical(65535), 2.0 * raw.back() + 1.0, 1e-12);
}

TEST(NiftiLoader, ConstantFloatVolume) {
  ScratchDir dir;
  write_nifti(dir / "c.nii", spec_3d(2, 2, 2, DT_FLOAT64, 64),
              as_bytes(std::vector<double>(8, 3.5)));
  const Volume v = load_nifti((dir / "c.nii").string());
  EXPECT_EQ(v.data, std::vector<std::uint16_t>(8, 0));
  EXPECT_EQ(v.to_physical(0), 3.5);
  EXPECT_EQ(v.bits, 1);
}

TEST(NiftiLoader, NonFiniteVoxelIsNamed) {
  ScratchDir dir;
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<double> raw(12, 1.0);
    raw[5] = bad;
    write_nifti(dir / "nan.nii", spec_3d(3, 2, 2, DT_FLOAT64, 64), as_bytes(raw));
    const std::string msg = error_of([&] { load_nifti((dir / "nan.nii").string()); });
    EXPECT_CONTAINS(msg, "nan.nii");
    EXPECT_CONTAINS(msg, "voxel 5 (x 2, y 1, z 0)");
  }
}

TEST(NiftiLoader, PixdimRulesAndUnits) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(2, 1, 1, DT_UINT8, 8);
  s.pixdim = {0.0f, -2.0f, 0.25f};
  write_nifti(dir / "p.nii", s, {1, 2});
  const Volume v = load_nifti((dir / "p.nii").string());
  EXPECT_EQ(v.spacing.x, 1.0);  // 0 -> 1
  EXPECT_EQ(v.spacing.y, 2.0);  // |pixdim|
  EXPECT_EQ(v.spacing.z, 0.25);

  s.pixdim = {0.001f, 0.001f, 0.002f};
  s.xyzt_units = NIFTI_UNITS_METER;
  write_nifti(dir / "m.nii", s, {1, 2});
  const Volume m = load_nifti((dir / "m.nii").string());
  EXPECT_NEAR(m.spacing.x, 1.0, 1e-6);
  EXPECT_NEAR(m.spacing.z, 2.0, 1e-6);

  s.xyzt_units = NIFTI_UNITS_MM;
  s.pixdim = {1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f};
  write_nifti(dir / "n.nii", s, {1, 2});
  const std::string msg = error_of([&] { load_nifti((dir / "n.nii").string()); });
  EXPECT_CONTAINS(msg, "n.nii");
  EXPECT_CONTAINS(msg, "pixdim[2] = nan");
}

TEST(NiftiLoader, BadDimsAreRefusedBeforeReadingData) {
  ScratchDir dir;
  struct Case {
    std::array<short, 8> dim;
    std::string expected;
  };
  const Case cases[] = {
      {{3, 64, -4, 64, 1, 1, 1, 1}, "dim[2] = -4 is not a valid size"},
      {{3, 64, 64, 0, 1, 1, 1, 1}, "dim[3] = 0 is not a valid size"},
      {{3, 32767, 32767, 32767, 1, 1, 1, 1}, "more than the limit of 2^31"},
      {{2, 64, 64, 1, 1, 1, 1, 1}, "dim[0] = 2"},
      {{4, 8, 8, 8, 3, 1, 1, 1}, "dim[4] = 3"},
  };
  for (const Case& c : cases) {
    NiftiSpec s = spec_3d(1, 1, 1, DT_UINT8, 8);
    s.dim = c.dim;
    write_nifti(dir / "dims.nii", s, std::vector<unsigned char>(64, 0));  // data deliberately short
    const std::string msg = error_of([&] { load_nifti((dir / "dims.nii").string()); });
    EXPECT_CONTAINS(msg, "dims.nii");
    EXPECT_CONTAINS(msg, c.expected);
  }
  // dim[0] = 4 with dim[4] = 1 is a 3-D volume.
  NiftiSpec s = spec_3d(2, 2, 2, DT_UINT8, 8);
  s.dim = {4, 2, 2, 2, 1, 1, 1, 1};
  write_nifti(dir / "four.nii", s, std::vector<unsigned char>(8, 7));
  EXPECT_EQ(load_nifti((dir / "four.nii").string()).dims, (std::array<int, 3>{2, 2, 2}));
}

TEST(NiftiLoader, UnsupportedDatatypeIsNamed) {
  ScratchDir dir;
  for (const auto& [type, bitpix, name] :
       {std::tuple<short, short, std::string>{DT_RGB24, 24, "RGB24"},
        std::tuple<short, short, std::string>{DT_INT64, 64, "INT64"},
        std::tuple<short, short, std::string>{DT_COMPLEX64, 64, "COMPLEX64"}}) {
    write_nifti(dir / "t.nii", spec_3d(2, 1, 1, type, bitpix),
                std::vector<unsigned char>(static_cast<std::size_t>(bitpix / 4), 0));
    const std::string msg = error_of([&] { load_nifti((dir / "t.nii").string()); });
    EXPECT_CONTAINS(msg, "t.nii");
    EXPECT_CONTAINS(msg, "datatype " + std::to_string(type));
    EXPECT_CONTAINS(msg, name);
    EXPECT_CONTAINS(msg, "not supported");
  }
}

TEST(NiftiLoader, TruncatedFilesAreErrorsNamingTheFile) {
  ScratchDir dir;
  std::vector<std::uint16_t> raw(16 * 16 * 16);
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<std::uint16_t>(i);
  for (bool gz : {false, true}) {
    NiftiSpec s = spec_3d(16, 16, 16, DT_UINT16, 16);
    s.gzip = gz;
    const fs::path p = dir / (gz ? "cut.nii.gz" : "cut.nii");
    write_nifti(p, s, as_bytes(raw));
    ASSERT_NO_THROW(load_nifti(p.string()));
    const auto full = fs::file_size(p);
    for (const std::uintmax_t keep : {full / 2, std::uintmax_t{360}, std::uintmax_t{200}}) {
      if (keep >= full) continue;
      // Rewrite, then cut.
      write_nifti(p, s, as_bytes(raw));
      fs::resize_file(p, keep);
      const std::string msg = error_of([&] { load_nifti(p.string()); });
      EXPECT_CONTAINS(msg, p.filename().string());
      EXPECT_CONTAINS(msg, "not a readable NIfTI-1 file");
    }
  }
}

TEST(NiftiLoader, NotNiftiOrMissing) {
  ScratchDir dir;
  const std::string text(1000, 'x');
  write_bytes(dir / "text.nii", std::vector<unsigned char>(text.begin(), text.end()));
  write_bytes(dir / "short.nii", {1, 2, 3});
  for (const char* name : {"text.nii", "short.nii"}) {
    const std::string msg = error_of([&] { load_nifti((dir / name).string()); });
    EXPECT_CONTAINS(msg, name);
    EXPECT_CONTAINS(msg, "not a readable NIfTI-1 file");
  }
  const std::string msg = error_of([&] { load_nifti((dir / "none.nii").string()); });
  EXPECT_CONTAINS(msg, "none.nii: no such file");
}

TEST(NiftiLoader, NonFiniteScalingIsRefused) {
  ScratchDir dir;
  NiftiSpec s = spec_3d(2, 1, 1, DT_UINT8, 8);
  s.scl_slope = std::numeric_limits<float>::infinity();
  write_nifti(dir / "s.nii", s, {1, 2});
  EXPECT_CONTAINS(error_of([&] { load_nifti((dir / "s.nii").string()); }), "scl_slope = inf");
}

// --- NIfTI files written by niftilib -------------------------------------------------

#ifdef VOXCAST_TEST_HAVE_NIFTILIB
template <typename T>
void write_with_niftilib(const fs::path& p, std::array<int, 3> dims, int datatype,
                         const std::vector<T>& values, float slope, float inter,
                         std::array<float, 3> pixdim) {
  nifti_set_debug_level(0);
  int d[8] = {3, dims[0], dims[1], dims[2], 1, 1, 1, 1};
  nifti_image* nim = nifti_make_new_nim(d, datatype, 1);
  ASSERT_NE(nim, nullptr);
  ASSERT_EQ(nim->nvox, values.size());
  ASSERT_EQ(static_cast<std::size_t>(nim->nbyper), sizeof(T));
  std::memcpy(nim->data, values.data(), values.size() * sizeof(T));
  nim->dx = nim->pixdim[1] = pixdim[0];
  nim->dy = nim->pixdim[2] = pixdim[1];
  nim->dz = nim->pixdim[3] = pixdim[2];
  nim->scl_slope = slope;
  nim->scl_inter = inter;
  ASSERT_EQ(nifti_set_filenames(nim, p.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  nifti_image_free(nim);
  ASSERT_TRUE(fs::exists(p)) << p;
}
#endif

TEST(NiftiLoader, RoundTripThroughNiftilibsWriter) {
#ifndef VOXCAST_TEST_HAVE_NIFTILIB
  GTEST_SKIP() << "niftilib's headers are not on this test's include path (link voxcast_nifti)";
#else
  ScratchDir dir;
  std::vector<std::int16_t> raw(7 * 5 * 3);
  for (std::size_t i = 0; i < raw.size(); ++i)
    raw[i] = static_cast<std::int16_t>(static_cast<int>(i * 37 % 211) - 100);
  for (const char* name : {"lib.nii", "lib.nii.gz"}) {
    write_with_niftilib(dir / name, {7, 5, 3}, DT_INT16, raw, 0.5f, -1024.0f, {0.9f, 0.9f, 3.0f});
    const Volume v = load_nifti((dir / name).string());
    EXPECT_EQ(v.dims, (std::array<int, 3>{7, 5, 3})) << name;
    EXPECT_EQ(v.spacing.x, static_cast<double>(0.9f)) << name;
    EXPECT_EQ(v.spacing.z, 3.0) << name;
    const auto lo = *std::min_element(raw.begin(), raw.end());
    const auto hi = *std::max_element(raw.begin(), raw.end());
    EXPECT_EQ(v.bits, bits_for(static_cast<std::uint32_t>(hi - lo))) << name;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      ASSERT_EQ(v.data[i], raw[i] - lo) << name << " voxel " << i;
      ASSERT_EQ(v.to_physical(v.data[i]), 0.5 * raw[i] - 1024.0) << name << " voxel " << i;
    }
  }
  // ... and a cut copy of what niftilib wrote is an error, not zero-filled data.
  for (const char* name : {"lib.nii", "lib.nii.gz"}) {
    fs::resize_file(dir / name, fs::file_size(dir / name) - 20);
    const std::string msg = error_of([&] { load_nifti((dir / name).string()); });
    EXPECT_CONTAINS(msg, name);
    EXPECT_CONTAINS(msg, "truncated");
  }
#endif
}

TEST(NiftiLoader, Colin27Template) {
  const std::string path = "/usr/share/mricron/templates/ch2.nii.gz";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is not installed (Debian package mricron-data)";
  const Volume v = load_nifti(path);
  EXPECT_EQ(v.dims, (std::array<int, 3>{181, 217, 181}));
  EXPECT_EQ(v.spacing.x, 1.0);
  EXPECT_EQ(v.spacing.y, 1.0);
  EXPECT_EQ(v.spacing.z, 1.0);
  EXPECT_EQ(v.bits, 8);
  EXPECT_EQ(v.slope, 1.0);
  EXPECT_EQ(v.intercept, 0.0);
}

// --- raw ---------------------------------------------------------------------------------

TEST(RawLoader, U8) {
  ScratchDir dir;
  std::vector<unsigned char> bytes(12);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i);
  write_bytes(dir / "v.raw", bytes);
  RawSpec spec;
  spec.dims = {3, 2, 2};
  spec.type = RawType::U8;
  spec.spacing = {0.5, 0.5, 1.25};
  const Volume v = load_raw((dir / "v.raw").string(), spec);
  EXPECT_EQ(v.dims, spec.dims);
  EXPECT_EQ(v.spacing.z, 1.25);
  EXPECT_EQ(v.bits, 4);
  EXPECT_EQ(v.data, std::vector<std::uint16_t>(bytes.begin(), bytes.end()));
  EXPECT_EQ(v.at(2, 1, 1), 11);
}

TEST(RawLoader, U16BothByteOrders) {
  ScratchDir dir;
  write_bytes(dir / "le.raw", {0x02, 0x01, 0x00, 0xFF, 0x07, 0x00});
  write_bytes(dir / "be.raw", {0x01, 0x02, 0xFF, 0x00, 0x00, 0x07});
  RawSpec spec;
  spec.dims = {3, 1, 1};
  spec.type = RawType::U16;
  const std::vector<std::uint16_t> expected{0x0102, 0xFF00, 7};
  EXPECT_EQ(load_raw((dir / "le.raw").string(), spec).data, expected);
  spec.big_endian = true;
  const Volume v = load_raw((dir / "be.raw").string(), spec);
  EXPECT_EQ(v.data, expected);
  EXPECT_EQ(v.bits, 16);
}

TEST(RawLoader, I16ShiftedToUnsigned) {
  ScratchDir dir;
  write_bytes(dir / "s.raw", as_bytes(std::vector<std::int16_t>{-1000, 0, 3000, -1}));
  RawSpec spec;
  spec.dims = {2, 2, 1};
  spec.type = RawType::I16;
  const Volume v = load_raw((dir / "s.raw").string(), spec);
  EXPECT_EQ(v.data, (std::vector<std::uint16_t>{0, 1000, 4000, 999}));
  EXPECT_EQ(v.intercept, -1000.0);
  EXPECT_EQ(v.slope, 1.0);
  EXPECT_EQ(v.bits, 12);
  EXPECT_EQ(v.to_physical(v.data[3]), -1.0);

  // Non-negative signed data keep their values.
  write_bytes(dir / "p.raw", as_bytes(std::vector<std::int16_t>{5, 10, 0, 1}));
  const Volume p = load_raw((dir / "p.raw").string(), spec);
  EXPECT_EQ(p.data, (std::vector<std::uint16_t>{5, 10, 0, 1}));
  EXPECT_EQ(p.intercept, 0.0);
}

TEST(RawLoader, SizeMustMatchDimsExactly) {
  ScratchDir dir;
  RawSpec spec;
  spec.dims = {4, 3, 2};
  spec.type = RawType::U16;
  write_bytes(dir / "short.raw", std::vector<unsigned char>(40, 0));
  write_bytes(dir / "long.raw", std::vector<unsigned char>(50, 0));
  const std::string shorter = (dir / "short.raw").string();
  EXPECT_EQ(error_of([&] { load_raw(shorter, spec); }),
            shorter + ": holds 40 bytes, dims 4x3x2 of u16 need 48");
  const std::string longer = (dir / "long.raw").string();
  EXPECT_EQ(error_of([&] { load_raw(longer, spec); }),
            longer + ": holds 50 bytes, dims 4x3x2 of u16 need 48");
  write_bytes(dir / "ok.raw", std::vector<unsigned char>(48, 0));
  EXPECT_NO_THROW(load_raw((dir / "ok.raw").string(), spec));
}

TEST(RawLoader, BadSpecOrMissingFile) {
  ScratchDir dir;
  write_bytes(dir / "v.raw", std::vector<unsigned char>(8, 0));
  RawSpec spec;
  spec.dims = {2, 0, 2};
  EXPECT_CONTAINS(error_of([&] { load_raw((dir / "v.raw").string(), spec); }),
                  "volume.dims y = 0 is not a valid size");
  spec.dims = {2, 2, 2};
  EXPECT_CONTAINS(error_of([&] { load_raw((dir / "none.raw").string(), spec); }),
                  "none.raw: no such file");
  spec.spacing = {1.0, -1.0, 1.0};
  EXPECT_CONTAINS(error_of([&] { load_raw((dir / "v.raw").string(), spec); }), "spacing along y");
}

// --- load_volume -----------------------------------------------------------------------------

TEST(LoadVolume, PhantomSources) {
  const Volume v = load_volume("phantom:box?size=8", "/nonexistent", nullptr);
  EXPECT_EQ(v.dims, (std::array<int, 3>{8, 8, 8}));
  EXPECT_EQ(v.source, "phantom:box?size=8");
  EXPECT_EQ(load_volume("phantom:shells", ".", nullptr).dims, (std::array<int, 3>{128, 128, 128}));

  struct Case {
    std::string source, expected;
  };
  for (const Case& c : {Case{"phantom:box?size=abc", "size \"abc\" is not a whole number"},
                        Case{"phantom:box?size=", "size \"\" is not a whole number"},
                        Case{"phantom:box?size=8x", "size \"8x\""},
                        Case{"phantom:box?size=-3", "size -3 is outside 2..1024"},
                        Case{"phantom:box?size=4096", "size 4096 is outside 2..1024"},
                        Case{"phantom:box?zoom=2", "unknown phantom parameter \"zoom=2\""},
                        Case{"phantom:cube?size=8", "phantom 'cube' is unknown"},
                        Case{"phantom:", "no phantom name"}}) {
    const std::string msg = error_of([&] { load_volume(c.source, ".", nullptr); });
    EXPECT_CONTAINS(msg, c.expected);
  }
}

TEST(LoadVolume, PathsResolveAgainstTheBaseDir) {
  ScratchDir dir;
  write_bytes(dir / "vol.raw", std::vector<unsigned char>(8, 3));
  RawSpec spec;
  spec.dims = {2, 2, 2};
  const std::string base = dir.path().string();
  EXPECT_EQ(load_volume("vol.raw", base, &spec).data, std::vector<std::uint16_t>(8, 3));
  EXPECT_EQ(load_volume((dir / "vol.raw").string(), "/elsewhere", &spec).voxel_count(), 8u);

  const std::string msg = error_of([&] { load_volume("vol.raw", base, nullptr); });
  EXPECT_CONTAINS(msg, (dir / "vol.raw").string());
  EXPECT_CONTAINS(msg,
                  "is not a NIfTI file or DICOM folder; give volume.dims and volume.type to "
                  "read it as raw");

  write_nifti(dir / "head.nii", spec_3d(2, 2, 2, DT_UINT8, 8), std::vector<unsigned char>(8, 9));
  EXPECT_EQ(load_volume("head.nii", base, &spec).data, std::vector<std::uint16_t>(8, 9));

  const std::string missing = error_of([&] { load_volume("missing.nii", base, nullptr); });
  EXPECT_CONTAINS(missing, (dir / "missing.nii").string());
  EXPECT_CONTAINS(missing, "no such file or folder");
  EXPECT_CONTAINS(error_of([&] { load_volume("", base, nullptr); }), "volume.source is empty");
}

TEST(LoadVolume, FolderWithoutSlices) {
  ScratchDir dir;
  fs::create_directories(dir / "empty");
  EXPECT_CONTAINS(error_of([&] { load_volume("empty", dir.path().string(), nullptr); }),
                  "no DICOM image slices found");
  write_bytes(dir / "empty" / "README.txt", {'h', 'i'});
  const std::string msg = error_of([&] { load_volume("empty", dir.path().string(), nullptr); });
  EXPECT_CONTAINS(msg, "no DICOM image slices found");
  EXPECT_CONTAINS(msg, "README.txt");
}

// --- DICOM ------------------------------------------------------------------------------------

const fs::path kCtFolder = fs::path(VOXCAST_SHARED_DIR) / "data/dicom/ct-skull-phantom-philips-5mm";

// prefix + n. (Not `"I" + std::to_string(n)`: GCC 12 at -O3 reports a false
// -Wrestrict on it.)
std::string numbered(const std::string& prefix, std::size_t n) {
  std::string s = prefix;
  s += std::to_string(n);
  return s;
}

// The series' slice files I10, I20, ..., I280 (k = 1..28).
std::vector<fs::path> ct_slices() {
  std::vector<fs::path> out;
  for (int k = 1; k <= 28; ++k) out.push_back(kCtFolder / numbered("I", 10 * k));
  return out;
}

#define SKIP_WITHOUT_CT_DATA()                                        \
  if (!fs::is_directory(kCtFolder) || !fs::exists(kCtFolder / "I10")) \
  GTEST_SKIP() << kCtFolder << " is absent"

TEST(DicomLoader, CtSkullPhantomSeries) {
  SKIP_WITHOUT_CT_DATA();
  const Volume v = load_dicom_series(kCtFolder.string());
  // 28 axial slices of 512x512, PixelSpacing 0.451171875, slice positions 5 mm apart.
  EXPECT_EQ(v.dims, (std::array<int, 3>{512, 512, 28}));
  EXPECT_EQ(v.spacing.x, 0.451171875);
  EXPECT_EQ(v.spacing.y, 0.451171875);
  EXPECT_NEAR(v.spacing.z, 5.0, 1e-9);
  EXPECT_EQ(v.slope, 1.0);
  EXPECT_EQ(v.intercept, -1024.0);
  EXPECT_EQ(v.bits, 11);  // stored 0..1806
  const auto [lo, hi] = std::minmax_element(v.data.begin(), v.data.end());
  EXPECT_EQ(v.to_physical(*lo), -1024.0);
  EXPECT_EQ(v.to_physical(*hi), 782.0);
  // Mostly air (about -1000 HU) around the phantom, and bone above +300 HU.
  std::size_t air = 0, bone = 0;
  for (std::uint16_t w : v.data) {
    const double hu = v.to_physical(w);
    air += hu <= -950.0;
    bone += hu >= 300.0;
  }
  EXPECT_GT(air, v.voxel_count() / 2);
  EXPECT_GT(bone, 100000u);
  EXPECT_EQ(v.source, kCtFolder.string());
}

TEST(DicomLoader, SliceOrderComesFromPositionsNotNames) {
  SKIP_WITHOUT_CT_DATA();
  ScratchDir dir;
  const auto slices = ct_slices();
  // Reverse the name order: I10 (the lowest slice) becomes z99, I280 becomes z72.
  for (std::size_t k = 0; k < slices.size(); ++k)
    fs::copy_file(slices[k], dir / numbered("z", 99 - k));
  fs::copy_file(kCtFolder / "README.md", dir / "README.md");
  const Volume shuffled = load_dicom_series(dir.path().string());
  const Volume original = load_dicom_series(kCtFolder.string());
  EXPECT_EQ(shuffled.dims, original.dims);
  EXPECT_EQ(shuffled.spacing, original.spacing);
  EXPECT_TRUE(shuffled.data == original.data);
}

// Voxels of `got` that break the rule for one missing slice: every plane is
// `whole`'s plane, bit for bit, except plane `gap`, the mean of its two
// neighbours in `whole`, rounded half up.
std::size_t off_the_gap_rule(const Volume& got, const Volume& whole, std::size_t gap) {
  const std::size_t per_slice = static_cast<std::size_t>(whole.dims[0]) * whole.dims[1];
  std::size_t differ = 0;
  for (std::size_t z = 0; z < static_cast<std::size_t>(whole.dims[2]); ++z)
    for (std::size_t k = 0; k < per_slice; ++k) {
      const std::size_t at = z * per_slice + k;
      const unsigned want = z == gap
                                ? (whole.data[at - per_slice] + whole.data[at + per_slice] + 1u) / 2u
                                : whole.data[at];
      differ += got.data[at] != want;
    }
  return differ;
}

TEST(DicomLoader, DuplicateMissingAndForeignSlices) {
  SKIP_WITHOUT_CT_DATA();
  const auto slices = ct_slices();
  {
    ScratchDir dir;
    for (const fs::path& s : slices) fs::copy_file(s, dir / s.filename());
    fs::copy_file(kCtFolder / "I100", dir / "I100-copy");
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, "duplicate slice");
    EXPECT_CONTAINS(msg, "I100");
  }
  {
    ScratchDir dir;
    for (const fs::path& s : slices)
      if (s.filename() != "I150") fs::copy_file(s, dir / s.filename());
    const std::string msg =
        error_of([&] { load_dicom_series(dir.path().string(), {.resample = false}); });
    EXPECT_CONTAINS(msg, "the gap between I140 and I160 is 10 mm");
    EXPECT_CONTAINS(msg, "unevenly spaced");
    // Resampled by default (rule 7): the whole series' grid; the planes with a
    // slice are that slice, I150's plane the mean of I140 and I160 rounded half up.
    std::ostringstream notices;
    const Volume v = load_dicom_series(dir.path().string(), {.notices = &notices});
    EXPECT_EQ(notices.str(), "voxcast: " + dir.path().string() +
                                 ": 1 uneven gap resampled onto 512x512x28 at 0.4512x0.4512x5 mm "
                                 "(linear)\n");
    const Volume whole = load_dicom_series(kCtFolder.string());
    ASSERT_EQ(v.dims, whole.dims);
    EXPECT_NEAR(v.spacing.z, whole.spacing.z, 1e-9);
    EXPECT_EQ(v.intercept, whole.intercept);
    EXPECT_EQ(off_the_gap_rule(v, whole, 14), 0u);
  }
  {
    // A second series: one copy whose SeriesInstanceUID (0020,000E) differs in
    // its last digit (explicit VR little endian: tag, "UI", 16-bit length).
    ScratchDir dir;
    for (const fs::path& s : slices) fs::copy_file(s, dir / s.filename());
    std::ifstream in(kCtFolder / "I280", std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
    const unsigned char tag[] = {0x20, 0x00, 0x0E, 0x00, 'U', 'I'};
    const auto at = std::search(bytes.begin(), bytes.end(), std::begin(tag), std::end(tag));
    ASSERT_NE(at, bytes.end());
    const std::size_t len = static_cast<std::size_t>(at[6] | (at[7] << 8));
    auto last = at + 8 + static_cast<std::ptrdiff_t>(len) - 1;
    while (*last == 0 || *last == ' ') --last;
    *last = *last == '9' ? '8' : static_cast<unsigned char>(*last + 1);
    write_bytes(dir / "I290", bytes);
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, "holds 2 series");
    EXPECT_CONTAINS(msg, "(28 files)");
    EXPECT_CONTAINS(msg, "(1 file)");
  }
  {
    ScratchDir dir;
    for (const fs::path& s : slices) fs::copy_file(s, dir / s.filename());
    fs::resize_file(dir / "I200", 2000);
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, "I200");
  }
}

// The CT series loads exactly as its files hold it (rule 5: regular, so nothing
// is resampled and nothing is said): voxel z*512*512 + k is the low 12 bits
// (BitsStored) of pixel word k of the z-th file in position order.
TEST(DicomLoader, CtSkullPhantomIsNotResampled) {
  SKIP_WITHOUT_CT_DATA();
  std::ostringstream notices;
  const Volume v = load_dicom_series(kCtFolder.string(), {.notices = &notices});
  EXPECT_EQ(notices.str(), "");
  ASSERT_EQ(v.dims, (std::array<int, 3>{512, 512, 28}));
  const std::size_t per_slice = 512 * 512;
  const auto slices = ct_slices();
  for (std::size_t z = 0; z < slices.size(); ++z) {
    std::ifstream in(slices[z], std::ios::binary);
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
    // (7FE0,0010) OW, explicit VR little endian: tag, VR, 2 reserved, 32-bit length.
    const unsigned char tag[] = {0xE0, 0x7F, 0x10, 0x00, 'O', 'W'};
    const auto at = std::find_end(bytes.begin(), bytes.end(), std::begin(tag), std::end(tag));
    ASSERT_NE(at, bytes.end()) << slices[z];
    const auto data = at + 12;
    ASSERT_EQ(bytes.end() - data, static_cast<std::ptrdiff_t>(2 * per_slice)) << slices[z];
    std::size_t differ = 0;
    for (std::size_t k = 0; k < per_slice; ++k) {
      const unsigned word = static_cast<unsigned>(data[static_cast<std::ptrdiff_t>(2 * k)]) |
                            static_cast<unsigned>(data[static_cast<std::ptrdiff_t>(2 * k + 1)])
                                << 8;
      differ += v.data[z * per_slice + k] != (word & 0x0FFFu);
    }
    EXPECT_EQ(differ, 0u) << slices[z];
  }
}

// --- DICOM: gantry tilt and uneven slices (docs/volumes.md, rule 7) ----------------------

// A series of square slices: the image plane turned by `tilt_deg` about the
// row (x) axis, positions `step` mm apart along `table`.
struct SynthSeries {
  int size = 64;       // columns = rows
  double pixel = 1.0;  // mm
  std::array<double, 6> orientation{};
  std::vector<std::array<double, 3>> positions;
  std::array<double, 3> row() const { return {orientation[0], orientation[1], orientation[2]}; }
  std::array<double, 3> column() const { return {orientation[3], orientation[4], orientation[5]}; }
  std::array<double, 3> normal() const {
    const auto r = row(), c = column();
    return {r[1] * c[2] - r[2] * c[1], r[2] * c[0] - r[0] * c[2], r[0] * c[1] - r[1] * c[0]};
  }
};

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

SynthSeries synth_series(double tilt_deg, std::array<double, 3> table, double step, int count,
                         int size) {
  const double t = tilt_deg * std::acos(-1.0) / 180.0;
  SynthSeries s;
  s.size = size;
  s.orientation = {1.0, 0.0, 0.0, 0.0, std::cos(t), std::sin(t)};
  const double len = std::sqrt(dot(table, table));
  const double half = (size - 1) / 2.0;
  for (int k = 0; k < count; ++k)
    s.positions.push_back({-half + k * step * table[0] / len, -half + k * step * table[1] / len,
                           k * step * table[2] / len});
  return s;
}

struct Ball {
  std::array<double, 3> centre{};  // patient mm
  double radius = 0.0;
};

// Slice k's pixel (i, j) at position + i * pixel * row + j * pixel * column:
// +1000 inside the ball, -1000 outside, a linear edge one pixel wide.
void write_series(const fs::path& dir, const SynthSeries& s, const Ball& ball) {
  const auto r = s.row(), c = s.column();
  for (std::size_t k = 0; k < s.positions.size(); ++k) {
    test::DicomSlice slice;
    slice.columns = slice.rows = s.size;
    slice.position = s.positions[k];
    slice.orientation = s.orientation;
    slice.pixel_spacing = {s.pixel, s.pixel};
    slice.instance = static_cast<int>(k) + 1;
    for (int j = 0; j < s.size; ++j)
      for (int i = 0; i < s.size; ++i) {
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double x = s.positions[k][static_cast<std::size_t>(a)] +
                           i * s.pixel * r[static_cast<std::size_t>(a)] +
                           j * s.pixel * c[static_cast<std::size_t>(a)];
          d2 += (x - ball.centre[static_cast<std::size_t>(a)]) *
                (x - ball.centre[static_cast<std::size_t>(a)]);
        }
        const double inside = std::clamp(ball.radius - std::sqrt(d2) + 0.5, 0.0, 1.0);
        slice.pixels.push_back(static_cast<std::int16_t>(std::lround(-1000.0 + 2000.0 * inside)));
      }
    write_bytes(dir / numbered("IM", 100 + k), test::dicom_slice_bytes(slice));
  }
}

// The ball's centre (voxel indices) and radius along each axis (mm), from the
// moments of the weight (value - min) / (max - min): a uniform ball's variance
// along any axis is radius^2 / 5. `shear` is the correlation of y with z and
// of x with z: 0 for a ball, tan/sqrt(1 + tan^2) of the tilt if left sheared.
struct BallFit {
  std::array<double, 3> centre{}, radius{};
  double shear = 0.0;
};

BallFit fit_ball(const Volume& v) {
  const auto [lo, hi] = std::minmax_element(v.data.begin(), v.data.end());
  double w_sum = 0.0;
  std::array<double, 3> m1{}, m2{};
  double yz = 0.0, xz = 0.0;
  std::size_t n = 0;
  for (int z = 0; z < v.dims[2]; ++z)
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x) {
        const double w = static_cast<double>(v.data[n++] - *lo) / (*hi - *lo);
        const std::array<double, 3> p{static_cast<double>(x), static_cast<double>(y),
                                      static_cast<double>(z)};
        w_sum += w;
        for (std::size_t a = 0; a < 3; ++a) {
          m1[a] += w * p[a];
          m2[a] += w * p[a] * p[a];
        }
        yz += w * p[1] * p[2];
        xz += w * p[0] * p[2];
      }
  BallFit f;
  std::array<double, 3> var{};
  const std::array<double, 3> spacing{v.spacing.x, v.spacing.y, v.spacing.z};
  for (std::size_t a = 0; a < 3; ++a) {
    f.centre[a] = m1[a] / w_sum;
    var[a] = m2[a] / w_sum - f.centre[a] * f.centre[a];
    f.radius[a] = std::sqrt(5.0 * var[a]) * spacing[a];
  }
  const double cyz = yz / w_sum - f.centre[1] * f.centre[2];
  const double cxz = xz / w_sum - f.centre[0] * f.centre[2];
  f.shear = std::max(std::abs(cyz) / std::sqrt(var[1] * var[2]),
                     std::abs(cxz) / std::sqrt(var[0] * var[2]));
  return f;
}

// Where the ball's centre must be on the resampled grid (rule 7): z from the
// first slice along the normal in steps of the median gap, in-plane the grid
// of the stack's middle (half way between the first and last slices' origins).
std::array<double, 3> expected_centre(const SynthSeries& s, const Ball& ball, double spacing_z) {
  const auto r = s.row(), c = s.column(), nrm = s.normal();
  const auto& first = s.positions.front();
  const auto& last = s.positions.back();
  const double u0 = (dot(first, r) + dot(last, r)) / 2, v0 = (dot(first, c) + dot(last, c)) / 2;
  return {(dot(ball.centre, r) - u0) / s.pixel, (dot(ball.centre, c) - v0) / s.pixel,
          (dot(ball.centre, nrm) - dot(first, nrm)) / spacing_z};
}

void expect_round_ball(const Volume& v, const SynthSeries& s, const Ball& ball) {
  const BallFit f = fit_ball(v);
  const auto truth = expected_centre(s, ball, v.spacing.z);
  const std::array<double, 3> spacing{v.spacing.x, v.spacing.y, v.spacing.z};
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_NEAR(f.centre[a], truth[a], 1.0) << "centre, axis " << a;
    EXPECT_NEAR(f.radius[a], ball.radius, spacing[a]) << "radius, axis " << a;
  }
  EXPECT_LT(f.shear, 0.05);
}

struct TiltCase {
  const char* name;
  double tilt_deg;
  std::array<double, 3> table;  // the slice positions' direction
  int slices;
};

std::ostream& operator<<(std::ostream& os, const TiltCase& c) {
  return os << c.name << ": plane tilted " << c.tilt_deg << " deg, table (" << c.table[0] << ", "
            << c.table[1] << ", " << c.table[2] << "), " << c.slices << " slices";
}

class DicomTilt : public testing::TestWithParam<TiltCase> {};

TEST_P(DicomTilt, BallStaysRound) {
  const TiltCase& c = GetParam();
  const SynthSeries s = synth_series(c.tilt_deg, c.table, 2.5, c.slices, 64);
  const Ball ball{{0.3, -2.0, 35.0}, 12.0};
  ScratchDir dir;
  write_series(dir.path(), s, ball);
  std::ostringstream notices;
  const Volume v = load_dicom_series(dir.path().string(), {.notices = &notices});
  // The median gap along the normal: the step's component along it.
  const auto nrm = s.normal();
  const double gap = 2.5 * dot(c.table, nrm) / std::sqrt(dot(c.table, c.table));
  EXPECT_EQ(v.dims, (std::array<int, 3>{64, 64, c.slices}));
  EXPECT_EQ(v.spacing.x, 1.0);
  EXPECT_EQ(v.spacing.y, 1.0);
  EXPECT_NEAR(v.spacing.z, gap, 1e-6);
  expect_round_ball(v, s, ball);
  // The tilt between the positions' line and the normal, as the notice gives it.
  const double tilt =
      std::acos(dot(c.table, nrm) / std::sqrt(dot(c.table, c.table))) * 180.0 / std::acos(-1.0);
  char line[256];
  std::snprintf(line, sizeof line,
                "voxcast: %s: gantry tilt %.1f deg resampled onto 64x64x%d at 1x1x%.4g mm "
                "(linear)\n",
                dir.path().string().c_str(), tilt, c.slices, gap);
  EXPECT_EQ(notices.str(), line);
}

INSTANTIATE_TEST_SUITE_P(DicomLoader, DicomTilt,
                         testing::Values(TiltCase{"tilt20", 20.0, {0.0, 0.0, 1.0}, 40},
                                         TiltCase{
                                             "plane12_table_oblique", 12.0, {0.2, 0.0, 1.0}, 36}),
                         [](const testing::TestParamInfo<TiltCase>& i) { return i.param.name; });

// Both at once: a tilted series with one slice missing keeps its slice count.
TEST(DicomLoader, TiltAndMissingSliceTogether) {
  const SynthSeries s = synth_series(20.0, {0.0, 0.0, 1.0}, 2.5, 40, 64);
  const Ball ball{{0.3, -2.0, 35.0}, 12.0};
  ScratchDir dir;
  write_series(dir.path(), s, ball);
  fs::remove(dir / "IM110");  // inside the ball
  std::ostringstream notices;
  const Volume v = load_dicom_series(dir.path().string(), {.notices = &notices});
  EXPECT_EQ(v.dims, (std::array<int, 3>{64, 64, 40}));
  expect_round_ball(v, s, ball);
  EXPECT_EQ(notices.str(), "voxcast: " + dir.path().string() +
                               ": gantry tilt 20.0 deg and 1 uneven gap resampled onto 64x64x40 "
                               "at 1x1x2.349 mm (linear)\n");
}

// Without the gantry correction the same series is refused as before.
TEST(DicomLoader, TiltRefusedWithoutResampling) {
  const SynthSeries s = synth_series(20.0, {0.0, 0.0, 1.0}, 2.5, 8, 16);
  ScratchDir dir;
  write_series(dir.path(), s, Ball{{0.0, 0.0, 8.0}, 4.0});
  const std::string msg =
      error_of([&] { load_dicom_series(dir.path().string(), {.resample = false}); });
  EXPECT_CONTAINS(msg, dir.path().string() + ": IM101 is offset ");
  EXPECT_CONTAINS(msg,
                  "mm sideways from the slice normal through IM100 (gantry tilt or sheared "
                  "series: not supported)");
  // The option reaches the loader through load_volume (the scene's volume.resample).
  EXPECT_EQ(error_of([&] { load_volume(dir.path().string(), "", nullptr, {.resample = false}); }),
            msg);
}

// One slice missing from an even axial series: the grid keeps the series'
// spacing and slice count; the planes that have a slice are that slice, bit
// for bit, and the missing one is the mean of its neighbours, rounded half up.
TEST(DicomLoader, MissingSliceIsInterpolated) {
  const SynthSeries s = synth_series(0.0, {0.0, 0.0, 1.0}, 2.0, 30, 48);
  const Ball ball{{0.4, -0.3, 25.0}, 10.0};
  ScratchDir full, gap;
  write_series(full.path(), s, ball);
  write_series(gap.path(), s, ball);
  fs::remove(gap / "IM112");
  std::ostringstream notices;
  const Volume a = load_dicom_series(full.path().string(), {.notices = &notices});
  EXPECT_EQ(notices.str(), "");  // regular: loaded as stored
  const Volume b = load_dicom_series(gap.path().string(), {.notices = &notices});
  EXPECT_EQ(notices.str(), "voxcast: " + gap.path().string() +
                               ": 1 uneven gap resampled onto 48x48x30 at 1x1x2 mm (linear)\n");
  ASSERT_EQ(b.dims, a.dims);
  EXPECT_EQ(b.spacing, a.spacing);
  EXPECT_EQ(b.slope, a.slope);
  EXPECT_EQ(b.intercept, a.intercept);
  EXPECT_EQ(b.bits, a.bits);
  EXPECT_EQ(off_the_gap_rule(b, a, 12), 0u);
  expect_round_ball(b, s, ball);
  // Refused as before without resampling.
  const std::string msg =
      error_of([&] { load_dicom_series(gap.path().string(), {.resample = false}); });
  EXPECT_CONTAINS(msg, gap.path().string() +
                           ": the gap between IM111 and IM113 is 4 mm, the "
                           "series' median is 2 mm (slices unevenly spaced");
}

// Degenerate series: one error naming the folder and the reason.
TEST(DicomLoader, DegenerateTiltedSeriesAreRefused) {
  {
    ScratchDir dir;
    write_series(dir.path(), synth_series(50.0, {0.0, 0.0, 1.0}, 2.5, 6, 16), Ball{});
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, dir.path().string() +
                             ": the slice positions lean 50.0 deg from "
                             "ImageOrientationPatient's normal (IM100 to IM105)");
    EXPECT_CONTAINS(msg, "more than 45 deg");
  }
  {
    // Slices stepping sideways back and forth: not one tilt.
    SynthSeries s = synth_series(0.0, {0.0, 0.0, 1.0}, 2.5, 5, 16);
    s.positions[1][0] += 3.0;
    ScratchDir dir;
    write_series(dir.path(), s, Ball{});
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, dir.path().string() +
                             ": IM101 is offset 3.0 pixels sideways from the "
                             "line of slice positions through IM100 and IM104");
  }
  {
    // Two slices at one position of a tilted series.
    SynthSeries s = synth_series(15.0, {0.0, 0.0, 1.0}, 2.5, 5, 16);
    s.positions[3] = s.positions[2];
    ScratchDir dir;
    write_series(dir.path(), s, Ball{});
    const std::string msg = error_of([&] { load_dicom_series(dir.path().string()); });
    EXPECT_CONTAINS(msg, dir.path().string() + ": IM102 and IM103 are both at slice position");
    EXPECT_CONTAINS(msg, "(duplicate slice)");
  }
}

TEST(DicomLoader, FolderThroughLoadVolume) {
  SKIP_WITHOUT_CT_DATA();
  const Volume v =
      load_volume("ct-skull-phantom-philips-5mm", kCtFolder.parent_path().string(), nullptr);
  EXPECT_EQ(v.dims, (std::array<int, 3>{512, 512, 28}));
}

}  // namespace
}  // namespace voxcast::ref
