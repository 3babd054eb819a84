#include "refmodel/bittrue/raycaster.hpp"

#include <algorithm>
#include <cmath>

#include "refmodel/parallel.hpp"

namespace voxcast::bittrue {

FrameSetup make_frame_setup(const PrecisionProfile& profile, const ref::Scene& scene,
                            const ref::RenderInputs& inputs) {
  FrameSetup fs;
  fs.profile = profile;
  fs.regs = make_frame_registers(profile, scene, inputs);
  if (fs.regs.perspective) fs.rsqrt_seed = make_rsqrt_seed(profile);
  // The table is addressed by the value field, where the data sit shifted to
  // its full range (§3.4): express the transfer function in field units.
  const ref::TransferFunction tf_field =
      field_transfer_function(profile, inputs.tf, *inputs.volume.volume);
  fs.class_table = make_class_table(profile, tf_field, inputs.settings.step);
  // A MIP or unshaded scene instantiates no shading unit: no reflectance maps.
  if (scene.render.mode == ref::RenderMode::Shaded)
    make_reflectance_maps(profile, inputs.shading, fs.rm_diffuse, fs.rm_specular);
  if (scene.render.space_leaping && scene.render.mode != ref::RenderMode::Mip) {
    LeapTables t;
    t.blocks = inputs.leap ? inputs.leap->blocks
                           : std::make_shared<const ref::MinMaxBlocks>(ref::make_min_max_blocks(
                                 *inputs.volume.volume, ref::leap_block_log2(scene.render.leap_block)));
    t.value_shift = value_shift(profile, *inputs.volume.volume);
    t.nonzero_prefix = nonzero_prefix(fs.class_table);
    fs.leap = std::move(t);
  }
  if (scene.render.partial_segments && scene.render.mode != ref::RenderMode::Mip)
    fs.segments = make_segment_tables(profile, fs.class_table);
  if (scene.render.preintegrated() && scene.render.mode != ref::RenderMode::Mip)
    fs.preint_table = make_preint_table(profile, tf_field, inputs.settings.step);
  return fs;
}

std::vector<std::uint32_t> nonzero_prefix(const std::vector<ClassEntry>& table) {
  std::vector<std::uint32_t> prefix(table.size() + 1, 0);
  for (std::size_t i = 0; i < table.size(); ++i)
    prefix[i + 1] = prefix[i] + (table[i].alpha != 0 ? 1u : 0u);
  return prefix;
}

bool bt_block_empty(const FrameSetup& fs, std::size_t block) {
  const LeapTables& t = *fs.leap;
  const double lo = std::ldexp(t.blocks->vmin[block], t.value_shift);
  const double hi = std::ldexp(t.blocks->vmax[block], t.value_shift);
  const auto a_lo = static_cast<std::size_t>(bt_class_address(fs.profile, lo));
  const auto a_hi = static_cast<std::size_t>(bt_class_address(fs.profile, hi));
  return t.nonzero_prefix[a_hi + 1] == t.nonzero_prefix[a_lo];
}

bool bt_skips(const FrameSetup& fs, const std::array<double, 3>& pos) {
  const ref::MinMaxBlocks& b = *fs.leap->blocks;
  std::array<int, 3> bc{};
  for (std::size_t k = 0; k < 3; ++k) {
    const double c = std::clamp(pos[k], static_cast<double>(fs.regs.LO[k]),
                                static_cast<double>(fs.regs.HI[k]));
    bc[k] = ref::cell_base(c, fs.regs.dims[k]) >> b.block_log2;
  }
  return bt_block_empty(fs, b.index(bc[0], bc[1], bc[2]));
}

const char* to_string(Unit u) {
  switch (u) {
    case Unit::RaySetup: return "ray setup (geometry processor)";
    case Unit::Stepping: return "stepping (geometry processor)";
    case Unit::Interpolation: return "interpolation processor";
    case Unit::Classification: return "classification table";
    case Unit::ReflectanceMap: return "reflectance map";
    case Unit::Shader: return "shader";
    case Unit::Compositor: return "compositor";
    case Unit::Output: return "output quantization";
  }
  return "?";
}

Divergence first_divergence(const RayTrace& a, const RayTrace& b) {
  if (a.hit != b.hit || a.samples != b.samples || a.p0 != b.p0 || a.step != b.step)
    return {true, 0, Unit::RaySetup};
  const std::size_t n = std::min(a.trace.size(), b.trace.size());
  for (std::size_t j = 0; j < n; ++j) {
    const SampleTrace& x = a.trace[j];
    const SampleTrace& y = b.trace[j];
    const auto at = [j](Unit u) { return Divergence{true, j, u}; };
    if (x.position != y.position) return at(Unit::Stepping);
    if (x.value != y.value || x.gradient != y.gradient) return at(Unit::Interpolation);
    if (x.class_address != y.class_address || x.alpha != y.alpha) return at(Unit::Classification);
    if (x.diffuse != y.diffuse || x.specular != y.specular) return at(Unit::ReflectanceMap);
    if (x.shaded != y.shaded) return at(Unit::Shader);
    if (x.accumulator != y.accumulator) return at(Unit::Compositor);
  }
  if (a.trace.size() != b.trace.size()) return {true, n, Unit::Compositor};  // ERT differs
  if (a.out != b.out) return {true, 0, Unit::Output};
  return {};
}

std::array<std::uint32_t, 4> bt_cast_ray(const FrameSetup& fs, const VoxelMemory& memory, int px,
                                         int py, RayTrace* trace, ref::RayStats* stats) {
  const PrecisionProfile& p = fs.profile;
  const BtRay ray = bt_ray_setup(fs, px, py);
  if (trace) {
    *trace = RayTrace{};
    trace->hit = ray.hit;
    trace->samples = ray.n;
    // A miss carries no position or step (docs/pipeline.md §1.6), in either engine.
    if (ray.hit) {
      trace->p0 = ray.p0;
      trace->step = ray.s;
    }
  }
  ref::RayStats local;
  ref::RayStats& rs = stats ? *stats : local;
  rs = ref::RayStats{};
  rs.hit = ray.hit;
  std::array<std::uint32_t, 4> out{0, 0, 0, 0};
  if (ray.hit) {
    const bool mip = fs.regs.mode == ref::RenderMode::Mip;
    const bool shaded = fs.regs.mode == ref::RenderMode::Shaded;
    const bool leap = fs.leap && !mip;
    BtAccumulator acc;
    double peak = 0.0;
    const BtSegmentWeights weights = bt_segment_weights(fs, ray, px, py);
    std::array<double, 3> pos = ray.p0;
    BtSample front;  // §4a: the previous sample (the segment's front value and gradient)
    for (std::uint64_t j = 0; j < ray.n; ++j) {
      if (j > 0) pos = bt_step(pos, ray.s);
      // A sample in an empty block classifies transparent: skipped unread.
      if (leap && bt_skips(fs, pos)) {
        ++rs.skipped;
        continue;
      }
      ++rs.samples;
      const BtSample s = bt_interpolate(p, fs.regs, memory, pos);
      SampleTrace st;
      st.position = pos;
      st.value = s.value;
      st.gradient = s.g;
      if (mip) {
        peak = bt_mip_max(peak, s.value);
        st.accumulator[0] = peak;
        if (trace) trace->trace.push_back(st);
        continue;
      }
      // §4a: the segment from the previous sample (the first sample's from itself).
      // §4a: the segment from the previous sample; a ray's first sample opens
      // the first segment and ends none (a transparent entry).
      static const ClassEntry kNoSegment{};
      const ClassEntry& e = !fs.preint_table ? bt_classify(fs, s.value)
                            : j == 0         ? kNoSegment
                                             : bt_classify_segment(fs, front.value, s.value);
      // §4a: a segment is shaded with its front sample's gradient.
      const std::array<double, 3> lit = fs.preint_table ? front.g : s.g;
      front = s;
      st.class_address = bt_class_address(p, s.value);
      // §7a: the opacity for the sample's segment (the table's alpha but for the
      // first and last samples of a ray with render.partial_segments).
      st.alpha = bt_segment_alpha(fs, st.class_address, bt_alpha(p, e),
                                  bt_sample_weight(weights, j, ray.n));
      bool stop = false;
      if (st.alpha > 0.0) {
        const BtReflect r = shaded ? bt_reflectance(fs, lit) : BtReflect{};
        st.diffuse = r.D;
        st.specular = r.S;
        st.shaded = bt_shade(p, e, r, shaded);
        bt_composite(p, acc, st.shaded, st.alpha);
        stop = bt_ert(fs, acc);
      }
      st.accumulator = {acc.C[0], acc.C[1], acc.C[2], acc.A};
      if (trace) trace->trace.push_back(st);
      if (stop) {
        rs.terminated_early = j + 1 < ray.n;
        break;
      }
    }
    out = bt_output(p, mip ? bt_mip_pixel(fs, peak) : acc);
  }
  if (trace) trace->out = out;
  return out;
}

ref::QuantImage bt_render_image(const FrameSetup& fs, const VoxelMemory& memory, int threads,
                                ref::FrameStats* stats) {
  ref::QuantImage img(fs.regs.width, fs.regs.height, fs.profile.out_bits);
  std::vector<ref::FrameStats> rows(static_cast<std::size_t>(img.height));
  ref::parallel_for(
      img.height,
      [&](int y) {
        for (int x = 0; x < img.width; ++x) {
          ref::RayStats rs;
          img.at(x, y) = bt_cast_ray(fs, memory, x, y, nullptr, &rs);
          rows[static_cast<std::size_t>(y)].add(rs);
        }
      },
      threads);
  if (stats) {
    *stats = ref::FrameStats{};
    for (const ref::FrameStats& r : rows) *stats += r;
  }
  return img;
}

}  // namespace voxcast::bittrue
