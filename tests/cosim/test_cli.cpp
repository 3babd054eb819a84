// The `voxcast` command as users and scripts run it: exit codes, one-line
// errors, and the files it writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "cosim/reports/image_io.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::test::Command;

Command run(const std::string& args) { return voxcast::test::run_voxcast(args); }

std::filesystem::path temp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("voxcast_cli_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::string scene(const char* name) { return std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name; }

TEST(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "render", "demo"}) {
    const Command r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, RenderWritesPngAndExrWithTheRequestedSize) {
  const auto d = temp_dir("render");
  const Command r = run("render " + scene("mip.toml") + " -o " + (d / "m.png").string() + " -o " +
                    (d / "m.exr").string() + " --set render.width=40 --set render.height=30");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("wrote    " + (d / "m.png").string()), std::string::npos);
  const voxcast::ref::Image exr = voxcast::cosim::read_image((d / "m.exr").string());
  EXPECT_EQ(exr.width, 40);
  EXPECT_EQ(exr.height, 30);
  const voxcast::ref::Image png = voxcast::cosim::read_image((d / "m.png").string());
  EXPECT_EQ(png.width, 40);
  // The two formats carry the same image: PNG is the EXR over a black
  // background, rounded to 8 bits.
  for (std::size_t i = 0; i < exr.pixels.size(); ++i)
    EXPECT_NEAR(png.pixels[i].r, exr.pixels[i].r, 0.5 / 255 + 1e-6);
}

TEST(Cli, StereoWritesTwoEyes) {
  const auto d = temp_dir("stereo");
  const Command r = run("render " + scene("mip.toml") + " -o " + (d / "s.png").string() +
                    " --set camera.stereo_deg=4 --set render.width=16 --set render.height=16");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(d / "s_left.png"));
  EXPECT_TRUE(std::filesystem::exists(d / "s_right.png"));
}

// The cycle model's VCD trace is one frame's: a stereo pair writes one per eye,
// named like the images; one view writes exactly the path given.
TEST(Cli, VcdTraceIsWrittenForEveryView) {
  const auto d = temp_dir("vcd");
  auto text = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string small = " --engine rtl --set render.width=12 --set render.height=12";
  Command r = run("render " + scene("mip.toml") + " -o " + (d / "s.png").string() + " --vcd " +
                  (d / "t.vcd").string() + " --set camera.stereo_deg=4" + small);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(d / "t.vcd"));
  for (const char* eye : {"t_left.vcd", "t_right.vcd"}) {
    const std::string vcd = text(d / eye);
    EXPECT_NE(vcd.find("$enddefinitions $end"), std::string::npos) << eye;
    // The frame's cycles follow the header, from cycle 0.
    EXPECT_NE(vcd.find("$enddefinitions $end\n#0\n"), std::string::npos) << eye;
    std::size_t stamps = 0;
    for (std::size_t at = vcd.find("\n#"); at != std::string::npos; at = vcd.find("\n#", at + 1))
      ++stamps;
    EXPECT_GT(stamps, 100u) << eye;
    EXPECT_NE(r.output.find("wrote    " + (d / eye).string()), std::string::npos) << r.output;
  }
  // The eyes see the volume from different angles: different command streams.
  EXPECT_NE(text(d / "t_left.vcd"), text(d / "t_right.vcd"));
  r = run("render " + scene("mip.toml") + " -o " + (d / "m.png").string() + " --vcd " +
          (d / "m.vcd").string() + small);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(text(d / "m.vcd").find("$enddefinitions $end"), std::string::npos);
}

TEST(Cli, ErrorsAreOneLineAndNonZero) {
  const auto d = temp_dir("errors");
  const std::string out = " -o " + (d / "x.png").string();
  struct Case {
    std::string args, expected;
  } cases[] = {
      {"render /nonexistent.toml" + out, "voxcast: /nonexistent.toml: cannot open scene file\n"},
      {"render " + scene("mip.toml") + out + " --set render.oversampling=32",
       "voxcast: --set render.oversampling=32: render.oversampling = 32 is outside [0.25, 16]\n"},
      {"render " + scene("mip.toml") + out + " --set volume.source=phantom:nope",
       "voxcast: phantom 'nope' is unknown"},
      {"render " + scene("mip.toml") + " -o " + (d / "x.bmp").string(),
       "unsupported image type \".bmp\" (use .exr or .png)\n"},
      {"render " + scene("mip.toml") + out + " --set volume.crop.lo=[0,0,0] --set volume.crop.hi=[0,0,200]",
       "volume.crop.hi[2] = 200 is outside the volume"},
  };
  for (const Case& c : cases) {
    const Command r = run(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "not one line: " << r.output;
  }
}

}  // namespace

namespace VOXCAST_UNITY_ID {

TEST(Cli, EveryFixedPointEngineWritesTheSameImage) {
  const auto d = temp_dir("engines");
  for (const char* engine : {"bittrue", "hls", "rtl"}) {
    const Command r = run("render " + scene("mip.toml") + " --engine " + engine + " -o " +
                          (d / (std::string(engine) + ".exr")).string() +
                          " --set render.width=24 --set render.height=20");
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    if (std::string(engine) == "rtl") {
      EXPECT_NE(r.output.find("cycles at 100 MHz"), std::string::npos);
    }
  }
  const auto bt = voxcast::cosim::read_image((d / "bittrue.exr").string());
  for (const char* engine : {"hls", "rtl"}) {
    const auto img = voxcast::cosim::read_image((d / (std::string(engine) + ".exr")).string());
    ASSERT_EQ(img.pixels.size(), bt.pixels.size());
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      ASSERT_EQ(img.pixels[i], bt.pixels[i]) << engine;
    }
  }
}

TEST(Cli, CosimReportHasTheDocumentedKeys) {
  const auto d = temp_dir("cosim");
  const Command r = run("cosim " + std::string(VOXCAST_SOURCE_DIR) +
                        "/tests/regress/grazing_faces.toml --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(d / "report.json");
  std::stringstream text;
  text << in.rdbuf();
  for (const char* key : {"\"bit_exact\": true", "\"engines\"", "\"psnr_db\"", "\"max_abs_err_lsb\"",
                          "\"rms_err_lsb\"", "\"pct_within_1lsb\"", "\"profile\"", "\"cycles\"",
                          "\"fps\"", "\"ns_per_sample\"", "\"samples\"", "\"row_hit_rate\"",
                          "\"stalls\""})
    EXPECT_NE(text.str().find(key), std::string::npos) << key;
  for (const char* f : {"layers.exr", "float.png", "hls.png", "bittrue.png", "diff.png"})
    EXPECT_TRUE(std::filesystem::exists(d / f)) << f;
}

}  // namespace
