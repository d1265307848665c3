// SPDX-License-Identifier: BSD-3-Clause
// Exact voxel traversal: lengths against ray-box chords computed directly.
#include "TestScenes.h"
#include "volrad/Transmittance.h"
#include "volrad/VoxelTraversal.h"

#include <gtest/gtest.h>

#include <limits>

using namespace volrad;

TEST(Traversal, LengthsAddUpToTheChordAndStayInTheirVoxels)
{
  Grid g;
  g.dims = { 7, 5, 9 };
  g.spacing = Vec3(0.3, 0.7, 0.2);
  g.origin = Vec3(-1.0, 2.0, 0.5);
  Rng rng(42);
  const Vec3 lo = g.lower(), hi = g.upper();
  for (int r = 0; r < 2000; ++r) {
    const Vec3 o = lo + Vec3(rng.uniform() * (hi - lo)[0],
                             rng.uniform() * (hi - lo)[1],
                             rng.uniform() * (hi - lo)[2]);
    const Vec3 d = sampleSphere(rng);
    double t0, t1;
    ASSERT_TRUE(clipToDomain(g, o, d, t0, t1));
    double total = 0.0;
    const DomainExit exit = traverseVoxels(
      g, o, d, std::numeric_limits<double>::infinity(), [&](Index v, double l, double tStart) {
        // The midpoint of every piece lies in the voxel reported for it.
        const Vec3 mid = o + d * (tStart + 0.5 * l);
        const Vec3 vl = g.voxelLower(v);
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(mid[a], vl[a] - 1e-9);
          EXPECT_LE(mid[a], vl[a] + g.spacing[a] + 1e-9);
        }
        total += l;
        return true;
      });
    ASSERT_TRUE(exit.exited);
    EXPECT_NEAR(total, t1, 1e-9);
    EXPECT_NEAR(exit.t, t1, 1e-9);
    // The exit patch contains the exit point.
    const Vec3 x = o + d * exit.t;
    const Vec3 pl = g.patchLower(exit.patch);
    const auto ax = faceAxesInPlane(exit.face);
    EXPECT_NEAR(x[faceAxis(exit.face)], pl[faceAxis(exit.face)], 1e-9);
    for (int a : ax) {
      EXPECT_GE(x[a], pl[a] - 1e-9);
      EXPECT_LE(x[a], pl[a] + g.spacing[a] + 1e-9);
    }
  }
}

TEST(Traversal, RayFromOutsideStartsAtTheBoundaryAndStopsAtTMax)
{
  Grid g;
  g.dims = { 4, 4, 4 };
  g.origin = Vec3::Constant(0.5);
  const Vec3 o(-3.0, 1.5, 2.5);
  const Vec3 d(1.0, 0.0, 0.0);
  std::vector<Index> seen;
  double total = 0.0;
  const DomainExit exit = traverseVoxels(g, o, d, 5.5, [&](Index v, double l, double) {
    seen.push_back(v);
    total += l;
    return true;
  });
  EXPECT_FALSE(exit.exited);
  EXPECT_NEAR(total, 2.5, 1e-12); // enters at t = 3, stops at t = 5.5
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], g.index(0, 1, 2));
  EXPECT_EQ(seen[2], g.index(2, 1, 2));
}

TEST(Traversal, MissingRayVisitsNothing)
{
  Grid g;
  g.dims = { 3, 3, 3 };
  int visits = 0;
  const DomainExit exit = traverseVoxels(
    g, Vec3(5, 5, 5), Vec3(1, 0, 0), 1e9, [&](Index, double, double) { return ++visits > 0; });
  EXPECT_FALSE(exit.exited);
  EXPECT_EQ(visits, 0);
}

TEST(Transmittance, HomogeneousAndLayeredMediaMatchBeersLaw)
{
  Scene s = test::cubeScene(10);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    // Two layers: kappa = 2 below z = 0.5, 7 above.
    s.kappaA[v] = s.grid.voxelCentre(v)[2] < 0.5 ? 1.5f : 5.0f;
    s.sigmaI[v] = s.grid.voxelCentre(v)[2] < 0.5 ? 0.5f : 2.0f;
  }
  Rng rng(7);
  for (int r = 0; r < 200; ++r) {
    // Segments from anywhere (also outside the cube) to anywhere.
    const Vec3 a(rng.uniform() * 1.6 - 0.3, rng.uniform() * 1.6 - 0.3, rng.uniform() * 1.6 - 0.3);
    const Vec3 b(rng.uniform() * 1.6 - 0.3, rng.uniform() * 1.6 - 0.3, rng.uniform() * 1.6 - 0.3);
    // Reference: clip to the cube, split at z = 0.5, lengths times kappa.
    double expected = 0.0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i) {
      const Vec3 x = a + (b - a) * ((i + 0.5) / steps);
      if ((x.array() >= 0.0).all() && (x.array() <= 1.0).all()) {
        expected += (x[2] < 0.5 ? 2.0 : 7.0) * (b - a).norm() / steps;
      }
    }
    EXPECT_NEAR(opticalDepth(s, 0, a, b), expected, 1e-4 * (1.0 + expected));
  }
  EXPECT_NEAR(transmittance(s, 0, Vec3(0.5, 0.5, 0.0), Vec3(0.5, 0.5, 1.0)),
              std::exp(-(2.0 * 0.5 + 7.0 * 0.5)),
              1e-12);
}
