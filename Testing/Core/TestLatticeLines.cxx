// SPDX-License-Identifier: BSD-3-Clause
// LatticeLines: the optical depth of lines between voxels, summed from walks
// made once per lattice offset, against sampling the medium along the line
// and against the exact traversal of the line where it lies.
#include "TestScenes.h"
#include "volrad/LatticeLines.h"
#include "volrad/Sampling.h"
#include "volrad/Transmittance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace volrad;
using namespace volrad::test;

namespace {

/// 23 x 17 x 19 voxels of unequal spacing, lumpy, with an empty slab.
Scene latticeScene()
{
  return lumpySlabScene({ 23, 17, 19 }, Vec3(0.1, 0.13, 0.08), Vec3(-0.4, 0.2, 1.0), 1, 6, 9, 6.0);
}

/// Integral of kappa_t along a -> b by the midpoint rule: independent of any
/// voxel walk (a piecewise-constant medium: error under crossings times a
/// sample's share).
double sampledDepth(const Scene& s, const Vec3& a, const Vec3& b, int samples)
{
  const Grid& g = s.grid;
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 x = a + (b - a) * ((i + 0.5) / samples);
    std::array<int, 3> ijk;
    for (int k = 0; k < 3; ++k) {
      ijk[k] = std::clamp(int(std::floor((x[k] - g.lower()[k]) / g.spacing[k])), 0, g.dims[k] - 1);
    }
    sum += s.kappaTAt(g.index(ijk[0], ijk[1], ijk[2]), 0);
  }
  return sum * (b - a).norm() / samples;
}

} // namespace

TEST(LatticeLines, DepthsMatchSamplingAndTheExactWalkForAnyPlaceOfThePair)
{
  const Scene s = latticeScene();
  const Grid& g = s.grid;
  // Shifted lines (the close links' Gauss points) and the centre line.
  const std::vector<Vec3> shifts = { Vec3::Zero(),
                                     Vec3(0.28, -0.28, 0.28).cwiseProduct(g.spacing),
                                     Vec3(-0.41, 0.07, -0.33).cwiseProduct(g.spacing) };
  const int reach = 6;
  const LatticeLines lines(g, reach, shifts);
  const auto kappa = [&](Index v) { return s.kappaTAt(v, 0); };
  Rng rng(11);
  int compared = 0;
  double worstSampled = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    std::array<int, 3> ia, d;
    for (int k = 0; k < 3; ++k) {
      d[k] = int(std::floor(rng.uniform() * (2 * reach + 1))) - reach;
      const int lo = std::max(0, -d[k]), hi = std::min(g.dims[k], g.dims[k] - d[k]);
      ia[k] = lo + int(std::floor(rng.uniform() * (hi - lo)));
    }
    ASSERT_TRUE(lines.covers(d[0], d[1], d[2]));
    const Index a = g.index(ia[0], ia[1], ia[2]);
    const Vec3 ca = g.voxelCentre(a);
    const Vec3 cb = g.voxelCentre(g.index(ia[0] + d[0], ia[1] + d[1], ia[2] + d[2]));
    for (int line = 0; line < int(shifts.size()); ++line) {
      const double table = lines.depth(kappa, a, d[0], d[1], d[2], line);
      const Vec3 p = ca + shifts[line], q = cb + shifts[line];
      const double exact = opticalDepth(s, 0, p, q);
      EXPECT_NEAR(table, exact, 1e-6 * (1.0 + exact)) << "line " << line << " offset " << d[0]
                                                      << "," << d[1] << "," << d[2];
      const double sampled = sampledDepth(s, p, q, 20000);
      EXPECT_NEAR(table, sampled, 2e-3 * (1.0 + sampled));
      worstSampled = std::max(worstSampled, std::abs(table - sampled) / (1.0 + sampled));
      ++compared;
    }
  }
  std::printf("[measured] lattice lines: %d depths, largest difference from 20000-point "
              "sampling %.2e (relative)\n",
              compared,
              worstSampled);
}

TEST(LatticeLines, ReachStopsAtTheGridAndCoversOnlyItsOffsets)
{
  Grid g;
  g.dims = { 4, 9, 3 };
  const LatticeLines lines(g, 16, { Vec3::Zero() });
  EXPECT_TRUE(lines.covers(8, -8, 8)); // the largest extent less one
  EXPECT_FALSE(lines.covers(9, 0, 0));
  EXPECT_FALSE(lines.covers(0, 0, -9));
  // The voxel itself: no line, no depth.
  EXPECT_EQ(lines.depth([](Index) { return 1.0; }, 0, 0, 0, 0, 0), 0.0);
  // Along an axis in a uniform medium: kappa times the distance.
  EXPECT_NEAR(lines.depth([](Index) { return 2.0; }, 0, 3, 0, 0, 0), 2.0 * 3.0 * g.spacing[0], 1e-6);
}
