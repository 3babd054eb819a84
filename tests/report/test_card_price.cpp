// The XCU250 and the DDR4 card priced on it (issue 23, part 4): the part's
// data-sheet totals, the DSP48E2 and URAM288 closed forms, and N pipelines
// priced as exactly N per-pipeline parts, ceil(N/2) shared table copies and
// four channels, with the N that does not fit flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/hardware/report.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/precision/presets.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/engine.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using cosim::CardPrice;
using cosim::Family;
using cosim::Op;
using cosim::OpKind;
using cosim::Resources;

Op mulop(int a, bool as, int b, bool bs) { return {OpKind::Mul, "m", 1, a, b, as, bs}; }

ref::Elaboration shaded_design() {
  const ref::TransferFunction tf({{0, {1, 0.5, 0.2}, 0.0}, {100, {1, 0.8, 0.9}, 0.5}},
                                 ref::TfInterpolation::Ramp, ref::Material{});
  ref::DataRange r{kBalanced.value_bits, (1u << kBalanced.value_bits) - 1u, 100.0};
  return ref::elaborate(kBalanced, ref::RenderMode::Shaded, ref::Projection::Perspective, 0.98,
                        tf, r);
}

// The U250 board's card (channels' DIMM, default caches) with n pipelines.
CardPrice u250_card(int n, const cosim::Part& part = cosim::find_part("xcu250")) {
  rtl::RtlConfig c = rtl::rtl_config_for_board(rtl::board::load_board("alveo_u250"));
  c.card.pipelines = n;
  return cosim::price_card(shaded_design(), c.pipeline, c.card, part, "alveo_u250");
}

void expect_same(const Resources& a, const Resources& b, const std::string& what) {
  EXPECT_EQ(a.luts, b.luts) << what;
  EXPECT_EQ(a.ffs, b.ffs) << what;
  EXPECT_EQ(a.dsps, b.dsps) << what;
  EXPECT_EQ(a.brams, b.brams) << what;
  EXPECT_EQ(a.urams, b.urams) << what;
}

TEST(Xcu250, PartTotalsAreTheDataSheets) {
  // DS962 table 1 / DS923 (VU13P): 1,728K LUT, 3,456K FF, 12,288 DSP48E2,
  // 2,688 RAMB36E2, 1,280 URAM288.
  const cosim::Part& u = cosim::find_part("xcu250");
  EXPECT_EQ(u.family, Family::UltraScalePlus);
  EXPECT_EQ(u.luts, 1728000);
  EXPECT_EQ(u.ffs, 2 * u.luts);
  EXPECT_EQ(u.dsps, 12288);
  EXPECT_EQ(u.brams, 2 * 2688);  // counted in RAMB18E2 as the 7-series parts are
  EXPECT_EQ(u.urams, 1280);
  EXPECT_EQ(static_cast<long long>(u.urams) * 4096 * 72, 360LL * 1024 * 1024);  // 360 Mb
  // The parts before it have no UltraRAM.
  for (const char* p : {"xcv1000e", "xc2v3000", "xc7a200t", "xc7k325t"})
    EXPECT_EQ(cosim::find_part(p).urams, 0) << p;
  // The board file names the device with package and grade.
  EXPECT_EQ(cosim::find_device_part("xcu250-figd2104-2L-e").name, "xcu250");
  try {
    cosim::find_device_part("xcvu9p-flga2104-2L-e");
    FAIL() << "an unknown device must throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "the board's FPGA \"xcvu9p-flga2104-2L-e\" is not a part voxcast report knows "
              "(known: xcv1000e, xc2v3000, xc7a200t, xc7k325t, xcu250)");
  }
}

TEST(Xcu250, Dsp48e2IsTwentySevenByEighteen) {
  const Family f = Family::UltraScalePlus;
  EXPECT_EQ(cosim::dsp_count(mulop(27, true, 18, true), f), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(18, true, 27, true), f), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(26, true, 18, true), f), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(26, true, 18, true), Family::Series7), 2);  // 25 x 18
  EXPECT_EQ(cosim::dsp_count(mulop(28, true, 18, true), f), 2);
  // limbs: ceil over 27-bit and 18-bit ports, the unsigned operand one bit wider.
  EXPECT_EQ(cosim::dsp_count(mulop(28, false, 64, false), f), 6);  // 2 x 3
  EXPECT_EQ(cosim::dsp_count(mulop(8, true, 8, true), f), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(4, true, 4, true), f), 0);  // < 9 bits: LUTs
}

