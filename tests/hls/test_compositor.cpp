// Shader (hls/shader.hpp, docs/pipeline.md §6) and compositor with output
// quantisation (hls/compositor.hpp, §7-8), the three checks of STYLE.md for the
// vizard2, balanced and precise presets:
//  (a) hls == bit-true exactly: fixed-seed samples of entries x reflectances,
//      accumulator states x alphas x colours, every accumulator value through the
//      output stage, ERT and MIP;
//  (b) against the float reference (ref::shade, ref::composite) with bounds
//      derived from the widths, for one step and for whole rays;
//  (c) closed forms: n samples of constant alpha reach 1 - (1 - a)^n, ERT stops at
//      the first sample with A >= threshold, alpha 0 is skipped, a miss is
//      (0, 0, 0, 0), opaque white and MIP's maximum reach full scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "hls/compositor.hpp"
#include "hls/shader.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/render/raycaster.hpp"

#include "preset_types.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;
namespace bt = voxcast::bittrue;

using test::Profile;
using Presets = test::ThreePresets;
using PresetNames = test::ThreePresetNames;

using C3 = std::array<double, 3>;

template <class T>
class PixelBackEndTest : public ::testing::Test {
 protected:
  static constexpr PrecisionProfile kP = T::value;
  using CP = hls::CompositorParams<ProfileTraits<kP>>;
  using acc_t = typename CP::acc_t;
  using alpha_t = typename CP::alpha_t;
  using shade_t = typename CP::shade_t;
  using entry_t = typename hls::ReflectanceParams<ProfileTraits<kP>>::entry_t;

  // A fixed or integer type holding a raw unsigned integer.
  template <class X>
  static X from_raw(std::uint64_t raw) {
    X x;
    x.range() = raw;
    return x;
  }
  static double lsb(int bits) { return std::ldexp(1.0, -bits); }
  static std::uint64_t top(int bits) { return (std::uint64_t{1} << bits) - 1; }

  std::uint64_t uniform(std::uint64_t hi) {
    return std::uniform_int_distribution<std::uint64_t>(0, hi)(rng_);
  }
  // A random raw value of `bits` bits, with the ends (0, 1, max - 1, max) 1/8 of the time.
  std::uint64_t raw_field(int bits) {
    const std::uint64_t hi = top(bits);
    switch (uniform(31)) {
      case 0:
        return 0;
      case 1:
        return std::min<std::uint64_t>(1, hi);
      case 2:
        return hi - std::min<std::uint64_t>(1, hi);
      case 3:
        return hi;
      default:
        return uniform(hi);
    }
  }
  bt::ClassEntry random_entry() {
    bt::ClassEntry e;
    e.r = static_cast<std::uint32_t>(raw_field(kP.color_bits));
    e.g = static_cast<std::uint32_t>(raw_field(kP.color_bits));
    e.b = static_cast<std::uint32_t>(raw_field(kP.color_bits));
    e.alpha = static_cast<std::uint32_t>(raw_field(kP.alpha_bits));
    e.ka = static_cast<std::uint32_t>(raw_field(kP.k_bits));
    e.kd = static_cast<std::uint32_t>(raw_field(kP.k_bits));
    e.ks = static_cast<std::uint32_t>(raw_field(kP.k_bits));
    return e;
  }
  // A state reachable by compositing: C[k] <= A <= 1.
  bt::BtAccumulator random_state() {
    bt::BtAccumulator s;
    const std::uint64_t one = std::uint64_t{1} << kP.acc_bits;
    const std::uint64_t a = uniform(3) == 0 ? one - uniform(3) : uniform(one);
    s.A = std::ldexp(static_cast<double>(a), -kP.acc_bits);
    for (double& c : s.C) c = std::ldexp(static_cast<double>(uniform(a)), -kP.acc_bits);
    return s;
  }
  static hls::Accumulator<ProfileTraits<kP>> to_hls(const bt::BtAccumulator& s) {
    hls::Accumulator<ProfileTraits<kP>> acc;
    for (int k = 0; k < 3; ++k) acc.C[k] = acc_t(s.C[static_cast<std::size_t>(k)]);
    acc.A = acc_t(s.A);
    return acc;
  }
  static hls::ShadedColor<ProfileTraits<kP>> to_hls(const C3& c) {
    hls::ShadedColor<ProfileTraits<kP>> out;
    for (int k = 0; k < 3; ++k) out.c[k] = shade_t(c[static_cast<std::size_t>(k)]);
    return out;
  }
  static bool same(const hls::Accumulator<ProfileTraits<kP>>& h, const bt::BtAccumulator& b) {
    return h.C[0].to_double() == b.C[0] && h.C[1].to_double() == b.C[1] &&
           h.C[2].to_double() == b.C[2] && h.A.to_double() == b.A;
  }
  C3 random_colour() {
    C3 c;
    for (double& x : c)
      x = std::ldexp(static_cast<double>(raw_field(kP.shade_bits)), -kP.shade_bits);
    return c;
  }
  double random_alpha() {
    return std::ldexp(static_cast<double>(raw_field(kP.alpha_bits)), -kP.alpha_bits);
  }

