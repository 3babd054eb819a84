// Bad input through the command line, as a user meets it: broken NIfTI and raw files
// and broken scene files. Every case must end with a non-zero exit code and exactly
// one line on stderr that names the file and the field at fault — never a crash, a
// hang, or a render of wrong data. (The loaders' and the scene parser's own tests,
// tests/refmodel/test_loaders.cpp and test_scene.cpp, cover the library functions;
// tests/cosim/test_cli.cpp the CLI's basics.)
#include <gtest/gtest.h>
#include <nifti/nifti1.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "extremes.hpp"
#include "tests/common/dicom_bytes.hpp"
#include "tests/common/nifti_bytes.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

// --- Writing broken files -------------------------------------------------------------

// An 8x8x8 uint8 NIfTI-1 (tests/common/nifti_bytes.hpp), to be broken field by field.
struct Nifti : NiftiSpec {
  Nifti() { dim = {3, 8, 8, 8, 1, 1, 1, 1}; }
};

// 512 voxels 0, 1, ..., 255, 0, 1, ...: a shifted read shows.
std::vector<unsigned char> ramp_voxels() {
  std::vector<unsigned char> d(512);
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = static_cast<unsigned char>(i);
  return d;
}

void write_bytes(const fs::path& p, const std::vector<unsigned char>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

void write_gzip(const fs::path& p, const std::vector<unsigned char>& bytes) {
  gzFile gz = gzopen(p.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size())),
            static_cast<int>(bytes.size()));
  ASSERT_EQ(gzclose(gz), Z_OK);
}

// A scene file next to the volume, rendered small.
fs::path scene_for(const fs::path& dir, const std::string& volume_table,
                   const std::string& name = "scene.toml") {
  const fs::path p = dir / name;
  write_text(p, "[volume]\n" + volume_table +
                    "\n[classification]\npoints = [ { value = 0, alpha = 0.5 } ]\n"
                    "[camera]\neye = [3.5, -20, 3.5]\ncenter = [3.5, 3.5, 3.5]\n"
                    "[render]\nwidth = 4\nheight = 4\n");
  return p;
}

// `voxcast render SCENE ARGS` must fail with exit code 1 and one line on stderr starting
// with `start` (the file, and the field) and containing `field`; it writes nothing to
// stdout and no image. The cases of one test run concurrently (distinct files).
struct ErrorCase {
  fs::path scene;
  std::string start, field, args;
};

void expect_one_line_errors(const std::vector<ErrorCase>& cases) {
  std::vector<std::string> args;
  for (std::size_t i = 0; i < cases.size(); ++i)
    args.push_back(
        "render " + cases[i].scene.string() + " -o " +
        (cases[i].scene.parent_path() / ("never" + std::to_string(i) + ".png")).string() + " " +
        cases[i].args);
  const std::vector<Command> runs = voxcast_all(args);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Command& c = runs[i];
    const ErrorCase& e = cases[i];
    EXPECT_EQ(c.signal, 0) << "crashed: " << c.err;
    EXPECT_EQ(c.status, 1) << args[i] << "\n" << c.err;
    EXPECT_EQ(c.out, "") << args[i];
    if (c.err.empty()) {
      ADD_FAILURE() << args[i] << ": nothing on stderr";
      continue;
    }
    EXPECT_EQ(c.err.find('\n'), c.err.size() - 1) << "not one line: " << c.err;
    EXPECT_EQ(c.err.rfind(e.start, 0), 0u) << "stderr: " << c.err << "expected start: " << e.start;
    EXPECT_NE(c.err.find(e.field), std::string::npos)
        << "stderr: " << c.err << "expected field: " << e.field;
    EXPECT_FALSE(fs::exists(e.scene.parent_path() / ("never" + std::to_string(i) + ".png")));
  }
}

// --- NIfTI ----------------------------------------------------------------------------

