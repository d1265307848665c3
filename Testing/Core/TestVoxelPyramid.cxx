// SPDX-License-Identifier: BSD-3-Clause
// The voxel hierarchy: aggregates, and transmittance at coarse levels with
// bounds that always contain the exact optical depth.
#include "TestScenes.h"
#include "volrad/Transmittance.h"
#include "volrad/VoxelPyramid.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

/// 13 x 10 x 7 voxels (not powers of two), lumpy medium with an empty slab.
Scene pyramidScene()
{
  return lumpySlabScene({ 13, 10, 7 }, Vec3(0.1, 0.13, 0.2), Vec3(-0.4, 0.2, 1.0), 0, 4, 9, 5.0);
}

} // namespace

TEST(VoxelPyramid, LevelsAggregateTheirChildren)
{
  const Scene s = pyramidScene();
  const VoxelPyramid p(s, 0);
  ASSERT_EQ(p.levels(), 5); // 13 -> 7 -> 4 -> 2 -> 1
  EXPECT_EQ(p.grid(p.levels() - 1).voxelCount(), 1);
  // The root's mean times its volume is the total extinction-volume (the
  // padding past the domain is vacuum).
  double total = 0.0;
  float mx = 0.f;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    total += s.kappaTAt(v, 0) * s.grid.voxelVolume();
    mx = std::max(mx, float(s.kappaTAt(v, 0)));
  }
  const Grid& root = p.grid(p.levels() - 1);
  EXPECT_NEAR(p.meanKappaT(p.levels() - 1, 0) * root.voxelVolume(), total, 1e-5 * total);
  EXPECT_FLOAT_EQ(float(p.maxKappaT(p.levels() - 1, 0)), mx);
  EXPECT_EQ(p.minKappaT(p.levels() - 1, 0), 0.0);
  EXPECT_LT((root.lower() - s.grid.lower()).norm(), 1e-12);
}

TEST(VoxelPyramid, CoarseDepthsAreBoundedAndAdaptiveMarchingMeetsItsTolerance)
{
  const Scene s = pyramidScene();
  const VoxelPyramid p(s, 0);
  Rng rng(3);
  const Vec3 lo = s.grid.lower(), hi = s.grid.upper();
  long long adaptiveCells = 0, fineCells = 0;
  for (int r = 0; r < 300; ++r) {
    auto point = [&] {
      return Vec3(lo[0] + rng.uniform() * (hi - lo)[0],
                  lo[1] + rng.uniform() * (hi - lo)[1],
                  lo[2] + rng.uniform() * (hi - lo)[2]);
    };
    const Vec3 a = point(), b = point();
    const double exact = opticalDepth(s, 0, a, b);
    const VoxelPyramid::Depth fine = p.opticalDepth(a, b, 0);
    EXPECT_NEAR(fine.estimate, exact, 1e-6 * (1.0 + exact)); // float storage
    fineCells += fine.cellsVisited;
    for (int l = 1; l < p.levels(); ++l) {
      const VoxelPyramid::Depth d = p.opticalDepth(a, b, l);
      EXPECT_LE(d.lower, exact * (1 + 1e-6));
      EXPECT_GE(d.upper, exact * (1 - 1e-6));
    }
    for (double tol : { 1.0, 0.1, 0.01 }) {
      const VoxelPyramid::Depth d = p.opticalDepthAdaptive(a, b, tol);
      EXPECT_LE(std::abs(d.estimate - exact), tol + 1e-6 * exact) << "tolerance " << tol;
      EXPECT_LE(d.lower, exact * (1 + 1e-6));
      EXPECT_GE(d.upper, exact * (1 - 1e-6));
      if (tol == 1.0) {
        adaptiveCells += d.cellsVisited;
      }
    }
  }
  std::printf("[measured] cells visited per segment, small lumpy grid: voxel level %.1f, adaptive "
              "(tolerance 1) %.1f\n",
              double(fineCells) / 300,
              double(adaptiveCells) / 300);
}

TEST(VoxelPyramid, EmptyRegionsAreSkippedWhole)
{
  // A smooth blob in one corner column of a mostly empty 64^3 box: long
  // segments skip the empty 32^3 cells whole (heterogeneous cells of 16
  // voxels and smaller are walked voxel by voxel: setting up a walk costs
  // several voxel steps).
  Scene s = cubeScene(64);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const double r = (s.grid.voxelCentre(v) - Vec3(0.25, 0.25, 0.5)).norm();
    s.kappaA[v] = r < 0.2 ? float(20.0 * (0.2 - r)) : 0.f;
  }
  const VoxelPyramid p(s, 0);
  Rng rng(5);
  long long fine = 0, adaptive = 0;
  for (int r = 0; r < 100; ++r) {
    const Vec3 a(rng.uniform(), rng.uniform(), 0.0), b(rng.uniform(), rng.uniform(), 1.0);
    const double exact = opticalDepth(s, 0, a, b);
    fine += p.opticalDepth(a, b, 0).cellsVisited;
    const VoxelPyramid::Depth d = p.opticalDepthAdaptive(a, b, 0.01);
    EXPECT_LE(std::abs(d.estimate - exact), 0.01 + 1e-6 * exact);
    adaptive += d.cellsVisited;
  }
  std::printf("[measured] cells visited per segment, blob in a corner of 64^3: voxel level "
              "%.1f, adaptive (tolerance 0.01) %.1f\n",
              fine / 100.0,
              adaptive / 100.0);
  EXPECT_LT(adaptive, 0.7 * fine);
}

// The link oracle marches a line once for its bounds and for the lower
// bound of the part between two clusters: that part equals the lower bound
// of the sub-segment marched on its own.
TEST(VoxelPyramid, LowerBoundWithinAWindowEqualsTheSubSegmentsOwn)
{
  const Scene s = pyramidScene();
  const VoxelPyramid p(s, 0);
  Rng rng(5);
  const Vec3 lo = s.grid.lower(), hi = s.grid.upper();
  auto inside = [&] {
    return Vec3(lo[0] + rng.uniform() * (hi[0] - lo[0]),
                lo[1] + rng.uniform() * (hi[1] - lo[1]),
                lo[2] + rng.uniform() * (hi[2] - lo[2]));
  };
  for (int k = 0; k < 300; ++k) {
    const Vec3 a = inside(), b = inside();
    const double r = (b - a).norm();
    const double s0 = rng.uniform() * r, s1 = s0 + rng.uniform() * (r - s0);
    const Vec3 w = (b - a) / r;
    for (int level = 0; level < p.levels(); ++level) {
      double within = -1.0;
      const VoxelPyramid::Depth whole = p.opticalDepth(a, b, level, s0, s1, within);
      const VoxelPyramid::Depth plain = p.opticalDepth(a, b, level);
      EXPECT_DOUBLE_EQ(whole.lower, plain.lower);
      EXPECT_DOUBLE_EQ(whole.upper, plain.upper);
      const double own = p.opticalDepth(a + s0 * w, a + s1 * w, level).lower;
      EXPECT_NEAR(within, own, 1e-9 * (1.0 + own)) << "line " << k << " level " << level;
    }
  }
}
