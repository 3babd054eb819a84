// The image module (cosim/reports/image_io_module.hpp): OpenImageIO is loaded
// when the first image is written, not when voxcast starts; and when the
// module cannot be loaded, writing an image is an error naming what was tried,
// after which nothing is half-written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using voxcast::test::Command;
using voxcast::test::run_voxcast;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("voxcast_image_io_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const std::string kSmallMip = std::string(VOXCAST_SOURCE_DIR) +
                              "/scenes/mip.toml --set render.width=24 --set render.height=16";

// The dynamic loader's own account (LD_DEBUG=files) of every library it maps.
TEST(ImageModule, OpenImageIOIsLoadedByTheFirstImageNotAtStart) {
  const Command help = run_voxcast("--help", "env LD_DEBUG=files");
  ASSERT_EQ(help.status, 0) << help.output;
  EXPECT_EQ(help.output.find("libOpenImageIO"), std::string::npos)
      << "voxcast maps OpenImageIO before it writes an image";

  const fs::path d = fresh_dir("lazy");
  const Command render =
      run_voxcast("render " + kSmallMip + " -o " + (d / "m.png").string(), "env LD_DEBUG=files");
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_TRUE(fs::is_regular_file(d / "m.png"));
  // Mapped as the module's dependency, by the dlopen of the first image.
  EXPECT_NE(render.output.find("libvoxcast_image_io.so"), std::string::npos);
  EXPECT_NE(render.output.find("libOpenImageIO"), std::string::npos);
}

TEST(ImageModule, AMissingModuleIsAnErrorNamingThePathTried) {
  const fs::path d = fresh_dir("missing");
  const std::string bogus = (d / "no_such_module.so").string();
  const Command r = run_voxcast("render " + kSmallMip + " -o " + (d / "m.png").string(),
                                "env VOXCAST_IMAGE_IO_MODULE=" + bogus);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("image module"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(bogus), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "m.png"));
}

// A library that loads but is not the module (zlib, which every build links).
TEST(ImageModule, ALibraryThatIsNotTheModuleIsRefused) {
  const fs::path d = fresh_dir("other");
  std::string zlib;
  for (const char* p : {"/lib/x86_64-linux-gnu/libz.so.1", "/usr/lib/x86_64-linux-gnu/libz.so.1",
                        "/lib64/libz.so.1", "/usr/lib/libz.so.1"})
    if (fs::exists(p)) zlib = p;
  if (zlib.empty()) GTEST_SKIP() << "no libz.so.1 at the usual paths";
  const Command r = run_voxcast("render " + kSmallMip + " -o " + (d / "m.exr").string(),
                                "env VOXCAST_IMAGE_IO_MODULE=" + zlib);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(zlib + ": not voxcast's image module"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "m.exr"));
}

}  // namespace VOXCAST_UNITY_ID
