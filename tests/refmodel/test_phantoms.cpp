// Built-in phantoms: closed-form facts from their definitions (docs/volumes.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <queue>
#include <set>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace VOXCAST_UNITY_ID {

// Normalised coordinate of voxel i on an axis of n voxels (docs/volumes.md).
double norm(int i, int n) { return (2.0 * i - (n - 1)) / (n - 1); }

// Voxel index nearest to normalised coordinate u.
int nearest(double u, int n) { return static_cast<int>(std::lround((u + 1.0) * (n - 1) / 2.0)); }

std::set<std::uint16_t> distinct_values(const Volume& v) {
  return std::set<std::uint16_t>(v.data.begin(), v.data.end());
}

std::string expect_error(const std::string& name, int size) {
  try {
    make_phantom(name, size);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "make_phantom(\"" << name << "\", " << size << ") did not throw";
  return "";
}

// --- all phantoms ---------------------------------------------------------------

TEST(Phantoms, SharedMetadata) {
  for (const std::string name : {"shepp-logan", "shells", "tube", "box", "grating"}) {
    const Volume v = make_phantom(name, 20);
    EXPECT_EQ(v.dims, (std::array<int, 3>{20, 20, 20})) << name;
    EXPECT_EQ(v.bits, 8) << name;
    EXPECT_EQ(v.spacing.x, 1.0) << name;
    EXPECT_EQ(v.spacing.y, 1.0) << name;
    EXPECT_EQ(v.spacing.z, 1.0) << name;
    EXPECT_EQ(v.slope, 1.0) << name;
    EXPECT_EQ(v.intercept, 0.0) << name;
    EXPECT_EQ(v.source, "phantom:" + name + "?size=20");
    EXPECT_NO_THROW(validate(v, name));
  }
}

TEST(Phantoms, DeterministicAcrossCalls) {
  for (const std::string name : {"shepp-logan", "shells", "tube", "box", "grating"})
    EXPECT_EQ(make_phantom(name, 33).data, make_phantom(name, 33).data) << name;
}

TEST(Phantoms, UnknownNameListsTheBuiltIns) {
  const std::string msg = expect_error("sphere", 64);
  EXPECT_NE(msg.find("'sphere'"), std::string::npos) << msg;
  for (const char* name : {"shepp-logan", "shells", "tube", "box", "grating"})
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
}

TEST(Phantoms, SizeOutsideRangeIsNamed) {
  for (int size : {1, 0, -5, 1025}) {
    const std::string msg = expect_error("tube", size);
    EXPECT_NE(msg.find("phantom:tube"), std::string::npos) << msg;
    EXPECT_NE(msg.find("size " + std::to_string(size)), std::string::npos) << msg;
    EXPECT_NE(msg.find("2..1024"), std::string::npos) << msg;
  }
  EXPECT_NO_THROW(make_phantom("box", 2));
}

// --- grating ----------------------------------------------------------------------

// 128 + 100 cos(2 pi x / 3) at integer x: cos is 1, -1/2, -1/2, so 228, 78, 78.
TEST(GratingPhantom, PlanesRepeat228_78_78AlongXAndAreConstantInYAndZ) {
  const Volume v = make_phantom("grating", 9);
  constexpr std::uint16_t kPattern[3] = {228, 78, 78};
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x) ASSERT_EQ(v.at(x, y, z), kPattern[x % 3]) << x << "," << y << "," << z;
}

// Partial volume averages over the voxel in x: the mean of cos over a whole
// voxel of a period-3 wave is sinc(1/3) = (3/pi) sin(pi/3) = 0.82699 of the
// point value, so 128 + 82.7 = 210.7 and 128 - 41.35 = 86.65, to within the
// aa = 8 midpoint rule's error (< 0.5%) and rounding.
TEST(GratingPhantom, PartialVolumeAttenuatesByTheVoxelSinc) {
  const Volume v = make_phantom("grating", 6, 8);
  EXPECT_NEAR(v.at(0, 2, 3), 210.7, 1.0);
  EXPECT_NEAR(v.at(1, 2, 3), 86.65, 1.0);
  EXPECT_NEAR(v.at(2, 2, 3), 86.65, 1.0);
}

