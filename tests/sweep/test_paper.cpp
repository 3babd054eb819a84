// `voxcast paper vizard2` at a tiny size: the report's structure, and the
// physics it reports (the sampling error of a binary wall falls as the
// sampling rate rises); `voxcast paper engel2001`'s error budget on a tiny
// scene.
#include <gtest/gtest.h>

#include <map>
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
  EXPECT_EQ(r.output, "voxcast: paper: unknown experiment \"virim\" (vizard2, engel2001)\n");
}

// `voxcast paper engel2001` on the sweep tests' tiny tube: every row of the
// error budget in the report and the JSON, post-classification's sampling
// error falling with the rate, and the verdicts the numbers decide.
TEST(PaperEngel2001, TinyRunWritesTheErrorBudgetAndItsVerdicts) {
  const auto d = temp_dir("paper_engel");
  const Command r =
      run("paper engel2001 " + tiny_scene() + " --truth-oversampling 8 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = json_of(d / "results.json");
  ASSERT_EQ(j.at("rows").size(), 9u);
  std::map<std::string, double> rms, psnr;
  for (const auto& w : j.at("rows")) {
    const std::string name = w.at("name");
    rms[name] = w.at("float_vs_truth").at("rms_err_lsb").get<double>();
    psnr[name] = w.at("float_vs_truth").at("psnr_db").get<double>();
    EXPECT_TRUE(fs::exists(d / w.at("image").get<std::string>())) << name;
    EXPECT_TRUE(fs::exists(d / w.at("error_map").get<std::string>())) << name;
  }
  EXPECT_LT(rms.at("post_2x"), rms.at("post_1x"));
  EXPECT_LT(rms.at("post_4x"), rms.at("post_2x"));
  EXPECT_EQ(j.at("goal_met").get<bool>(), psnr.at("preint_1x") >= psnr.at("post_4x"));
  EXPECT_EQ(j.at("lighting_can_reach").get<bool>(),
            psnr.at("preint_1x_exact_lighting") >= psnr.at("post_4x"));
  const std::string md = text_of(d / "report.md");
  for (const auto& [name, _] : rms)
    EXPECT_NE(md.find("| " + name + " | "), std::string::npos) << name;
  EXPECT_NE(md.find("## Finding"), std::string::npos);
}

TEST(PaperEngel2001, SceneWithoutAClassificationToPreintegrateIsAOneLineError) {
  const Command none = run("paper engel2001 --out " + temp_dir("paper_engel_none").string());
  EXPECT_EQ(none.status, 1);
  EXPECT_EQ(none.output, "voxcast: paper engel2001: a SCENE file is required\n");
  const Command mip = run("paper engel2001 " + tiny_scene() + " --set render.mode=mip --out " +
                          temp_dir("paper_engel_mip").string());
  EXPECT_EQ(mip.status, 1);
  EXPECT_EQ(mip.output, "voxcast: paper engel2001: " + tiny_scene() +
                            ": render.mode = mip has no classification to pre-integrate\n");
}

}  // namespace
