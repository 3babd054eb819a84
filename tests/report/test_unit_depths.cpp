// One source for the pipeline depths (issue 17, item 4): each unit's depth is
// declared once, next to its kernel in hls/ (hls/geometry_processor.hpp,
// "Pipeline depths"), and three readers must agree with it:
//   1. the cycle model's defaults, rtl::pipeline::UnitLatencies and the
//      elaborated latencies of a frame's units;
//   2. the resource report's per-unit latency and its ray set-up and sample
//      latencies;
//   3. the HLS LATENCY pragmas of the kernels: voxcast_synth_lint (libclang,
//      the synthesis compile of the VIZARD II top) lists every reachable
//      function with a LATENCY pragma, the constant it names and that
//      constant's value, and the list must be exactly the kernels below.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "cosim/hardware/report.hpp"
#include "hls/classification_table.hpp"
#include "hls/compositor.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/shader.hpp"
#include "hls/space_leaping_unit.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "rtl_model/pipeline/config.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

namespace pl = rtl::pipeline;

// ---- 1. The cycle model ---------------------------------------------------------------------

TEST(UnitDepths, CycleModelDefaultsAreTheDeclaredDepths) {
  const pl::UnitLatencies l;
  EXPECT_EQ(l.ray_setup, hls::ray_setup_depth + hls::rsqrt_depth);
  EXPECT_EQ(l.address, hls::stepping_depth + hls::address_generator_depth);
  EXPECT_EQ(l.interpolation, hls::crossbar_depth + hls::lerp_depth);
  EXPECT_EQ(l.classification, hls::classification_depth);
  EXPECT_EQ(l.shading, hls::reflectance_map_depth + hls::shader_depth);
  EXPECT_EQ(l.leap_lookup, hls::leap_lookup_depth);
  EXPECT_EQ(l.leap, hls::leap_lookup_depth + hls::leap_search_depth);
  EXPECT_EQ(pl::kRsqrtStages, hls::rsqrt_depth);
  EXPECT_EQ(pl::kUnshadedShadeStages, hls::shader_depth);
  // The search: max_leap_bits stages, five to a clock.
  EXPECT_EQ(hls::leap_search_depth, (hls::widths::max_leap_bits + 4) / 5);
}

TEST(UnitDepths, ElaboratedCycleModelDropsTheAbsentUnitsDepths) {
  const pl::UnitLatencies base;
  // {mip, shaded, perspective, leaping}
  const pl::UnitLatencies parallel = pl::elaborate_latencies(base, {false, true, false, false});
  EXPECT_EQ(parallel.ray_setup, hls::ray_setup_depth);
  EXPECT_EQ(parallel.leap_lookup, 0);
  const pl::UnitLatencies unshaded = pl::elaborate_latencies(base, {false, false, true, true});
  EXPECT_EQ(unshaded.shading, hls::shader_depth);
  EXPECT_EQ(unshaded.leap_lookup, hls::leap_lookup_depth);
  const pl::UnitLatencies mip = pl::elaborate_latencies(base, {true, false, true, false});
  EXPECT_EQ(mip.classification, 0);
  EXPECT_EQ(mip.shading, 0);
  EXPECT_EQ(mip.interpolation, hls::interpolation_depth);
}


// ---- 2. The report --------------------------------------------------------------------------

ref::Elaboration design(bool mip, bool shaded, bool perspective) {
  ref::Elaboration e;
  e.profile = kBalanced;
  e.perspective = perspective;
  e.parallel_direction = !perspective;
  e.mip = mip;
  e.classification = e.compositor = e.ert = !mip;
  e.reflectance_map = e.gradients = !mip && shaded;
  e.shader = !mip;
  e.space_leaping = !mip;
  e.leap_blocks = 64;
  e.jitter = true;
  return e;
}

std::map<std::string, int> latencies(const cosim::ResourceReport& r) {
  std::map<std::string, int> out;
  for (const auto& u : r.units) out[u.unit.name] = u.unit.latency;
  return out;
}

TEST(UnitDepths, ReportLatenciesAreTheDeclaredDepths) {
  const cosim::Part part = cosim::find_part("xc7a200t");
  // Shaded, perspective, with space leaping and jitter: every unit but MIP.
  const auto shaded = cosim::estimate_resources(design(false, true, true), part);
  const std::map<std::string, int> expected = {
      {"ray_direction+rsqrt", hls::rsqrt_depth},
      {"ray_setup", hls::ray_setup_depth},
      {"stepping", hls::stepping_depth},
      {"address_generator", hls::address_generator_depth},
      {"space_leaping", hls::leap_lookup_depth},
      {"jitter", 0},  // beside the direction and rsqrt pipeline
      {"interpolation", hls::interpolation_depth},
      {"classification", hls::classification_depth},
      {"reflectance_map", hls::reflectance_map_depth},
      {"shader", hls::shader_depth},
      {"compositor", hls::compositor_depth},
      {"ert", hls::ert_depth},
      {"output", hls::output_quantization_depth},
      {"pipeline_buffers", 0},
  };
  EXPECT_EQ(latencies(shaded), expected);
  EXPECT_EQ(shaded.latency_ray_setup, hls::perspective_ray_setup_depth);
  EXPECT_EQ(shaded.latency_sample,
            hls::stepping_depth + hls::address_generator_depth + hls::leap_lookup_depth +
                hls::interpolation_depth + hls::classification_depth +
                hls::reflectance_map_depth + hls::shader_depth + hls::compositor_depth);

  // Unshaded, parallel: no rsqrt unit, no reflectance map.
  const auto unshaded = cosim::estimate_resources(design(false, false, false), part);
  const auto u = latencies(unshaded);
  EXPECT_EQ(u.count("ray_direction+rsqrt"), 0u);
  EXPECT_EQ(u.count("reflectance_map"), 0u);
  EXPECT_EQ(u.at("ray_setup"), hls::ray_setup_depth);
  EXPECT_EQ(u.at("shader"), hls::shader_depth);
  EXPECT_EQ(unshaded.latency_ray_setup, hls::ray_setup_depth);
  EXPECT_EQ(unshaded.latency_sample,
            hls::stepping_depth + hls::address_generator_depth + hls::leap_lookup_depth +
                hls::interpolation_depth + hls::classification_depth + hls::shader_depth +
                hls::compositor_depth);

  // MIP: the maximum register after the interpolation.
  const auto mip = cosim::estimate_resources(design(true, false, true), part);
  EXPECT_EQ(latencies(mip).at("mip"), hls::mip_depth);
  EXPECT_EQ(mip.latency_sample, hls::stepping_depth + hls::address_generator_depth +
                                    hls::interpolation_depth + hls::mip_depth);

  // The report's text says the same numbers.
  std::ostringstream line;
  line << "Latency: ray set-up " << hls::perspective_ray_setup_depth << " cycles; a sample "
       << shaded.latency_sample << " cycles";
  EXPECT_NE(cosim::report_markdown(shaded).find(line.str()), std::string::npos);
  EXPECT_NE(cosim::report_markdown(shaded).find("| interpolation | §3.4-3.5 | " +
                                                std::to_string(hls::interpolation_depth) + " |"),
            std::string::npos);
}