TEST(Extremes, CliTruncatedNifti) {
  const fs::path dir = scratch_dir();
  const std::vector<unsigned char> whole = nifti_bytes(Nifti{}, ramp_voxels());
  struct Case {
    std::string name;
    std::size_t keep;
    bool gz;
    std::string why;
  };
  std::vector<ErrorCase> cases;
  for (const Case& c :
       {Case{"header.nii", 200, false, "truncated or corrupt header"},
        Case{"data.nii", 400, false, "truncated or corrupt data: 48 of 512 data bytes"},
        Case{"empty.nii", 0, false, "truncated or corrupt header"},
        Case{"data.nii.gz", 600, true, "truncated or corrupt data: 248 of 512 data bytes"}}) {
    const std::vector<unsigned char> cut(whole.begin(),
                                         whole.begin() + static_cast<std::ptrdiff_t>(c.keep));
    if (c.gz) {
      write_gzip(dir / c.name, cut);
    } else {
      write_bytes(dir / c.name, cut);
    }
    cases.push_back({scene_for(dir, "source = \"" + c.name + "\"", c.name + ".toml"),
                     "voxcast: " + (dir / c.name).string() + ": not a readable NIfTI-1 file (",
                     c.why, ""});
  }
  expect_one_line_errors(cases);
}

TEST(Extremes, CliNiftiAbsurdDims) {
  const fs::path dir = scratch_dir();
  struct Case {
    std::array<short, 8> dim;
    std::string field;
  };
  std::vector<ErrorCase> cases;
  int k = 0;
  for (const Case& c :
       {Case{{3, 32767, 32767, 32767, 1, 1, 1, 1},
             "dim 32767x32767x32767 = 35181150961663 voxels, more than the limit of 2^31"},
        Case{{9, 8, 8, 8, 1, 1, 1, 1}, "dim[0] = 9 is not a 3-D volume"},
        Case{{4, 8, 8, 8, 3, 1, 1, 1}, "dim[4] = 3"}}) {
    Nifti s;
    s.dim = c.dim;
    const std::string name = "huge" + std::to_string(k++) + ".nii";
    write_bytes(dir / name, nifti_bytes(s, ramp_voxels()));
    cases.push_back({scene_for(dir, "source = \"" + name + "\"", name + ".toml"),
                     "voxcast: " + (dir / name).string() + ": ", c.field, ""});
  }
  expect_one_line_errors(cases);
}

TEST(Extremes, CliNiftiNegativeSize) {
  const fs::path dir = scratch_dir();
  const std::pair<int, short> sizes[] = {
      {1, short{-4}}, {2, short{0}}, {3, std::numeric_limits<short>::min()}};
  std::vector<ErrorCase> cases;
  for (const auto& [axis, bad] : sizes) {
    Nifti s;
    s.dim[static_cast<std::size_t>(axis)] = bad;
    const std::string name = "neg" + std::to_string(axis) + ".nii";
    write_bytes(dir / name, nifti_bytes(s, ramp_voxels()));
    cases.push_back(
        {scene_for(dir, "source = \"" + name + "\"", name + ".toml"),
         "voxcast: " + (dir / name).string() + ": ",
         "dim[" + std::to_string(axis) + "] = " + std::to_string(bad) + " is not a valid size",
         ""});
  }
  expect_one_line_errors(cases);
}

TEST(Extremes, CliNiftiNonFinite) {
  const fs::path dir = scratch_dir();
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  Nifti slope;
  slope.scl_slope = nan;
  write_bytes(dir / "slope.nii", nifti_bytes(slope, ramp_voxels()));
  Nifti pixdim;
  pixdim.pixdim = {1.0f, inf, 1.0f};
  write_bytes(dir / "pixdim.nii", nifti_bytes(pixdim, ramp_voxels()));
  // A float volume with one NaN voxel.
  Nifti f;
  f.dim = {3, 2, 2, 2, 1, 1, 1, 1};
  f.datatype = DT_FLOAT32;
  f.bitpix = 32;
  std::vector<float> voxels(8, 1.5f);
  voxels[5] = nan;
  std::vector<unsigned char> data(sizeof(float) * voxels.size());
  std::memcpy(data.data(), voxels.data(), data.size());
  write_bytes(dir / "voxel.nii", nifti_bytes(f, data));
  const auto at = [&](const std::string& name) {
    return "voxcast: " + (dir / name).string() + ": ";
  };
  expect_one_line_errors(
      {{scene_for(dir, "source = \"slope.nii\"", "a.toml"), at("slope.nii"), "scl_slope = nan", ""},
       {scene_for(dir, "source = \"pixdim.nii\"", "b.toml"), at("pixdim.nii"), "pixdim[2] = inf",
        ""},
       {scene_for(dir, "source = \"voxel.nii\"", "c.toml"), at("voxel.nii"),
        "voxel 5 (x 1, y 0, z 1)", ""}});
}