// --- box --------------------------------------------------------------------------

TEST(BoxPhantom, EveryVoxelMatchesTheIndexRule) {
  for (int n = 2; n <= 40; ++n) {
    const Volume v = make_phantom("box", n);
    const int lo = n / 4, hi = n - 1 - n / 4;
    auto in = [&](int i) { return i >= lo && i <= hi; };
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          ASSERT_EQ(v.at(x, y, z), (in(x) && in(y) && in(z)) ? 200 : 0)
              << "n " << n << " at " << x << "," << y << "," << z;
  }
}

TEST(BoxPhantom, CountsAndExtents) {
  struct Case {
    int n, lo, hi;
  };
  // lo = n/4, hi = n-1-n/4: the edge holds n - 2*(n/4) voxels.
  for (const Case c : {Case{2, 0, 1}, Case{3, 0, 2}, Case{4, 1, 2}, Case{7, 1, 5}, Case{64, 16, 47},
                       Case{255, 63, 191}, Case{256, 64, 191}}) {
    const Volume v = make_phantom("box", c.n);
    const std::size_t edge = static_cast<std::size_t>(c.hi - c.lo + 1);
    EXPECT_EQ(static_cast<std::size_t>(std::count(v.data.begin(), v.data.end(), 200)),
              edge * edge * edge)
        << "n " << c.n;
    EXPECT_EQ(static_cast<std::size_t>(std::count(v.data.begin(), v.data.end(), 0)),
              v.voxel_count() - edge * edge * edge)
        << "n " << c.n;
    const int m = (c.lo + c.hi) / 2;
    for (int axis = 0; axis < 3; ++axis) {
      auto value = [&](int i) {
        std::array<int, 3> p{m, m, m};
        p[axis] = i;
        return v.at(p[0], p[1], p[2]);
      };
      EXPECT_EQ(value(c.lo), 200) << "n " << c.n << " axis " << axis;
      EXPECT_EQ(value(c.hi), 200) << "n " << c.n << " axis " << axis;
      if (c.lo > 0) {
        EXPECT_EQ(value(c.lo - 1), 0) << "n " << c.n << " axis " << axis;
      }
      if (c.hi < c.n - 1) {
        EXPECT_EQ(value(c.hi + 1), 0) << "n " << c.n << " axis " << axis;
      }
    }
  }
}

// --- shells -------------------------------------------------------------------------

TEST(ShellsPhantom, ValuesAlongTheAxesAtKnownRadii) {
  // n = 129: the centre voxel is 64 and a voxel m steps from it along an axis is
  // at radius m/64. Shells [0.82, 0.9], [0.52, 0.6], [0.22, 0.3] hold the m with
  // 52.48 <= m <= 57.6, 33.28 <= m <= 38.4, 14.08 <= m <= 19.2.
  const int n = 129, c = 64;
  const Volume v = make_phantom("shells", n);
  auto expected = [](int m) -> int {
    if (m >= 53 && m <= 57) return 80;
    if (m >= 34 && m <= 38) return 160;
    if (m >= 15 && m <= 19) return 240;
    return 0;
  };
  for (int m = 0; m <= 64; ++m) {
    for (int s : {-1, 1}) {
      const int i = c + s * m;
      EXPECT_EQ(v.at(i, c, c), expected(m)) << "x axis, m " << m;
      EXPECT_EQ(v.at(c, i, c), expected(m)) << "y axis, m " << m;
      EXPECT_EQ(v.at(c, c, i), expected(m)) << "z axis, m " << m;
    }
  }
  EXPECT_EQ(v.at(c, c, c), 0);
  EXPECT_EQ(v.at(0, 0, 0), 0);
}

TEST(ShellsPhantom, MirrorSymmetricAndOnlyFourValues) {
  for (int n : {64, 65}) {
    const Volume v = make_phantom("shells", n);
    EXPECT_EQ(distinct_values(v), (std::set<std::uint16_t>{0, 80, 160, 240})) << "n " << n;
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::uint16_t w = v.at(x, y, z);
          ASSERT_EQ(w, v.at(n - 1 - x, y, z));
          ASSERT_EQ(w, v.at(x, n - 1 - y, z));
          ASSERT_EQ(w, v.at(x, y, n - 1 - z));
        }
  }
}

