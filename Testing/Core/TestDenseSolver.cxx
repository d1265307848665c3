// SPDX-License-Identifier: BSD-3-Clause
// The dense solver's contract: energy balance, size limit, abort, channels.
#include "TestScenes.h"
#include "volrad/DenseSolver.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

TEST(DenseSolver, EnergyBalanceClosesWithEverythingSwitchedOn)
{
  Scene s = cubeScene(7, 3);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    for (int c = 0; c < 3; ++c) {
      s.kappaA[v * 3 + c] = float(lumpy(x, 0.1, 3.0, c));
      s.sigmaI[v * 3 + c] = float(lumpy(x, 0.0, 5.0, 1.0 + c));
      s.sigmaD[v * 3 + c] = float(lumpy(x, 0.0, 3.0, 2.0 + c));
      s.emissionI[v * 3 + c] = float(lumpy(x, 0.0, 1.0, 3.0));
      s.emissionD[v * 3 + c] = float(lumpy(x, 0.0, 1.0, 4.0));
    }
  }
  radialNormals(s);
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  wall.reflectance = { 0.2, 0.5, 0.8 };
  wall.emission = { 0.1, 0.0, 0.3 };
  s.boundary[0] = wall;
  s.boundary[3] = wall;
  s.boundary[4].radiance = { 0.1, 0.2, 0.3 };
  s.directionalLights.push_back({ Vec3(0.2, 0.3, -1.0), { 1.0, 2.0, 3.0 } });
  s.pointLights.push_back({ Vec3(0.5, 0.5, 0.5), { 0.1, 0.1, 0.1 } });
  s.pointLights.push_back({ Vec3(3.0, 0.5, 0.5), { 1.0, 1.0, 1.0 } }); // outside, through xmax
  const Solution sol = solveDense(s);
  for (int c = 0; c < 3; ++c) {
    const EnergyTerms& e = sol.energy[c];
    std::printf("[measured] energy balance channel %d: emitted %.6g removed %.6g residual %.3g\n",
                c,
                e.emitted(),
                e.removed(),
                e.relativeResidual());
    EXPECT_LT(e.relativeResidual(), 1e-6);
    EXPECT_GT(e.enteringLights, 0.0);
    EXPECT_GT(e.absorbedWalls, 0.0);
    EXPECT_GT(e.escaped, 0.0);
  }
  for (std::size_t i = 0; i < sol.G.size(); ++i) {
    ASSERT_GE(sol.G[i], 0.0);
    ASSERT_LE(sol.Gplus[i], sol.G[i] * (1 + 1e-12));
  }
}

TEST(DenseSolver, DirectLightAloneFollowsBeersLaw)
{
  // A column along z lit from above: G in each voxel is the mean of
  // E exp(-kappa z) over the voxel, (E/kappa h)(e^{-kappa z0} - e^{-kappa z1}).
  Scene s;
  s.grid.dims = { 1, 1, 10 };
  s.grid.spacing = Vec3(1.0, 1.0, 0.1);
  s.allocate();
  const double kappa = 3.0;
  for (auto& k : s.kappaA) {
    k = float(kappa);
  }
  s.directionalLights.push_back({ Vec3(0, 0, -1), uniformChannels(2.0) });
  const Solution sol = solveDense(s);
  const double top = s.grid.upper()[2];
  for (int k = 0; k < 10; ++k) {
    const double z1 = top - s.grid.voxelLower(k)[2], z0 = z1 - 0.1;
    const double expected = 2.0 / (kappa * 0.1) * (std::exp(-kappa * z0) - std::exp(-kappa * z1));
    // Direct part is exact; the emission of the medium is zero, so G is direct only.
    EXPECT_NEAR(sol.G[k], expected, 1e-9 * expected) << "voxel " << k;
  }
}

TEST(DenseSolver, RefusesTooLargeGridsBeforeAllocating)
{
  Scene s = cubeScene(1);
  s.grid.dims = { 200, 200, 200 };
  s.allocate();
  for (auto& k : s.kappaA) {
    k = 1.0f;
  }
  try {
    solveDense(s);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dense solver would need"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hierarchical"), std::string::npos) << e.what();
  }
}

TEST(DenseSolver, AbortsWhenProgressSaysStop)
{
  Scene s = cubeScene(6);
  for (auto& k : s.kappaA) {
    k = 1.0f;
  }
  DenseSolverOptions o;
  int calls = 0;
  o.progress = [&](double) { return ++calls < 3; };
  EXPECT_THROW(solveDense(s, o), Aborted);
  // And it runs to the end otherwise, reporting monotone progress up to 1.
  double last = -1.0;
  bool monotone = true;
  o.progress = [&](double f) {
    monotone = monotone && f >= last - 1e-12;
    last = f;
    return true;
  };
  solveDense(s, o);
  EXPECT_TRUE(monotone);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

TEST(DenseSolver, SingleThreadedRunsAreBitIdentical)
{
  Scene s = cubeScene(5);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.1, 3.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.1, 3.0, 1.0); });
  s.directionalLights.push_back({});
  DenseSolverOptions o;
  o.threads = 1;
  const Solution a = solveDense(s, o);
  const Solution b = solveDense(s, o);
  EXPECT_EQ(a.G, b.G);
  o.threads = 0;
  const Solution c = solveDense(s, o);
  for (std::size_t i = 0; i < a.G.size(); ++i) {
    EXPECT_NEAR(c.G[i], a.G[i], 1e-9 * a.G[i]);
  }
}
