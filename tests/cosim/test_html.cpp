// The report pages (issue 22): cosim --html and sweep --html write one
// self-contained page; hostile names arrive escaped; headless Chromium
// (Debian's chromium) loads the cosim page without console errors, every image
// at its pixel size, and renders it to a PNG of the window's size.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>


#include "cosim/reports/html.hpp"
#include "cosim/reports/image_io.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
namespace html = voxcast::cosim::html;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Html, EscapesMarkupAndBytesThatAreNotUtf8) {
  EXPECT_EQ(html::escape("<img src=x onerror=\"a('&')\">"),
            "&lt;img src=x onerror=&quot;a(&#39;&amp;&#39;)&quot;&gt;");
  EXPECT_EQ(html::escape("a\xff" "b\x01"), "a\xEF\xBF\xBD" "b\xEF\xBF\xBD");
  EXPECT_EQ(html::file_url("hls.png"), "./hls.png");
  EXPECT_EQ(html::file_url("a b\"#?.png"), "./a%20b%22%23%3F.png");
  // A table's cells are text, never markup.
  const std::string t = html::table({"<th>"}, {{"</td><script>x</script>"}});
  EXPECT_EQ(t.find("<script>"), std::string::npos) << t;
  EXPECT_NE(t.find("&lt;/td&gt;&lt;script&gt;"), std::string::npos) << t;
}

TEST(Html, ScatterLabelsEveryPointAndJoinsTheFront) {
  const std::string svg = html::scatter("t", "x", "y",
                                        {{1, 40, "profile=vizard2", false},
                                         {2, 50, "profile=balanced", true},
                                         {3, 45, "profile=<precise>", true}});
  EXPECT_NE(svg.find(">profile=vizard2</text>"), std::string::npos);
  EXPECT_NE(svg.find(">profile=balanced</text>"), std::string::npos);
  EXPECT_NE(svg.find(">profile=&lt;precise&gt;</text>"), std::string::npos);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  std::size_t circles = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1))
    ++circles;
  EXPECT_EQ(circles, 3u);
}

// A scene whose file name is hostile: the page shows it as text.
fs::path hostile_scene(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path p = dir / "a<script>alert(1)&\"x\".toml";
  fs::copy_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml", p,
                fs::copy_options::overwrite_existing);
  return p;
}

std::string cosim_html(const fs::path& d) {
  const fs::path scene = hostile_scene(d);
  const auto r = voxcast::test::run_voxcast(
      "cosim '" + scene.string() + "' --set render.width=20 --set render.height=20 "
      "--truth-oversampling 2 --html --out " + (d / "out").string());
  EXPECT_EQ(r.status, 0) << r.output;
  return slurp(d / "out" / "cosim.html");
}

TEST(Html, CosimPageHasEverySectionAndNoInjectedMarkup) {
  const fs::path d = fs::temp_directory_path() / "voxcast_html_cosim";
  fs::remove_all(d);
  const std::string page = cosim_html(d);
  for (const char* s : {"<h2>Verdict</h2>", "<h2>Images</h2>", "<h2>Accuracy</h2>",
                        "<h2>Cycle model</h2>", "<h2>Resources", "./float.png", "./hls.png",
                        "./bittrue.png", "./diff.png", "./truth.png", "bit-exact",
                        "Stall cycles by cause", "error against the truth"})
    EXPECT_NE(page.find(s), std::string::npos) << s;
  EXPECT_EQ(page.find("<script>alert"), std::string::npos);
  EXPECT_NE(page.find("a&lt;script&gt;alert(1)&amp;&quot;x&quot;.toml"), std::string::npos);
}

TEST(Html, SweepPageLabelsEveryPoint) {
  const fs::path d = fs::temp_directory_path() / "voxcast_html_sweep";
  fs::remove_all(d);
  const auto r = voxcast::test::run_voxcast(
      "sweep " + std::string(VOXCAST_SOURCE_DIR) +
      "/scenes/default.toml --set render.width=12 --set render.height=12 --truth-oversampling 2 "
      "--vary precision.profile=vizard2,balanced --no-plots --html --out " + (d / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string page = slurp(d / "out" / "sweep.html");
  for (const char* label : {">profile=vizard2</text>", ">profile=balanced</text>"})
    EXPECT_NE(page.find(label), std::string::npos) << label;
  EXPECT_NE(page.find("<h2>Points</h2>"), std::string::npos);
}

// Headless Chromium, as a reader opens the page: no console error, every
// image loaded at the scene's pixel size, a screenshot of the window's size.
TEST(Html, ChromiumRendersTheCosimPage) {
  const char* chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium)) GTEST_SKIP() << "Debian's chromium is not installed";
  const fs::path d = fs::temp_directory_path() / "voxcast_html_chromium";
  fs::remove_all(d);
  cosim_html(d);
  const std::string url = "file://" + (d / "out" / "cosim.html").string();
  const std::string flags =
      std::string(chromium) + " --headless --no-sandbox --disable-gpu --disable-quic "
      "--no-first-run --disable-background-networking --disable-component-update --disable-sync "
      "--user-data-dir=" + (d / "profile").string() + " --enable-logging=stderr --v=0 ";

  const auto dom = voxcast::test::run_command(flags + "--virtual-time-budget=5000 --dump-dom '" +
                                              url + "'");
  ASSERT_EQ(dom.status, 0) << dom.output;
  std::size_t images = 0;
  const std::regex loaded("data-loaded=\"(\\d+)x(\\d+)\"");
  for (auto it = std::sregex_iterator(dom.output.begin(), dom.output.end(), loaded);
       it != std::sregex_iterator(); ++it) {
    ++images;
    EXPECT_EQ((*it)[1], "20") << "an image did not load at its width";
    EXPECT_EQ((*it)[2], "20") << "an image did not load at its height";
  }
  EXPECT_EQ(images, 5u) << dom.output;
  // Console messages at error level, and scripts that threw.
  EXPECT_EQ(dom.output.find(":ERROR:CONSOLE"), std::string::npos) << dom.output;
  EXPECT_EQ(dom.output.find("Uncaught"), std::string::npos) << dom.output;

  const fs::path shot = d / "cosim.png";
  const auto png = voxcast::test::run_command(flags + "--window-size=1200,1800 --screenshot=" +
                                              shot.string() + " '" + url + "'");
  ASSERT_EQ(png.status, 0) << png.output;
  ASSERT_TRUE(fs::is_regular_file(shot)) << "no screenshot at " << shot;
  const voxcast::cosim::ImageFileInfo info = voxcast::cosim::read_image_info(shot.string());
  EXPECT_EQ(info.width, 1200);
  EXPECT_EQ(info.height, 1800);
}

}  // namespace VOXCAST_UNITY_ID