  std::mt19937_64 rng_{0xC0FFEE};
};
TYPED_TEST_SUITE(PixelBackEndTest, Presets, PresetNames);

// ==== Shader (§6) =============================================================================

TYPED_TEST(PixelBackEndTest, ShaderMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const int rbits = P.rm_int_bits + P.rm_frac_bits;
  for (int n = 0; n < 100000; ++n) {
    const bt::ClassEntry raw = this->random_entry();
    const std::uint64_t d = this->raw_field(rbits), s = this->raw_field(rbits);
    const hls::ClassEntry<ProfileTraits<P>> e = hls::host::entry_from_raw<ProfileTraits<P>>(raw);
    hls::Reflect<ProfileTraits<P>> r;
    r.D = TestFixture::template from_raw<typename TestFixture::entry_t>(d);
    r.S = TestFixture::template from_raw<typename TestFixture::entry_t>(s);
    const bt::BtReflect br{r.D.to_double(), r.S.to_double()};
    for (const bool shaded : {true, false}) {
      const hls::ShadedColor<ProfileTraits<P>> got = hls::shade(e, r, shaded);
      const C3 want = bt::bt_shade(P, raw, br, shaded);
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(got.c[k].to_double(), want[static_cast<std::size_t>(k)])
            << "n " << n << " channel " << k << " shaded " << shaded;
    }
  }
}

// Against ref::shade with the same inputs: I rounds by <= 2^-(sb+1), which colour < 1
// passes on scaled; U(colour·I) rounds by <= 2^-(sb+1) and saturates 1 to 1 - 2^-sb.
// |c - min(colour·I_exact, 1)| <= 2^-sb + 2^-(sb+1).
TYPED_TEST(PixelBackEndTest, ShaderWithinDerivedBoundOfFloatShade) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const int rbits = P.rm_int_bits + P.rm_frac_bits;
  const double bound = 1.5 * TestFixture::lsb(P.shade_bits);
  double worst = 0.0;
  for (int n = 0; n < 50000; ++n) {
    const bt::ClassEntry raw = this->random_entry();
    const hls::ClassEntry<ProfileTraits<P>> e = hls::host::entry_from_raw<ProfileTraits<P>>(raw);
    hls::Reflect<ProfileTraits<P>> r;
    r.D = TestFixture::template from_raw<typename TestFixture::entry_t>(this->raw_field(rbits));
    r.S = TestFixture::template from_raw<typename TestFixture::entry_t>(this->raw_field(rbits));
    ref::Classified c;
    c.color = {e.r.to_double(), e.g.to_double(), e.b.to_double()};
    c.ka = e.ka.to_double(), c.kd = e.kd.to_double(), c.ks = e.ks.to_double();
    const ref::Vec3 want = ref::shade(c, ref::Reflectance{r.D.to_double(), r.S.to_double()});
    const hls::ShadedColor<ProfileTraits<P>> got = hls::shade(e, r, true);
    for (int k = 0; k < 3; ++k) {
      const double err = std::abs(got.c[k].to_double() - want[k]);
      ASSERT_LE(err, bound) << "n " << n << " channel " << k;
      worst = std::max(worst, err);
    }
  }
  this->RecordProperty("worst_shade_error_lsb", std::to_string(std::ldexp(worst, P.shade_bits)));
}