// ---- 3. The kernels' LATENCY pragmas --------------------------------------------------------

// function -> (constant, value), as voxcast_synth_lint --latencies prints them.
using PragmaList = std::set<std::tuple<std::string, std::string, long long>>;

PragmaList expected_pragmas() {
  auto h = [](const char* name) { return std::string("voxcast::hls::") + name; };
  return {
      {h("normalize_direction"), h("rsqrt_depth"), hls::rsqrt_depth},
      {h("ray_setup_perspective"), h("perspective_ray_setup_depth"),
       hls::perspective_ray_setup_depth},
      {h("ray_setup_parallel"), h("ray_setup_depth"), hls::ray_setup_depth},
      {h("step_position"), h("stepping_depth"), hls::stepping_depth},
      {h("address_generator"), h("address_generator_depth"), hls::address_generator_depth},
      {h("interpolation_processor"), h("lerp_depth"), hls::lerp_depth},
      {h("sample_block_empty"), h("leap_lookup_depth"), hls::leap_lookup_depth},
      {h("leap_run"), h("leap_search_depth"), hls::leap_search_depth},
  };
}

PragmaList parse_latency_lines(const std::string& output) {
  PragmaList out;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("latency: ", 0) != 0) continue;
    std::istringstream fields(line.substr(9));
    std::string fn, constant;
    long long value = 0;
    fields >> fn >> constant >> value;
    out.insert({fn, constant, value});
  }
  return out;
}

// render.partial_segments (docs/pipeline.md §7a): the segment-opacity unit runs
// beside the reflectance map and the shader. A shaded frame's shading stage
// (4 clocks) covers its 3; an unshaded frame's single clock grows to 3; MIP has
// no such stage.
TEST(UnitDepths, SegmentOpacityOverlapsTheShadingStage) {
  const pl::UnitLatencies base;
  // {mip, shaded, perspective, leaping, partial_segments}
  EXPECT_EQ(pl::elaborate_latencies(base, {false, true, true, false, true}).shading,
            hls::reflectance_map_depth + hls::shader_depth);
  EXPECT_GE(hls::reflectance_map_depth + hls::shader_depth, hls::segment_opacity_depth);
  EXPECT_EQ(pl::elaborate_latencies(base, {false, false, true, false, true}).shading,
            hls::segment_opacity_depth);
  EXPECT_EQ(pl::elaborate_latencies(base, {true, false, true, false, true}).shading, 0);
  // The report lists the unit at its depth; the sample's latency is the longer path.
  const cosim::Part part = cosim::find_part("xc7a200t");
  for (const bool shaded : {true, false}) {
    ref::Elaboration e = design(false, shaded, true);
    e.partial_segments = true;
    ref::Elaboration e0 = e;
    e0.partial_segments = false;
    const auto with = cosim::estimate_resources(e, part);
    const auto without = cosim::estimate_resources(e0, part);
    EXPECT_EQ(latencies(with).at("segment_opacity"), hls::segment_opacity_depth);
    EXPECT_EQ(latencies(with).at("shader"), hls::shader_depth);
    EXPECT_EQ(latencies(without).count("segment_opacity"), 0u);
    EXPECT_EQ(with.latency_sample - without.latency_sample,
              shaded ? 0 : hls::segment_opacity_depth - hls::shader_depth);
  }
}

TEST(UnitDepths, LatencyPragmasNameTheDeclaredDepths) {
#if defined(VOXCAST_SYNTH_LINT_EXE) && defined(VOXCAST_SYNTH_LINT_ARGS)
  for (const char* profile : {"Vizard2Traits", "BalancedTraits", "PreciseTraits"}) {
    const Command r = run_command(std::string(VOXCAST_SYNTH_LINT_EXE) + " --latencies " +
                                  VOXCAST_SYNTH_LINT_ARGS + " -DVOXCAST_SYNTH_PROFILE=" + profile +
                                  " " + VOXCAST_SOURCE_DIR + "/hls/vizard2_synth_top.cpp");
    // Exit 0: no latency-pragma finding (a number in a pragma, a LATENCY in an
    // inlined function) and nothing else.
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(parse_latency_lines(r.output), expected_pragmas()) << profile << "\n" << r.output;
  }
#else
  GTEST_SKIP() << "voxcast_synth_lint is not built (no libclang): the pragmas are not checked";
#endif
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