TEST(ShellsPhantom, ShellVolumesMatchTheSphereFormulaWithinOnePercent) {
  // Voxels per shell ~ 4/3 pi (R^3 - r^3) h^3 with h = (n-1)/2 voxels per unit.
  const int n = 200;
  const Volume v = make_phantom("shells", n);
  const double h3 = std::pow((n - 1) / 2.0, 3.0);
  const std::array<std::array<double, 3>, 3> shells{
      {{0.9, 0.82, 80}, {0.6, 0.52, 160}, {0.3, 0.22, 240}}};
  for (const auto& s : shells) {
    const double expected =
        4.0 / 3.0 * std::numbers::pi * (std::pow(s[0], 3) - std::pow(s[1], 3)) * h3;
    const auto count = std::count(v.data.begin(), v.data.end(), static_cast<std::uint16_t>(s[2]));
    EXPECT_NEAR(static_cast<double>(count), expected, 0.01 * expected) << "value " << s[2];
  }
}

// --- tube -----------------------------------------------------------------------------

constexpr std::uint16_t kLumen = 0, kWall = 200, kTissue = 40;

TEST(TubePhantom, OnlyLumenWallAndTissueValues) {
  EXPECT_EQ(distinct_values(make_phantom("tube", 64)),
            (std::set<std::uint16_t>{kLumen, kTissue, kWall}));
}

TEST(TubePhantom, EndoscopyEyePointIsInTheLumen) {
  // The eye of the endoscopy scenes, normalised (-0.3, 0, -0.7): all eight
  // voxels around it (what trilinear sampling reads) are lumen.
  for (int n : {16, 32, 64, 100, 128, 256}) {
    const Volume v = make_phantom("tube", n);
    const double h = (n - 1) / 2.0;
    const double ex = (-0.3 + 1.0) * h, ey = h, ez = (-0.7 + 1.0) * h;
    const int x0 = static_cast<int>(std::floor(ex)), y0 = static_cast<int>(std::floor(ey)),
              z0 = static_cast<int>(std::floor(ez));
    for (int dz = 0; dz <= 1; ++dz)
      for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx)
          EXPECT_EQ(v.at(x0 + dx, y0 + dy, z0 + dz), kLumen)
              << "n " << n << " voxel " << x0 + dx << "," << y0 + dy << "," << z0 + dz;
    // Looking along +z, the centreline stays in the lumen up to the bend.
    for (double uz = -0.7; uz <= 0.0; uz += 0.05)
      EXPECT_EQ(v.at(nearest(-0.3, n), nearest(0.0, n), nearest(uz, n)), kLumen)
          << "n " << n << " uz " << uz;
  }
}

TEST(TubePhantom, LumenRadiusScalesWithSize) {
  // On the line along x through the first segment's axis (odd n: y = 0 is a
  // voxel), the lumen holds the voxels within 0.16 h of x = -0.3 h.
  for (int n : {65, 129, 193}) {
    const Volume v = make_phantom("tube", n);
    const double h = (n - 1) / 2.0;
    const int y = (n - 1) / 2, z = nearest(-0.7, n);
    int lumen = 0;
    for (int x = 0; x < n; ++x) {
      const double d = std::abs((x - h) - (-0.3 * h));
      const bool expect_lumen = d <= 0.16 * h;
      EXPECT_EQ(v.at(x, y, z) == kLumen, expect_lumen) << "n " << n << " x " << x;
      lumen += v.at(x, y, z) == kLumen;
    }
    EXPECT_NEAR(lumen, 2 * 0.16 * h, 2.0) << "n " << n;
  }
}