// Unshaded mode is U(colour, shade_bits); ka = 1 - LSB with D = S = 0 scales by I = Q_RND(ka).
TYPED_TEST(PixelBackEndTest, ShaderClosedForms) {
  constexpr PrecisionProfile P = TestFixture::kP;
  bt::ClassEntry raw;
  raw.r = static_cast<std::uint32_t>(TestFixture::top(P.color_bits));
  raw.g = 0;
  raw.b = 1u << (P.color_bits - 1);
  raw.ka = static_cast<std::uint32_t>(TestFixture::top(P.k_bits));
  const hls::ClassEntry<ProfileTraits<P>> e = hls::host::entry_from_raw<ProfileTraits<P>>(raw);
  hls::Reflect<ProfileTraits<P>> r;
  r.D = 0;
  r.S = 0;
  const hls::ShadedColor<ProfileTraits<P>> flat = hls::shade(e, r, false);
  EXPECT_EQ(flat.c[0].to_double(), bt::u_frac(1.0 - TestFixture::lsb(P.color_bits), P.shade_bits));
  EXPECT_EQ(flat.c[1].to_double(), 0.0);
  EXPECT_EQ(flat.c[2].to_double(), 0.5);
  const double intensity = bt::q_rnd(1.0 - TestFixture::lsb(P.k_bits), P.shade_bits);
  const hls::ShadedColor<ProfileTraits<P>> lit = hls::shade(e, r, true);
  EXPECT_EQ(lit.c[2].to_double(), bt::q_rnd(0.5 * intensity, P.shade_bits));
}

// ==== Compositor (§7) and output (§8) =========================================================

TYPED_TEST(PixelBackEndTest, CompositeStepMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  for (int n = 0; n < 200000; ++n) {
    const bt::BtAccumulator s = this->random_state();
    const double alpha = this->random_alpha();
    const C3 c = this->random_colour();
    hls::Accumulator<ProfileTraits<P>> h = TestFixture::to_hls(s);
    bt::BtAccumulator b = s;
    const bool hc = hls::composite(h, TestFixture::to_hls(c), typename TestFixture::alpha_t(alpha));
    const bool bc = bt::bt_composite(P, b, c, alpha);
    ASSERT_EQ(hc, bc);
    ASSERT_TRUE(TestFixture::same(h, b))
        << "from " << s << " alpha " << alpha << ": hls " << h << ", bit-true " << b;
  }
}

TYPED_TEST(PixelBackEndTest, EveryAccumulatorValueQuantizesLikeBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const std::uint64_t one = std::uint64_t{1} << P.acc_bits;
  for (std::uint64_t raw = 0; raw <= one; ++raw) {
    const auto x = TestFixture::template from_raw<typename TestFixture::acc_t>(raw);
    ASSERT_EQ(hls::quantize_output<ProfileTraits<P>>(x).to_uint(), bt::bt_output_channel(P, x.to_double()))
        << "x = " << x.to_double();
  }
  // And whole pixels.
  for (int n = 0; n < 10000; ++n) {
    const bt::BtAccumulator s = this->random_state();
    const hls::OutputPixel<ProfileTraits<P>> got = hls::output(TestFixture::to_hls(s));
    const std::array<std::uint32_t, 4> want = bt::bt_output(P, s);
    for (int k = 0; k < 4; ++k) ASSERT_EQ(got.ch[k].to_uint(), want[static_cast<std::size_t>(k)]);
  }
}

TYPED_TEST(PixelBackEndTest, ErtMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  bt::FrameSetup fs;
  fs.profile = P;
  for (int n = 0; n < 20000; ++n) {
    fs.regs.ert_enabled = n % 4 != 0;
    fs.regs.ert_threshold = static_cast<bt::Raw>(this->uniform(std::uint64_t{1} << P.acc_bits));
    const hls::CompositorRegisters<ProfileTraits<P>> regs = hls::host::compositor_registers<ProfileTraits<P>>(fs.regs);
    const bt::BtAccumulator s = this->random_state();
    ASSERT_EQ(hls::ert_reached(TestFixture::to_hls(s), regs), bt::bt_ert(fs, s));
  }
}