TEST(Extremes, CliNiftiBadVoxOffset) {
  // Fixed: CliNiftiBadVoxOffset was a bug found by this suite (docs/extremes.md).
  const fs::path dir = scratch_dir();
  std::vector<ErrorCase> cases;
  int k = 0;
  for (float off : {-1000.0f, 100.0f, std::numeric_limits<float>::quiet_NaN(), 1e30f}) {
    Nifti s;
    s.vox_offset = off;
    const std::string name = "offset" + std::to_string(k++) + ".nii";
    write_bytes(dir / name, nifti_bytes(s, ramp_voxels()));
    cases.push_back({scene_for(dir, "source = \"" + name + "\"", name + ".toml"),
                     "voxcast: " + (dir / name).string() + ": ", "vox_offset", ""});
  }
  expect_one_line_errors(cases);
}

// --- raw --------------------------------------------------------------------------------

TEST(Extremes, CliRawShorterThanDims) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "short.raw", std::vector<unsigned char>(40, 7));
  write_bytes(dir / "empty.raw", std::vector<unsigned char>(0));
  expect_one_line_errors(
      {{scene_for(dir, "source = \"short.raw\"\ndims = [4, 3, 2]\ntype = \"u16\"", "a.toml"),
        "voxcast: " + (dir / "short.raw").string() + ": ",
        "holds 40 bytes, dims 4x3x2 of u16 need 48", ""},
       {scene_for(dir, "source = \"empty.raw\"\ndims = [1, 1, 1]\ntype = \"u8\"", "b.toml"),
        "voxcast: " + (dir / "empty.raw").string() + ": ", "holds 0 bytes, dims 1x1x1 of u8 need 1",
        ""}});
}

TEST(Extremes, CliRawAbsurdDims) {
  const fs::path dir = scratch_dir();
  write_bytes(dir / "v.raw", std::vector<unsigned char>(64, 7));
  const fs::path scene = scene_for(dir, "source = \"v.raw\"\ndims = [4, 4, 4]\ntype = \"u8\"");
  write_text(dir / "big.toml",
             "[volume]\nsource = \"v.raw\"\ntype = \"u8\"\ndims = [4, 4, 70000]\n"
             "[classification]\npoints = [ { value = 0, alpha = 0.5 } ]\n"
             "[camera]\neye = [3.5, -20, 3.5]\ncenter = [3.5, 3.5, 3.5]\n");
  expect_one_line_errors(
      {{scene, "voxcast: " + (dir / "v.raw").string() + ": ",
        "volume.dims 65535x65535x65535 hold 281462092005375 voxels, more than the limit of 2^31",
        "--set 'volume.dims=[65535,65535,65535]'"},
       {scene, "voxcast: --set volume.dims=[4,-3,2]: ", "volume.dims[1] = -3 is outside [1, 65535]",
        "--set 'volume.dims=[4,-3,2]'"},
       {scene, "voxcast: --set volume.dims=[0,4,4]: ", "volume.dims[0] = 0 is outside [1, 65535]",
        "--set 'volume.dims=[0,4,4]'"},
       {dir / "big.toml", "voxcast: " + (dir / "big.toml").string() + ":",
        "volume.dims[2] = 70000 is outside [1, 65535]", ""}});
}

// --- Scene files ----------------------------------------------------------------------------

