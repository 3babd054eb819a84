// JUnit XML (issue 22): what CI servers read. The document parses, its counts
// match the cases, a failing case names what broke, and hostile text (markup,
// bytes that are not UTF-8, control characters) arrives escaped, never as
// markup or a malformed file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <pugixml.hpp>

#include "cosim/reports/junit.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using voxcast::cosim::JUnitCase;
using voxcast::cosim::JUnitSuite;

pugi::xml_document parse(const std::string& xml) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_string(xml.c_str());
  EXPECT_TRUE(ok) << ok.description() << "\n" << xml;
  return doc;
}

TEST(JUnit, CountsAndOutcomes) {
  JUnitSuite s{"voxcast regress", {}};
  s.cases.push_back({"regress.a", "balanced", 1.25});
  JUnitCase failed{"regress.a", "precise", 2.0};
  failed.outcome = JUnitCase::Outcome::Failed;
  failed.type = "MISMATCH";
  failed.message = "hls differs from bit-true at pixel (3, 4)";
  s.cases.push_back(failed);
  JUnitCase skipped{"cosim.a", "rtl == hls", 0.0};
  skipped.outcome = JUnitCase::Outcome::Skipped;
  skipped.message = "not run";
  s.cases.push_back(skipped);

  const auto doc = parse(voxcast::cosim::junit_xml(s));
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(suite.attribute("tests").as_int(), 3);
  EXPECT_EQ(suite.attribute("failures").as_int(), 1);
  EXPECT_EQ(suite.attribute("skipped").as_int(), 1);
  EXPECT_EQ(std::string(suite.attribute("time").value()), "3.250");
  const pugi::xml_node f = suite.find_child_by_attribute("testcase", "name", "precise");
  EXPECT_EQ(std::string(f.child("failure").attribute("type").value()), "MISMATCH");
  EXPECT_EQ(std::string(f.child("failure").attribute("message").value()), failed.message);
  EXPECT_TRUE(suite.find_child_by_attribute("testcase", "name", "rtl == hls").child("skipped"));
}

TEST(JUnit, HostileTextIsEscapedNotMarkup) {
  const std::string hostile = "</testcase><script>\"&'\xff\x01 ok";
  JUnitCase c{"regress." + hostile, hostile, 0.0};
  c.outcome = JUnitCase::Outcome::Failed;
  c.message = hostile;
  c.details = hostile;
  const auto doc = parse(voxcast::cosim::junit_xml({hostile, {c}}));
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(std::distance(suite.children().begin(), suite.children().end()), 1);
  const std::string safe = "</testcase><script>\"&'\xEF\xBF\xBD\xEF\xBF\xBD ok";
  EXPECT_EQ(voxcast::cosim::xml_safe_text(hostile), safe);
  const pugi::xml_node tc = suite.child("testcase");
  EXPECT_EQ(std::string(tc.attribute("name").value()), safe);
  EXPECT_EQ(std::string(tc.child("failure").attribute("message").value()), safe);
  EXPECT_EQ(std::string(tc.child("failure").text().get()), safe);
  // Well-formed UTF-8 passes through; overlong forms and surrogates do not.
  EXPECT_EQ(voxcast::cosim::xml_safe_text("K\xC3\xB6ln \xE2\x82\xAC"), "K\xC3\xB6ln \xE2\x82\xAC");
  EXPECT_EQ(voxcast::cosim::xml_safe_text("\xC0\xAF"), "\xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(voxcast::cosim::xml_safe_text("\xED\xA0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");
}

// regress --junit: one case per scene x preset, the counts of the text table,
// and a changed golden named in its failure.
TEST(JUnit, RegressCasesMatchTheTable) {
  const fs::path d = fs::temp_directory_path() / "voxcast_junit_regress";
  fs::remove_all(d);
  fs::create_directories(d / "scenes");
  fs::create_directories(d / "golden");
  fs::copy_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml", d / "scenes" / "mip.toml");
  const std::string base = "regress --scenes " + (d / "scenes").string() + " --golden " +
                           (d / "golden").string() +
                           " --profiles balanced,precise --set render.width=12 --set render.height=12";
  ASSERT_EQ(voxcast::test::run_voxcast(base + " --bless").status, 0);
  // Break one golden: its hash no longer matches.
  {
    std::ifstream in(d / "golden" / "mip.precise.json");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("\"hash\": \"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at + 9, 16, "0000000000000000");
    std::ofstream(d / "golden" / "mip.precise.json") << text;
  }
  const auto r = voxcast::test::run_voxcast(base + " --junit " + (d / "out" / "r.xml").string());
  EXPECT_EQ(r.status, 4) << r.output;
  EXPECT_NE(r.output.find("1 passed, 1 failed"), std::string::npos) << r.output;

  std::ifstream in(d / "out" / "r.xml");
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto doc = parse(xml);
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(suite.attribute("tests").as_int(), 2);
  EXPECT_EQ(suite.attribute("failures").as_int(), 1);
  const pugi::xml_node bad = suite.find_child_by_attribute("testcase", "name", "precise");
  EXPECT_EQ(std::string(bad.attribute("classname").value()), "regress.mip");
  EXPECT_EQ(std::string(bad.child("failure").attribute("type").value()), "CHANGED");
  EXPECT_NE(std::string(bad.child("failure").attribute("message").value()).find("mip.precise.json"),
            std::string::npos);
  EXPECT_FALSE(suite.find_child_by_attribute("testcase", "name", "balanced").child("failure"));
}

}  // namespace VOXCAST_UNITY_ID