// Lengths of the runs of wall voxels along a line; the line must cross the
// tube: tissue, wall, lumen, wall, tissue.
std::vector<int> wall_runs(const std::vector<std::uint16_t>& line) {
  std::vector<int> runs;
  std::vector<std::uint16_t> kinds;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (kinds.empty() || kinds.back() != line[i]) {
      kinds.push_back(line[i]);
      if (line[i] == kWall) runs.push_back(0);
    }
    if (line[i] == kWall) ++runs.back();
  }
  EXPECT_EQ(kinds, (std::vector<std::uint16_t>{kTissue, kWall, kLumen, kWall, kTissue}));
  return runs;
}

TEST(TubePhantom, WallIsOneOrTwoVoxelsThickAtEverySize) {
  for (int n : {48, 64, 129, 256}) {
    const Volume v = make_phantom("tube", n);
    auto line = [&](int axis, int a, int b) {
      std::vector<std::uint16_t> out(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        std::array<int, 3> p{};
        p[axis] = i;
        p[(axis + 1) % 3] = a;
        p[(axis + 2) % 3] = b;
        out[static_cast<std::size_t>(i)] = v.at(p[0], p[1], p[2]);
      }
      return out;
    };
    auto check = [&](const std::vector<std::uint16_t>& l, const std::string& where) {
      SCOPED_TRACE("n " + std::to_string(n) + ", " + where);
      for (int run : wall_runs(l)) {
        EXPECT_GE(run, 1);
        EXPECT_LE(run, 2);
      }
    };
    // First straight segment (axis along z at x = -0.3, y = 0), away from the
    // branch at z = -0.45 and the bend at z = 0: lines along x and along y.
    for (double uz : {-0.85, -0.7, -0.2, -0.1}) {
      const int z = nearest(uz, n);
      check(line(0, nearest(0.0, n), z), "segment 1, line along x, uz " + std::to_string(uz));
      check(line(1, z, nearest(-0.3, n)), "segment 1, line along y, uz " + std::to_string(uz));
    }
    // Last straight segment (axis along x at y = 0, z = 0.5), away from the
    // bend and the branch at x = 0.55: lines along y and along z.
    for (double ux : {0.3, 0.35, 0.75, 0.8}) {
      const int x = nearest(ux, n);
      check(line(1, nearest(0.5, n), x), "segment 2, line along y, ux " + std::to_string(ux));
      check(line(2, x, nearest(0.0, n)), "segment 2, line along z, ux " + std::to_string(ux));
    }
  }
}

TEST(TubePhantom, LumenNeverTouchesTissue) {
  // The wall is >= 1.5 voxels thick, so no lumen voxel has a tissue 6-neighbour.
  const int n = 96;
  const Volume v = make_phantom("tube", n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (v.at(x, y, z) != kLumen) continue;
        const std::array<std::array<int, 3>, 6> nb{{{x - 1, y, z},
                                                    {x + 1, y, z},
                                                    {x, y - 1, z},
                                                    {x, y + 1, z},
                                                    {x, y, z - 1},
                                                    {x, y, z + 1}}};
        for (const auto& p : nb) {
          if (std::min({p[0], p[1], p[2]}) < 0 || std::max({p[0], p[1], p[2]}) >= n) continue;
          ASSERT_NE(v.at(p[0], p[1], p[2]), kTissue) << x << "," << y << "," << z;
        }
      }
}