// MIP: the maximum and the grey SAT(Q_RND(M·RM, acc_bits), 0, 1), for the RM of every
// volume width 1..16 bits and for random RM.
TYPED_TEST(PixelBackEndTest, MipMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  using value_t = typename TestFixture::CP::value_t;
  bt::FrameSetup fs;
  fs.profile = P;
  const std::uint64_t max_value_raw = TestFixture::top(P.value_bits) << P.sample_frac_bits;
  for (int n = 0; n < 40000; ++n) {
    const int bits = 1 + n % 16;
    fs.regs.RM = n % 2 == 0
                     ? bt::to_raw(bt::q_rnd(1.0 / (std::ldexp(1.0, bits) - 1.0), P.dir_frac_bits),
                                  P.dir_frac_bits)
                     : static_cast<bt::Raw>(this->uniform(std::uint64_t{1} << P.dir_frac_bits));
    const hls::CompositorRegisters<ProfileTraits<P>> regs = hls::host::compositor_registers<ProfileTraits<P>>(fs.regs);
    value_t m_hls = TestFixture::template from_raw<value_t>(0);
    double m_bt = 0.0;
    for (int j = 0; j < 4; ++j) {
      const std::uint64_t raw = this->uniform(max_value_raw);
      hls::mip_update<ProfileTraits<P>>(m_hls, TestFixture::template from_raw<value_t>(raw));
      m_bt = bt::bt_mip_max(m_bt, std::ldexp(static_cast<double>(raw), -P.sample_frac_bits));
    }
    ASSERT_EQ(m_hls.to_double(), m_bt);
    const hls::Accumulator<ProfileTraits<P>> px = hls::mip_pixel<ProfileTraits<P>>(m_hls, regs);
    ASSERT_TRUE(TestFixture::same(px, bt::bt_mip_pixel(fs, m_bt))) << "M " << m_bt;
  }
}

// (b) One step against ref::composite from the same state and inputs: w rounds by
// <= h = 2^-(acc+1); C[k] moves by w·c (c < 1, so w's error passes scaled by c) rounded by
// <= h: |dC| <= 2h = 2^-acc, |dA| <= h.
TYPED_TEST(PixelBackEndTest, CompositeStepWithinDerivedBoundOfFloat) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double h = TestFixture::lsb(P.acc_bits + 1);
  for (int n = 0; n < 50000; ++n) {
    const bt::BtAccumulator s = this->random_state();
    const double alpha = this->random_alpha();
    const C3 c = this->random_colour();
    hls::Accumulator<ProfileTraits<P>> got = TestFixture::to_hls(s);
    hls::composite(got, TestFixture::to_hls(c), typename TestFixture::alpha_t(alpha));
    ref::Accumulator want;
    want.color = {s.C[0], s.C[1], s.C[2]};
    want.alpha = s.A;
    if (alpha > 0.0) ref::composite(want, ref::Vec3(c[0], c[1], c[2]), alpha);
    for (int k = 0; k < 3; ++k) ASSERT_LE(std::abs(got.C[k].to_double() - want.color[k]), 2 * h);
    ASSERT_LE(std::abs(got.A.to_double() - want.alpha), h);
  }
}

