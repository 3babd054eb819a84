#include "cosim/explore/tune.hpp"
#include "cosim/reports/progress.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <ostream>
#include <sstream>
#include <tuple>

#include "cosim/engines/engines.hpp"
#include "cosim/reports/metrics.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/render/raycaster.hpp"

namespace voxcast::cosim {

namespace {

const ProfileField& field(const std::string& name) {
  for (const ProfileField& f : profile_fields())
    if (name == f.name) return f;
  throw Error("tune: unknown precision field \"" + name + "\" (see docs/scenes.md [precision])");
}

// Every point of the space, in the axes' order (the first axis slowest).
std::vector<PrecisionProfile> enumerate(const PrecisionProfile& base,
                                        const std::vector<TuneAxis>& axes) {
  std::vector<PrecisionProfile> out{base};
  for (const TuneAxis& a : axes) {
    const ProfileField& f = field(a.field);
    std::vector<PrecisionProfile> next;
    next.reserve(out.size() * static_cast<std::size_t>(a.hi - a.lo + 1));
    for (const PrecisionProfile& p : out)
      for (int v = a.lo; v <= a.hi; ++v) {
        PrecisionProfile q = p;
        q.*f.member = v;
        next.push_back(q);
      }
    out = std::move(next);
  }
  return out;
}

// The widths the kernels require of one another (the static_asserts of hls/):
// a profile breaking one is outside the design space.
bool kernel_constraints_hold(const PrecisionProfile& p) {
  return p.rsqrt_seed_bits <= p.dir_frac_bits &&
         p.addr_bits + p.pos_frac_bits + p.t_frac_bits <= 49 &&
         p.gradient_bits + 3 * p.weight_bits + 2 <= 64;
}

}  // namespace

std::vector<TuneAxis> default_tune_axes(const ref::Elaboration& e) {
  std::vector<TuneAxis> axes{{"weight_bits", 3, 8}, {"sample_frac_bits", 0, 6}};
  if (e.classification) {
    axes.push_back({"color_bits", 6, 12});
    axes.push_back({"alpha_bits", 8, 16});
  }
  // §4a: a quarter of the 2-D table per bit; below 5 bits (32 addresses per end)
  // a segment's ends are coarser than most transfer functions' features.
  if (e.preintegration) axes.push_back({"preint_addr_bits", 5, 8});
  if (e.reflectance_map) axes.push_back({"rm_frac_bits", 6, 12});
  if (e.shader) axes.push_back({"shade_bits", 8, 12});
  if (e.compositor || e.mip) axes.push_back({"acc_bits", 10, 16});
  return axes;
}

TuneAxis parse_tune_axis(const std::string& text) {
  const auto eq = text.find('=');
  const auto dots = text.find("..");
  if (eq == std::string::npos || dots == std::string::npos || dots < eq)
    throw Error("tune: --vary \"" + text + "\" is not FIELD=LO..HI (e.g. weight_bits=3..8)");
  TuneAxis a;
  a.field = text.substr(0, eq);
  if (a.field.rfind("precision.", 0) == 0) a.field = a.field.substr(10);
  try {
    a.lo = std::stoi(text.substr(eq + 1, dots - eq - 1));
    a.hi = std::stoi(text.substr(dots + 2));
  } catch (const std::exception&) {
    throw Error("tune: --vary \"" + text + "\": the range is not two integers LO..HI");
  }
  const ProfileField& f = field(a.field);
  if (a.lo > a.hi || a.lo < f.min || a.hi > f.max)
    throw Error("tune: --vary \"" + text + "\": the range must lie in " + std::to_string(f.min) +
                ".." + std::to_string(f.max) + " with LO <= HI");
  return a;
}

TuneResult run_tune(const ref::Scene& scene, const TuneOptions& o) {
  check_truth_settings(o.truth, scene);  // before anything is loaded or rendered
  const SceneVolume sv = load_scene_volume(scene);
  check_fixed_point(scene, sv, false);
  const ref::DataRange range = ref::data_range(sv.volume, sv.gradients);
  const ref::TransferFunction tf = ref::stored_transfer_function(scene, sv.volume);
  auto elaborate = [&](const PrecisionProfile& p) {
    ref::Elaboration e = ref::elaborate(p, scene.render.mode, scene.camera.projection,
                                        scene.render.ert_threshold, tf, range);
    // The pre-integration table is priced with the widths it is tuned over.
    e.preintegration = scene.render.preintegrated() && scene.render.mode != ref::RenderMode::Mip;
    return e;
  };
  const Part& part = find_part(o.part);

  TuneResult r;
  r.axes = o.axes.empty() ? default_tune_axes(elaborate(scene.precision)) : o.axes;
  std::vector<const ProfileField*> fields;
  for (const TuneAxis& a : r.axes) fields.push_back(&field(a.field));

  // Price every point; order by cost, then by the axes' values (deterministic).
  for (const PrecisionProfile& p : enumerate(scene.precision, r.axes)) {
    TunePoint t;
    t.profile = p;
    t.valid = kernel_constraints_hold(p);
    if (t.valid) {
      try {
        check_profile_fits(p, sv.volume, range.max_gradient);
      } catch (const Error&) {
        t.valid = false;
      }
    }
    if (t.valid) t.cost = cost(estimate_resources(elaborate(p), part).total, part);
    r.points.push_back(t);
  }
  r.space = r.points.size();
  auto key = [&](const TunePoint& t) {
    std::vector<int> v;
    for (const ProfileField* f : fields) v.push_back(t.profile.*f->member);
    return v;
  };
  std::stable_sort(r.points.begin(), r.points.end(), [&](const TunePoint& a, const TunePoint& b) {
    if (a.valid != b.valid) return a.valid;
    if (a.cost != b.cost) return a.cost < b.cost;
    return key(a) < key(b);
  });

  // The truth (cosim/engines/truth.hpp), as cosim and sweep measure against it: the
  // precision does not enter it, so one render serves the whole search.
  const ref::Image truth = render_truth_with_progress(scene, sv, o.truth);
  const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
  const ref::RenderInputs inputs = ref::make_render_inputs(scene, sv.volume, sv.gradients, pose);
  // Voxel memories depend on three fields only; build each once. Renders are
  // memoised by profile (the probes below and the walk share them).
  std::map<std::tuple<int, int, int>, bittrue::VoxelMemory> memories;
  std::map<std::vector<int>, double> psnr_of;
  // The search stops at the first point meeting the target: at most every
  // valid point is rendered.
  Progress progress("tune", static_cast<std::size_t>(std::count_if(
                                r.points.begin(), r.points.end(),
                                [](const TunePoint& t) { return t.valid; })),
                    false, true);
  auto measure = [&](const PrecisionProfile& p) {
    std::vector<int> k;
    for (const ProfileField& f : profile_fields()) k.push_back(p.*f.member);
    const auto hit = psnr_of.find(k);
    if (hit != psnr_of.end()) return hit->second;
    const auto mkey = std::make_tuple(p.value_bits, p.gradient_bits, p.gradient_frac_bits);
    auto it = memories.find(mkey);
    if (it == memories.end())
      it = memories.emplace(mkey, bittrue::make_voxel_memory(p, sv.volume, sv.gradients)).first;
    const bittrue::FrameSetup setup = bittrue::make_frame_setup(p, scene, inputs);
    const ref::QuantImage img = bittrue::bt_render_image(setup, it->second, scene.render.threads);
    const double psnr = measure_accuracy(img, truth).psnr_db;
    ++r.rendered;
    progress.step();
    psnr_of.emplace(k, psnr);
    return psnr;
  };
  auto valid = [&](const PrecisionProfile& p) {
    if (!kernel_constraints_hold(p)) return false;
    try {
      check_profile_fits(p, sv.volume, range.max_gradient);
    } catch (const Error&) {
      return false;
    }
    return true;
  };

  // Pruning: with accuracy monotone in every width, an axis value that misses
  // the target with every other axis at its widest misses with any other
  // values too. Binary search per axis for the narrowest value that meets the
  // target with the others at their widest: every point below it is skipped.
  std::vector<int> floor(r.axes.size());
  for (std::size_t i = 0; i < r.axes.size(); ++i) floor[i] = r.axes[i].lo;
  if (o.prune) {
    PrecisionProfile widest = scene.precision;
    for (std::size_t i = 0; i < r.axes.size(); ++i) widest.*fields[i]->member = r.axes[i].hi;
    if (!valid(widest) || measure(widest) < o.target_psnr_db) {
      r.pruned = r.space;  // nothing meets the target
      return r;
    }
    for (std::size_t i = 0; i < r.axes.size(); ++i) {
      int lo = r.axes[i].lo, hi = r.axes[i].hi;  // hi meets the target
      while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        PrecisionProfile q = widest;
        q.*fields[i]->member = mid;
        if (valid(q) && measure(q) >= o.target_psnr_db) {
          hi = mid;
        } else {
          lo = mid + 1;
        }
      }
      floor[i] = lo;
    }
  }
  for (TunePoint& t : r.points) {
    if (!t.valid) continue;
    bool below = false;
    for (std::size_t i = 0; i < fields.size(); ++i)
      below = below || t.profile.*fields[i]->member < floor[i];
    if (below) {
      ++r.pruned;
      continue;
    }
    t.psnr_db = measure(t.profile);
    t.rendered = true;
    if (t.psnr_db >= o.target_psnr_db) {
      r.found = true;
      r.best = t;
      break;
    }
  }
  return r;
}