TEST(TubePhantom, BranchesAndBendFormOneConnectedLumen) {
  const int n = 64;
  const Volume v = make_phantom("tube", n);
  auto value = [&](double ux, double uy, double uz) {
    return v.at(nearest(ux, n), nearest(uy, n), nearest(uz, n));
  };
  // Branch 1 (along +y at x = -0.3, z = -0.45) and branch 2 (along -y at
  // x = 0.55, z = 0.5) exist; nothing mirrors them on the other side.
  EXPECT_EQ(value(-0.3, 0.4, -0.45), kLumen);
  EXPECT_EQ(value(-0.3, 0.65, -0.45), kLumen);
  EXPECT_EQ(value(-0.3, 0.9, -0.45), kTissue);  // beyond the cap at y = 0.78
  EXPECT_EQ(value(-0.3, -0.4, -0.45), kTissue);
  EXPECT_EQ(value(0.55, -0.4, 0.5), kLumen);
  EXPECT_EQ(value(0.55, -0.65, 0.5), kLumen);
  EXPECT_EQ(value(0.55, -0.9, 0.5), kTissue);
  EXPECT_EQ(value(0.55, 0.4, 0.5), kTissue);
  // The bend: the arc's midpoint, centre (0.2, 0, 0) + 0.5 (-cos 45, 0, sin 45).
  EXPECT_EQ(value(0.2 - 0.5 * std::numbers::sqrt2 / 2, 0.0, 0.5 * std::numbers::sqrt2 / 2), kLumen);
  EXPECT_EQ(value(0.2, 0.0, 0.0), kTissue);  // the arc's centre is outside the tube
  // The tube is open where it meets the grid faces z = 0 and x = n-1.
  EXPECT_EQ(v.at(nearest(-0.3, n), nearest(0.0, n), 0), kLumen);
  EXPECT_EQ(v.at(n - 1, nearest(0.0, n), nearest(0.5, n)), kLumen);

  // Flood the lumen from the eye voxel: it reaches both branch tips and both
  // open ends, and every lumen voxel.
  std::vector<char> seen(v.voxel_count(), 0);
  std::queue<std::array<int, 3>> todo;
  const std::array<int, 3> eye{nearest(-0.3, n), nearest(0.0, n), nearest(-0.7, n)};
  ASSERT_EQ(v.at(eye[0], eye[1], eye[2]), kLumen);
  todo.push(eye);
  seen[v.index(eye[0], eye[1], eye[2])] = 1;
  std::size_t reached = 0;
  while (!todo.empty()) {
    const auto p = todo.front();
    todo.pop();
    ++reached;
    for (int axis = 0; axis < 3; ++axis)
      for (int step : {-1, 1}) {
        auto q = p;
        q[axis] += step;
        if (q[axis] < 0 || q[axis] >= n) continue;
        const std::size_t i = v.index(q[0], q[1], q[2]);
        if (seen[i] || v.data[i] != kLumen) continue;
        seen[i] = 1;
        todo.push(q);
      }
  }
  auto reached_at = [&](double ux, double uy, double uz) {
    return seen[v.index(nearest(ux, n), nearest(uy, n), nearest(uz, n))] != 0;
  };
  EXPECT_TRUE(reached_at(-0.3, 0.65, -0.45)) << "branch 1 tip";
  EXPECT_TRUE(reached_at(0.55, -0.65, 0.5)) << "branch 2 tip";
  EXPECT_TRUE(reached_at(0.95, 0.0, 0.5)) << "end of the last segment";
  EXPECT_TRUE(reached_at(-0.3, 0.0, -0.95)) << "start of the first segment";
  EXPECT_EQ(reached, static_cast<std::size_t>(std::count(v.data.begin(), v.data.end(), kLumen)));
}

// --- shepp-logan ------------------------------------------------------------------------

TEST(SheppLoganPhantom, CornersAreBackground) {
  for (int n : {2, 17, 64}) {
    const Volume v = make_phantom("shepp-logan", n);
    for (int z : {0, n - 1})
      for (int y : {0, n - 1})
        for (int x : {0, n - 1}) EXPECT_EQ(v.at(x, y, z), 0) << "n " << n;
  }
}

TEST(SheppLoganPhantom, GreyLevelsAreTheTableSums) {
  // Densities (tenths) 0, 2, 3, 4, 6, 10 map to round(25.5 d): 0 51 77 102 153 255.
  const std::set<std::uint16_t> allowed{0, 51, 77, 102, 153, 255};
  for (int n : {64, 128}) {
    const std::set<std::uint16_t> got = distinct_values(make_phantom("shepp-logan", n));
    for (std::uint16_t w : got) EXPECT_TRUE(allowed.count(w)) << "n " << n << " value " << w;
    EXPECT_TRUE(got.count(255) && got.count(51) && got.count(102)) << "n " << n;
  }
}