// (b) Whole rays of random samples, no ERT, against ref::composite. With h = 2^-(acc+1),
// the errors e_A, e_C of the fixed state against the float one obey
//   e_A' = e_A·(1 - alpha) + r_w,              |r_w| <= h,
//   e_C' = e_C + (r_w - e_A·alpha)·c + r_c,    |r_c| <= h,
// so E_A' = E_A·(1 - alpha) + h and E_C' = E_C + (E_A·alpha + h)·c + h bound them (the
// saturations never act, §7). The output then differs from x_float·(2^out - 1) by at most
// 0.5 + E·(2^out - 1).
TYPED_TEST(PixelBackEndTest, RaysWithinDerivedBoundOfFloatInOutputLsbs) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double h = TestFixture::lsb(P.acc_bits + 1);
  const double scale = std::ldexp(1.0, P.out_bits) - 1.0;
  double worst_lsb = 0.0, worst_bound_lsb = 0.0;
  for (int ray = 0; ray < 2000; ++ray) {
    const int n = 1 + static_cast<int>(this->uniform(299));
    const double alpha_scale = std::ldexp(1.0, -static_cast<int>(this->uniform(6)));
    hls::Accumulator<ProfileTraits<P>> fixed;
    bt::BtAccumulator bit_true;
    ref::Accumulator flt;
    double ea = 0.0;
    C3 ec{0.0, 0.0, 0.0};
    for (int j = 0; j < n; ++j) {
      const double alpha = bt::q_rnd(this->random_alpha() * alpha_scale, P.alpha_bits);
      const C3 c = this->random_colour();
      hls::composite(fixed, TestFixture::to_hls(c), typename TestFixture::alpha_t(alpha));
      bt::bt_composite(P, bit_true, c, alpha);
      if (alpha > 0.0) ref::composite(flt, ref::Vec3(c[0], c[1], c[2]), alpha);
      for (std::size_t k = 0; k < 3; ++k) ec[k] += (ea * alpha + h) * c[k] + h;
      ea = ea * (1.0 - alpha) + h;
    }
    ASSERT_TRUE(TestFixture::same(fixed, bit_true)) << "ray " << ray;
    const hls::OutputPixel<ProfileTraits<P>> out = hls::output(fixed);
    const double want[4] = {flt.color[0], flt.color[1], flt.color[2], flt.alpha};
    const double e[4] = {ec[0], ec[1], ec[2], ea};
    for (int k = 0; k < 4; ++k) {
      const double err = std::abs(out.ch[k].to_uint() - want[k] * scale);
      const double bound = 0.5 + e[k] * scale;
      ASSERT_LE(err, bound) << "ray " << ray << " channel " << k;
      worst_lsb = std::max(worst_lsb, err);
      worst_bound_lsb = std::max(worst_bound_lsb, bound);
    }
  }
  this->RecordProperty("worst_output_error_lsb", std::to_string(worst_lsb));
  this->RecordProperty("largest_output_bound_lsb", std::to_string(worst_bound_lsb));
}

// (c) n samples of constant alpha a: A_n = 1 - (1 - a)^n within h·(1 - (1 - a)^n)/a
// (the recursion above with E_A(0) = 0), for alphas from one LSB to nearly 1.
TYPED_TEST(PixelBackEndTest, ConstantAlphaReachesClosedForm) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double h = TestFixture::lsb(P.acc_bits + 1);
  const C3 white{1.0 - TestFixture::lsb(P.shade_bits), 1.0 - TestFixture::lsb(P.shade_bits),
                 1.0 - TestFixture::lsb(P.shade_bits)};
  for (const double a_in : {0.001, 0.01, 0.05, 0.2, 0.5, 0.9, 0.999}) {
    const double a = bt::u_frac(std::max(a_in, TestFixture::lsb(P.alpha_bits)), P.alpha_bits);
    hls::Accumulator<ProfileTraits<P>> acc;
    for (int n = 1; n <= 600; ++n) {
      hls::composite(acc, TestFixture::to_hls(white), typename TestFixture::alpha_t(a));
      const double exact = 1.0 - std::pow(1.0 - a, n);
      ASSERT_LE(std::abs(acc.A.to_double() - exact), h * exact / a) << "a " << a << " n " << n;
    }
  }
}

