// `voxcast paper vizard2` at a tiny size: the report's structure, and the
// physics it reports (the sampling error of a binary wall falls as the
// sampling rate rises).
#include <gtest/gtest.h>

#include <regex>

#include "cli.hpp"

namespace VOXCAST_UNITY_ID {

using namespace sweep_test;
namespace fs = std::filesystem;

TEST(PaperVizard2, TinyRunWritesTheReportAndErrorFallsWithOversampling) {
  const auto d = temp_dir("paper");
  const Command r = run("paper vizard2 --size 24 --volume-size 32 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string md = text_of(d / "report.md");
  for (const char* section : {"# VIZARD II's oversampling experiment, reproduced", "## Setup",
                              "## Error against the truth and modelled speed", "## Images",
                              "## The paper's finding, checked"})
    EXPECT_NE(md.find(section), std::string::npos) << section;
  // One table row per cell: 2 transfer functions x 4 rates.
  const std::regex row(R"(\n\| (binary|ramp) \| (1|2|4|8)x \| )");
  EXPECT_EQ(std::distance(std::sregex_iterator(md.begin(), md.end(), row), std::sregex_iterator()),
            8);
  // Every image the report shows exists.
  const std::regex image(R"(\]\(([a-z_0-9]+\.png)\))");
  int images = 0;
  for (auto it = std::sregex_iterator(md.begin(), md.end(), image); it != std::sregex_iterator();
       ++it, ++images)
    EXPECT_TRUE(fs::exists(d / (*it)[1].str())) << (*it)[1].str();
  EXPECT_EQ(images, 2 * (4 + 1) + 2 * 4);  // cells and truths, error maps

  const nlohmann::json j = json_of(d / "results.json");
  ASSERT_EQ(j.at("cells").size(), 8u);
  std::vector<double> rms, card;
  for (const auto& c : j.at("cells"))
    if (c.at("tf") == "binary") {
      rms.push_back(c.at("float_vs_truth").at("rms_err_lsb").get<double>());
      card.push_back(c.at("card_vs_truth").at("rms_err_lsb").get<double>());
      EXPECT_GT(c.at("rtl").at("fps").get<double>(), 0.0);
    }
  ASSERT_EQ(rms.size(), 4u);
  // Sampling error of the binary wall: strictly smaller at every doubling.
  for (std::size_t k = 1; k < rms.size(); ++k) EXPECT_LT(rms[k], rms[k - 1]) << k;
  // The card (sampling + fixed point) also gains from 1x to 8x.
  EXPECT_LT(card.back(), card.front());
  EXPECT_TRUE(j.at("finding_holds").is_boolean());
  EXPECT_NE(md.find(j.at("finding_holds").get<bool>() ? "0.25-voxel sampling distance: holds"
                                                      : "0.25-voxel sampling distance: does not"),
            std::string::npos);
}

TEST(PaperVizard2, UnknownExperimentIsAOneLineError) {
  const Command r = run("paper virim --out " + temp_dir("paper_bad").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "voxcast: paper: unknown experiment \"virim\" (vizard2)\n");
}

}  // namespace