// A minimal valid scene with `render_body` as its [render] table (line 9) and `extra`
// appended (from line 10).
fs::path scene_with(const fs::path& dir, const std::string& render_body,
                    const std::string& extra = "", const std::string& name = "s.toml") {
  const fs::path p = dir / name;
  write_text(p,
             "[volume]\nsource = \"phantom:box?size=8\"\n"
             "[classification]\npoints = [ { value = 0, alpha = 0.5 } ]\n"
             "[camera]\neye = [3.5, -20, 3.5]\ncenter = [3.5, 3.5, 3.5]\n"
             "[render]\n" +
                 render_body + "\n" + extra);
  return p;
}

TEST(Extremes, CliTomlWrongType) {
  const fs::path dir = scratch_dir();
  std::vector<ErrorCase> cases;
  int k = 0;
  for (const auto& [body, message] :
       {std::pair<std::string, std::string>{"width = \"wide\"",
                                            "render.width must be an integer, not string"},
        {"height = 3.5", "render.height must be an integer, not floating-point"},
        {"background = [0, 0]", "render.background must be an array of 3 numbers"}}) {
    const fs::path p = scene_with(dir, body, "", "t" + std::to_string(k++) + ".toml");
    cases.push_back({p, "voxcast: " + p.string() + ":9: " + message, message, ""});
  }
  const fs::path crop = scene_with(dir, "width = 4", "[volume.crop]\nlo = \"all\"\n", "crop.toml");
  cases.push_back({crop, "voxcast: " + crop.string() + ":",
                   "volume.crop.lo must be an array of 3 integers", ""});
  const fs::path ok = scene_with(dir, "width = 4", "", "ok.toml");
  cases.push_back({ok, "voxcast: --set camera.eye=\"here\": ",
                   "camera.eye must be an array of 3 numbers", "--set 'camera.eye=\"here\"'"});
  cases.push_back({ok, "voxcast: --set classification.points=3: ",
                   "classification.points must be an array of tables",
                   "--set classification.points=3"});
  expect_one_line_errors(cases);
}

TEST(Extremes, CliTomlNanAndInf) {
  const fs::path dir = scratch_dir();
  const fs::path a = scene_with(dir, "oversampling = nan", "", "a.toml");
  const fs::path b = scene_with(dir, "ert_threshold = -inf", "", "b.toml");
  // An array element names the file and the element, but not the line
  // (Extremes.CliTomlArrayElementErrorsNameTheLine).
  const fs::path c = scene_with(dir, "background = [0, nan, 0]", "", "c.toml");
  const fs::path d = scene_with(dir, "width = 1e400", "", "d.toml");  // overflows
  const fs::path point = dir / "p.toml";
  write_text(point,
             "[volume]\nsource = \"phantom:box?size=8\"\n[classification]\n"
             "points = [ { value = nan, alpha = 0.5 } ]\n[camera]\neye = [3.5, -20, 3.5]\n"
             "center = [3.5, 3.5, 3.5]\n");
  const fs::path eye = dir / "e.toml";
  write_text(eye,
             "[volume]\nsource = \"phantom:box?size=8\"\n[classification]\n"
             "points = [ { value = 0, alpha = 0.5 } ]\n[camera]\neye = [3.5, -inf, 3.5]\n"
             "center = [3.5, 3.5, 3.5]\n");
  const fs::path ok = scene_with(dir, "width = 4", "", "ok.toml");
  const auto at = [](const fs::path& p, const std::string& line) {
    return "voxcast: " + p.string() + line;
  };
  expect_one_line_errors(
      {{a, at(a, ":9: "), "render.oversampling = nan is not a finite number", ""},
       {b, at(b, ":9: "), "render.ert_threshold = -inf is not a finite number", ""},
       {c, at(c, ":"), "render.background[1] = nan is not a finite number", ""},
       {d, at(d, ":9: "), "1e400", ""},
       {point, at(point, ":4: "), "classification.points[0].value = nan is not a finite number",
        ""},
       {eye, at(eye, ":"), "camera.eye[1] = -inf is not a finite number", ""},
       {ok, "voxcast: --set lights[0].intensity=nan: ",
        "lights[0].intensity = nan is not a finite number", "--set 'lights[0].intensity=nan'"}});
}