// (c) ERT: the ray stops at the first composited sample with A >= T = Q_RND(threshold,
// acc_bits); skipped (alpha 0) samples are never tested. With constant alpha a the exact
// opacity after n samples is 1 - (1 - a)^n and the fixed one is within tol = h/a of it
// (ConstantAlphaReachesClosedForm), so the stop lies between the closed-form stops
// n*(T - tol) and n*(T + tol), n*(t) = min{n >= 1 : 1 - (1 - a)^n >= t}; it equals n*(T)
// when no exact opacity falls within tol of T.
TYPED_TEST(PixelBackEndTest, ErtStopsAtTheFirstSampleReachingTheThreshold) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double h = TestFixture::lsb(P.acc_bits + 1);
  bt::FrameSetup fs;
  fs.profile = P;
  fs.regs.ert_enabled = true;
  const C3 grey{0.5, 0.5, 0.5};
  for (const double threshold : {0.0, 0.5, 0.9, 0.95, 0.98}) {
    fs.regs.ert_threshold = bt::to_raw(bt::q_rnd(threshold, P.acc_bits), P.acc_bits);
    const double t_q = bt::q_rnd(threshold, P.acc_bits);
    const hls::CompositorRegisters<ProfileTraits<P>> regs = hls::host::compositor_registers<ProfileTraits<P>>(fs.regs);
    for (const double a_in : {0.01, 0.1, 0.3, 0.7}) {
      const double a = bt::u_frac(a_in, P.alpha_bits);
      hls::Accumulator<ProfileTraits<P>> acc;
      bt::BtAccumulator b;
      int stop = -1, samples = 0;
      for (int j = 0; j < 5000 && stop < 0; ++j) {
        // Every third sample is transparent: skipped, never tested.
        const double alpha = j % 3 == 0 ? 0.0 : a;
        const bool composited =
            hls::composite(acc, TestFixture::to_hls(grey), typename TestFixture::alpha_t(alpha));
        ASSERT_EQ(composited, bt::bt_composite(P, b, grey, alpha));
        ASSERT_EQ(composited, alpha > 0.0);
        if (!composited) continue;
        ++samples;
        const bool stops = hls::ert_reached(acc, regs);
        ASSERT_EQ(stops, bt::bt_ert(fs, b));
        ASSERT_EQ(stops, acc.A.to_double() >= t_q);
        if (stops) stop = j;
      }
      ASSERT_GE(stop, 0);
      auto closed = [&](double t) {
        int n = 1;
        while (n < 100000 && 1.0 - std::pow(1.0 - a, n) < t) ++n;
        return n;
      };
      const double tol = h / a;
      EXPECT_GE(samples, closed(t_q - tol)) << "threshold " << threshold << " alpha " << a;
      EXPECT_LE(samples, closed(t_q + tol)) << "threshold " << threshold << " alpha " << a;
      const int n_star = closed(t_q);
      bool clear = true;
      for (int n = 1; n <= closed(t_q + tol); ++n)
        clear = clear && std::abs(1.0 - std::pow(1.0 - a, n) - t_q) > tol;
      if (clear) {
        EXPECT_EQ(samples, n_star) << "threshold " << threshold << " alpha " << a;
      }
    }
  }
}

// (c) A miss is (0, 0, 0, 0); opaque white saturates A to exactly 1 (full scale); alpha 0
// changes nothing; the MIP maximum of a full-range volume is full-scale grey.
TYPED_TEST(PixelBackEndTest, OutputClosedForms) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const unsigned full = (1u << P.out_bits) - 1u;
  const hls::OutputPixel<ProfileTraits<P>> miss = hls::output(hls::Accumulator<ProfileTraits<P>>{});
  for (int k = 0; k < 4; ++k) EXPECT_EQ(miss.ch[k].to_uint(), 0u);

  hls::Accumulator<ProfileTraits<P>> acc;
  const C3 white{1.0, 1.0, 1.0};  // saturates to 1 - 2^-shade_bits
  EXPECT_FALSE(hls::composite(acc, TestFixture::to_hls(white), typename TestFixture::alpha_t(0.0)));
  EXPECT_TRUE(TestFixture::same(acc, bt::BtAccumulator{}));
  for (int j = 0; j < 64; ++j)
    hls::composite(acc, TestFixture::to_hls(white),
                   typename TestFixture::alpha_t(1.0 - TestFixture::lsb(P.alpha_bits)));
  EXPECT_EQ(acc.A.to_double(), 1.0);
  const hls::OutputPixel<ProfileTraits<P>> px = hls::output(acc);
  EXPECT_EQ(px.ch[3].to_uint(), full);
  // The colour reaches 1 - 2^-shade_bits: full scale once shade_bits > out_bits.
  const unsigned white_out = bt::bt_output_channel(P, 1.0 - TestFixture::lsb(P.shade_bits));
  EXPECT_EQ(px.ch[0].to_uint(), white_out);
  EXPECT_EQ(white_out, P.shade_bits > P.out_bits ? full : full - 1u);

  bt::FrameSetup fs;
  fs.profile = P;
  fs.regs.RM = bt::to_raw(bt::q_rnd(1.0 / 255.0, P.dir_frac_bits), P.dir_frac_bits);
  using value_t = typename TestFixture::CP::value_t;
  const hls::Accumulator<ProfileTraits<P>> mip =
      hls::mip_pixel<ProfileTraits<P>>(value_t(255.0), hls::host::compositor_registers<ProfileTraits<P>>(fs.regs));
  const hls::OutputPixel<ProfileTraits<P>> grey = hls::output(mip);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(grey.ch[k].to_uint(), full);
}

}  // namespace