TEST(Xcu250, UramCountIsTheCascadeOfFourKByWideSeventyTwo) {
  const Family f = Family::UltraScalePlus;
  for (int lines : {4096, 8192, 16384, 32768, 65536}) {
    const int u = cosim::uram_count(lines, 512, f);
    EXPECT_EQ(u, ((lines + 4095) / 4096) * ((512 + 71) / 72)) << lines;
    // Never below the bit-capacity bound ceil(L·512 / (4096·72)): a 64-byte
    // line is read whole, so it takes eight 72-bit URAMs side by side.
    EXPECT_GE(u, static_cast<int>(std::ceil(lines * 512.0 / (4096 * 72)))) << lines;
  }
  EXPECT_EQ(cosim::uram_count(16384, 512, f), 32);
  EXPECT_EQ(cosim::uram_count(65536, 32, f), 16);  // the pre-integration table at 8 bits an end
  EXPECT_EQ(cosim::uram_count(16384, 512, Family::Series7), 0);
  EXPECT_EQ(cosim::uram_count(32, 512, f), 0);  // LUT RAM
  const cosim::Part& u250 = cosim::find_part("xcu250");
  EXPECT_TRUE(cosim::prefers_uram(16384, 512, u250));  // 32/1280 against 480/5376
  EXPECT_FALSE(cosim::prefers_uram(1024, 18, u250));   // 1/1280 against 1/5376
  EXPECT_FALSE(cosim::prefers_uram(16384, 512, cosim::find_part("xc7k325t")));
  const Resources r = cosim::op_resources({OpKind::Ram, "lines", 1, 16384, 512}, u250);
  EXPECT_EQ(r.urams, 32);
  EXPECT_EQ(r.brams, 0);
}

TEST(CardPrice, TotalIsNPipelinesHalfAsManyTableCopiesAndFourChannels) {
  const CardPrice one = u250_card(1);
  EXPECT_EQ(one.channels, 4);
  EXPECT_GT(one.per_pair.brams + one.per_pair.urams, 0);  // the shaded design's tables
  EXPECT_EQ(one.per_pair.luts + one.per_pair.ffs + one.per_pair.dsps, 0);
  for (int n : {1, 2, 3, 4, 8, 16, 64}) {
    const CardPrice c = u250_card(n);
    Resources expect = static_cast<double>(n) * one.per_pipeline;
    expect += static_cast<double>((n + 1) / 2) * one.per_pair;
    expect += 4.0 * one.per_channel;
    expect_same(c.total, expect, "N = " + std::to_string(n));
    expect_same(c.total, cosim::card_total(one, n), "card_total N = " + std::to_string(n));
  }
  // Per channel: the 16K lines of 64 bytes in URAM (ceil(16384/4096) x
  // ceil(512/72) = 32), the controller's assumed figures included.
  ASSERT_FALSE(one.channel.empty());
  EXPECT_EQ(one.cache_lines, 16384u);
  EXPECT_EQ(one.channel.front().res.urams, 32);
  Resources channel;
  for (const auto& it : one.channel) channel += it.res;
  channel += one.controller;
  expect_same(one.per_channel, channel, "per channel");
  EXPECT_FALSE(one.controller_source.empty());
}

TEST(CardPrice, LargestFitIsTheLastNWithinThePart) {
  const cosim::Part& u250 = cosim::find_part("xcu250");
  const CardPrice c = u250_card(1);
  ASSERT_GE(c.largest_fit, 1);
  EXPECT_LE(cosim::binding_share(cosim::card_total(c, c.largest_fit), u250), 1.0);
  if (c.largest_fit < CardPrice::kMaxPipelines) {
    EXPECT_GT(cosim::binding_share(cosim::card_total(c, c.largest_fit + 1), u250), 1.0);
  }
  EXPECT_TRUE(c.fits);
  // On an Artix-7 the four channels' 16K-line caches alone need 4 x 480
  // RAMB18 of its 730: not even one pipeline fits, and the report says so.
  const CardPrice a7 = u250_card(1, cosim::find_part("xc7a200t"));
  EXPECT_FALSE(a7.fits);
  EXPECT_EQ(a7.largest_fit, 0);
  EXPECT_STREQ(cosim::binding_resource(a7.total, cosim::find_part("xc7a200t")), "BRAM");
}