TEST(Extremes, CliTomlArrayElementErrorsNameTheLine) {
  // Fixed: CliTomlArrayElementErrorsNameTheLine was a bug found by this suite (docs/extremes.md).
  const fs::path dir = scratch_dir();
  const fs::path b = scene_with(dir, "background = [0, nan, 0]");
  expect_one_line_errors({{b, "voxcast: " + b.string() + ":9: ",
                           "render.background[1] = nan is not a finite number", ""}});
}

TEST(Extremes, CliTomlUnknownKey) {
  const fs::path dir = scratch_dir();
  const fs::path p = scene_with(dir, "oversmapling = 2", "", "p.toml");
  const fs::path q = scene_with(dir, "width = 4", "[camra]\nfov = 3\n", "q.toml");
  const fs::path r = dir / "c.toml";
  write_text(r,
             "[volume]\nsource = \"phantom:box?size=8\"\n[classification]\n"
             "points = [ { value = 0, alpha = 0.5, colour = [1, 0, 0] } ]\n[camera]\n"
             "eye = [3.5, -20, 3.5]\ncenter = [3.5, 3.5, 3.5]\n");
  const fs::path ok = scene_with(dir, "width = 4", "", "ok.toml");
  const fs::path t = scene_with(dir, "width = 4", "[precision]\nprofile = \"vizard3\"\n", "t.toml");
  expect_one_line_errors(
      {{p, "voxcast: " + p.string() + ":9: ",
        "unknown key render.oversmapling (did you mean render.oversampling?)", ""},
       {q, "voxcast: " + q.string() + ":10: ", "unknown key camra (did you mean camera?)", ""},
       {r, "voxcast: " + r.string() + ":4: ",
        "unknown key classification.points[0].colour (did you mean "
        "classification.points[0].color?)",
        ""},
       {ok, "voxcast: --set precision.alpha_bitz=3: ",
        "unknown key precision.alpha_bitz (did you mean precision.alpha_bits?)",
        "--engine bittrue --set precision.alpha_bitz=3"},
       {t, "voxcast: " + t.string() + ":", "precision.profile = \"vizard3\" is not one of",
        "--engine hls"}});
}

// --- DICOM ----------------------------------------------------------------------------

// A gantry-tilted series (8x8 slices, the plane turned 20 degrees about x, positions
// 2.5 mm apart along z): resampled with one notice on stderr (docs/volumes.md, rule
// 7), or refused as before with volume.resample = false.
TEST(Extremes, CliTiltedDicomSeries) {
  const fs::path dir = scratch_dir();
  const fs::path series = dir / "tilted";
  fs::create_directories(series);
  const double tilt = 20.0 * std::acos(-1.0) / 180.0;
  for (int k = 0; k < 6; ++k) {
    DicomSlice slice;
    slice.columns = slice.rows = 8;
    slice.position = {-3.5, -3.5, 2.5 * k};
    slice.orientation = {1.0, 0.0, 0.0, 0.0, std::cos(tilt), std::sin(tilt)};
    slice.instance = k + 1;
    for (int p = 0; p < 64; ++p) slice.pixels.push_back(static_cast<std::int16_t>(10 * k + p));
    write_bytes(series / ("IM" + std::to_string(k)), dicom_slice_bytes(slice));
  }
  const Command on = voxcast("render " + scene_for(dir, "source = \"tilted\"", "on.toml").string() +
                             " -o " + (dir / "on.png").string());
  EXPECT_EQ(on.status, 0) << on.err;
  const std::string notice =
      "voxcast: " + series.string() +
      ": gantry tilt 20.0 deg resampled onto 8x8x6 at 1x1x2.349 mm (linear)\n";
  EXPECT_NE(on.err.find(notice), std::string::npos) << on.err;
  EXPECT_EQ(on.err.find(notice), on.err.rfind(notice)) << "said more than once: " << on.err;
  expect_one_line_errors({{scene_for(dir, "source = \"tilted\"\nresample = false", "off.toml"),
                           "voxcast: " + series.string() + ": IM1 is offset ",
                           "(gantry tilt or sheared series: not supported)", ""}});
}

}  // namespace
}  // namespace voxcast::test