TEST(SheppLoganPhantom, SkullIsTheBrightestAndOutermostLayer) {
  const int n = 96;
  const Volume v = make_phantom("shepp-logan", n);
  EXPECT_EQ(*std::max_element(v.data.begin(), v.data.end()), 255);
  // 255 = inside ellipsoid 1 but outside ellipsoid 2, whose smallest semi-axis
  // is 0.6624 and ellipsoid 1's largest 0.92: skull voxels have 0.6624 < |u| <= 0.92.
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (v.at(x, y, z) != 255) continue;
        const double r = std::hypot(norm(x, n), norm(y, n), norm(z, n));
        ASSERT_GT(r, 0.6624);
        ASSERT_LE(r, 0.92 + 1e-12);
      }
  // Walking in from outside along each axis, the first non-zero voxel is skull.
  const int c = n / 2;
  for (int axis = 0; axis < 3; ++axis)
    for (int dir : {1, -1}) {
      std::array<int, 3> p{c, c, c};
      p[axis] = dir > 0 ? 0 : n - 1;
      while (v.at(p[0], p[1], p[2]) == 0) p[axis] += dir;
      EXPECT_EQ(v.at(p[0], p[1], p[2]), 255) << "axis " << axis << " dir " << dir;
    }
}

TEST(SheppLoganPhantom, KnownRegions) {
  const int n = 128;
  const Volume v = make_phantom("shepp-logan", n);
  auto value = [&](double ux, double uy, double uz) {
    return v.at(nearest(ux, n), nearest(uy, n), nearest(uz, n));
  };
  EXPECT_EQ(value(0.0, -0.3, 0.0), 51);        // brain: 1.0 - 0.8
  EXPECT_EQ(value(-0.22, 0.0, -0.25), 0);      // left ventricle: 1.0 - 0.8 - 0.2
  EXPECT_EQ(value(0.22, 0.0, -0.25), 0);       // right ventricle
  EXPECT_EQ(value(0.0, 0.35, -0.25), 102);     // ellipsoid 5: 0.2 + 0.2
  EXPECT_EQ(value(0.06, -0.105, 0.625), 102);  // ellipsoid 9: 0.2 + 0.2
  EXPECT_EQ(value(0.0, 0.1, 0.625), 0);        // ellipsoid 10: 0.2 - 0.2
  EXPECT_EQ(value(-0.08, -0.65, -0.25), 77);   // ellipsoid 7: 0.2 + 0.1
  EXPECT_EQ(value(0.0, 0.0, 0.0), 51);
  EXPECT_EQ(value(0.0, 0.0, 0.89), 255);  // skull above the brain (0.88 < z <= 0.9)
}

TEST(SheppLoganPhantom, MirrorSymmetricWhereOnlyTheHeadEllipsoidsReach) {
  // Every inner ellipsoid lies within |z| <= 0.75, where the phantom is not
  // symmetric; beyond it only the two centred head ellipsoids remain, and
  // those slices are symmetric under x -> -x, y -> -y and z -> -z.
  for (int n : {64, 65}) {
    const Volume v = make_phantom("shepp-logan", n);
    int checked = 0;
    for (int z = 0; z < n; ++z) {
      if (std::abs(norm(z, n)) <= 0.76) continue;
      ++checked;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::uint16_t w = v.at(x, y, z);
          ASSERT_EQ(w, v.at(n - 1 - x, y, z)) << "n " << n;
          ASSERT_EQ(w, v.at(x, n - 1 - y, z)) << "n " << n;
          ASSERT_EQ(w, v.at(x, y, n - 1 - z)) << "n " << n;
        }
    }
    EXPECT_GT(checked, 0);
    // ... and the inner structures make the middle asymmetric (the two
    // ventricles differ), which the test above must not claim.
    bool asymmetric = false;
    const int z = nearest(-0.25, n);
    for (int y = 0; y < n && !asymmetric; ++y)
      for (int x = 0; x < n && !asymmetric; ++x)
        asymmetric = v.at(x, y, z) != v.at(n - 1 - x, y, z);
    EXPECT_TRUE(asymmetric) << "n " << n;
  }
}

}  // namespace
}  // namespace voxcast::ref
