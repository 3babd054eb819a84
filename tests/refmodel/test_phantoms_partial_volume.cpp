// Partial volume (phantom parameter aa): the mean of aa^3 point samples.
#include <gtest/gtest.h>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

TEST(PartialVolume, InteriorsKeepTheirValueAndEdgesBlend) {
  const int n = 48;
  const ref::Volume exact = ref::make_phantom("shells", n, 1);
  const ref::Volume pv = ref::make_phantom("shells", n, 3);
  int blended = 0;
  for (std::size_t i = 0; i < exact.data.size(); ++i) {
    // Every partial-volume value lies between the values the voxel touches,
    // i.e. within the phantom's value set's range.
    EXPECT_LE(pv.data[i], 240);
    if (pv.data[i] != exact.data[i]) ++blended;
  }
  EXPECT_GT(blended, 0);
  // The centre voxel of the grid is inside the innermost empty core: 0 either way.
  EXPECT_EQ(pv.at(n / 2, n / 2, n / 2), 0);
  EXPECT_EQ(pv.source, "phantom:shells?size=48&aa=3");
}

TEST(PartialVolume, BoxIsUnchangedAndAaIsChecked) {
  EXPECT_EQ(ref::make_phantom("box", 20, 4).data, ref::make_phantom("box", 20, 1).data);
  EXPECT_THROW(ref::make_phantom("box", 20, 0), Error);
  EXPECT_THROW(ref::make_phantom("box", 20, 9), Error);
  EXPECT_THROW(ref::load_volume("phantom:box?size=20&bogus=1", ".", nullptr), Error);
  EXPECT_EQ(ref::load_volume("phantom:box?aa=2&size=20", ".", nullptr).dims[0], 20);
}

TEST(PartialVolume, ConservesTheAnalyticMass) {
  // Sum of value x voxel volume = sum over shells of value x (4/3) pi
  // (r_out^3 - r_in^3) h^3, with h = (n-1)/2 voxels per normalised unit.
  // Partial volume integrates each voxel, so its sum approaches that integral;
  // at n = 64, aa = 4 it is within 0.5 % (centre sampling alone is not held to it).
  const int n = 64;
  const double h = (n - 1) / 2.0;
  const double pi = 3.14159265358979323846;
  const double shells[3][3] = {{0.9, 0.82, 80}, {0.6, 0.52, 160}, {0.3, 0.22, 240}};
  double analytic = 0.0;
  for (const auto& s : shells)
    analytic += s[2] * 4.0 / 3.0 * pi * (s[0] * s[0] * s[0] - s[1] * s[1] * s[1]) * h * h * h;
  const ref::Volume pv = ref::make_phantom("shells", n, 4);
  double sum = 0.0;
  for (std::uint16_t v : pv.data) sum += v;
  EXPECT_NEAR(sum / analytic, 1.0, 0.005);
}

}  // namespace
}  // namespace voxcast::test