// A read port per look-up: N dual-port copies of each channel's lines (32
// URAM) and tags (4 URAM), so 144·N URAMs on the card; the vizard2 design's
// tables use no URAM, so the URAMs allow floor(1280 / 144) = 8 pipelines.
TEST(CardPrice, PortedCachesAreNCopiesOfEachChannelsStores) {
  const CardPrice c = u250_card(1);
  EXPECT_EQ(c.cache_store.urams, 36);
  for (int n : {1, 2, 5, 16}) {
    Resources expect = cosim::card_total(c, n);
    expect += static_cast<double>(4 * (n - 1)) * c.cache_store;
    expect_same(cosim::ported_card_total(c, n), expect, "N = " + std::to_string(n));
  }
  rtl::RtlConfig cfg = rtl::rtl_config_for_board(rtl::board::load_board("alveo_u250"));
  const ref::TransferFunction tf({{0, {1, 0.5, 0.2}, 0.0}, {100, {1, 0.8, 0.9}, 0.5}},
                                 ref::TfInterpolation::Ramp, ref::Material{});
  const ref::Elaboration v2 = ref::elaborate(kVizard2, ref::RenderMode::Shaded,
                                             ref::Projection::Perspective, 0.98, tf,
                                             {kVizard2.value_bits, 255u, 100.0});
  const CardPrice p = cosim::price_card(v2, cfg.pipeline, cfg.card, cosim::find_part("xcu250"),
                                        "alveo_u250");
  ASSERT_EQ(p.per_pair.urams + p.per_pipeline.urams, 0);
  EXPECT_EQ(cosim::ported_card_total(p, 8).urams, 144 * 8);
  EXPECT_EQ(p.ported_largest_fit, 1280 / 144);
  EXPECT_LT(p.ported_largest_fit, p.largest_fit);
}

TEST(CardPrice, ImpossiblePipelineCountIsOneError) {
  rtl::RtlConfig c = rtl::rtl_config_for_board(rtl::board::load_board("alveo_u250"));
  c.card.pipelines = 65;
  try {
    cosim::price_card(shaded_design(), c.pipeline, c.card, cosim::find_part("xcu250"), "u250");
    FAIL() << "65 pipelines must throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "DDR4 card: 65 pipelines is out of range 1..64");
  }
}

// `voxcast report` on the U250 board: the board's part by default, the card
// section in the Markdown and the JSON, its total the closed form.
TEST(CardPrice, ReportOnTheU250BoardPricesTheCard) {
  const std::string dir = ::testing::TempDir();
  const std::string json = dir + "/card_report.json", md = dir + "/card_report.md";
  const Command r = run_voxcast(
      "report " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml --set rtl.board=alveo_u250 " +
      "--set rtl.pipelines=8 --set render.width=32 --set render.height=32 --json " + json +
      " --md " + md);
  ASSERT_EQ(r.status, 0) << r.output;
  const Command cat = run_command("cat " + json);
  const nlohmann::json j = nlohmann::json::parse(cat.output);
  EXPECT_EQ(j["part"]["name"], "xcu250");
  EXPECT_EQ(j["part"]["uram"], 1280);
  const nlohmann::json& c = j.at("card");
  EXPECT_EQ(c["pipelines"], 8);
  for (const char* k : {"lut", "ff", "dsp", "bram", "uram"})
    EXPECT_EQ(c["total"][k].get<double>(), 8 * c["per_pipeline"][k].get<double>() +
                                               4 * c["per_pair"][k].get<double>() +
                                               4 * c["per_channel"][k].get<double>())
        << k;
  EXPECT_TRUE(c["fits"].get<bool>());
  const Command text = run_command("cat " + md);
  EXPECT_NE(text.output.find("## The DDR4 card: 8 pipelines on the xcu250"), std::string::npos);
  EXPECT_NE(text.output.find("| URAM288 |"), std::string::npos);
  // The SDR card's report has no card section.
  const Command sdr = run_voxcast("report " + std::string(VOXCAST_SOURCE_DIR) +
                                  "/scenes/mip.toml --set render.width=32 --set render.height=32");
  ASSERT_EQ(sdr.status, 0) << sdr.output;
  EXPECT_EQ(sdr.output.find("DDR4 card"), std::string::npos);
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