std::string precision_table(const ref::Scene& scene, const PrecisionProfile& p) {
  const std::string preset = scene.precision_name.substr(0, scene.precision_name.find('+'));
  const PrecisionProfile base = preset_profile(preset);
  std::ostringstream s;
  s << "[precision]\nprofile = \"" << preset << "\"\n";
  for (const ProfileField& f : profile_fields())
    if (p.*f.member != base.*f.member) s << f.name << " = " << p.*f.member << "\n";
  return s.str();
}

void print_tune(std::ostream& os, const ref::Scene& scene, const TuneOptions& o,
                const TuneResult& r) {
  os << "tune " << scene.origin << ": target PSNR " << o.target_psnr_db << " dB against the "
     << "truth (float reference at " << o.truth.oversampling << "x oversampling), cost on "
     << o.part << "\n  search space:";
  for (const TuneAxis& a : r.axes) os << " " << a.field << "=" << a.lo << ".." << a.hi;
  os << " (" << r.space << " points; " << r.rendered << " rendered, " << r.pruned
     << " pruned)\n";
  if (!r.found) {
    os << (o.prune ? "  the widest point misses the target, so the pruned search stops (accuracy "
                     "is not always monotone: the exact search, without --prune, may find one)\n"
                   : "  no point of the search space meets the target\n");
    return;
  }
  os << "  cheapest: cost " << r.best.cost << ", PSNR " << r.best.psnr_db << " dB\n\n"
     << precision_table(scene, r.best.profile);
}

}  // namespace voxcast::cosim
