// SPDX-License-Identifier: BSD-3-Clause
// physics.md 5.1: in a white furnace G = 4E and Q_I = E exactly, whatever
// the medium.
#include "TestScenes.h"
#include "volrad/DenseSolver.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

double maxRelativeError(const std::vector<double>& a, double expected)
{
  double worst = 0.0;
  for (double x : a)
  {
    worst = std::max(worst, std::abs(x - expected) / expected);
  }
  return worst;
}

} // namespace

TEST(WhiteFurnace, EmittingAbsorbingScatteringMediumInOpenSpace)
{
  Scene s = cubeScene(10);
  const double E = 2.5;
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.05, 30.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.0, 20.0, 1.3); });
  for (Index v = 0; v < s.grid.voxelCount(); ++v)
  {
    s.emissionI[v] = float(E);
  }
  BoundaryCondition open;
  open.radiance = uniformChannels(E / kPi);
  setAllFaces(s, open);
  const Solution sol = solveDense(s);
  const double errG = maxRelativeError(sol.G, 4.0 * E);
  const double errQ = maxRelativeError(sol.QI, E);
  std::printf("[measured] furnace 10^3: max |G/4E - 1| = %.3g, max |Q_I/E - 1| = %.3g\n", errG, errQ);
  EXPECT_LT(errG, 1e-3);
  EXPECT_LT(errQ, 1e-3);
}

TEST(WhiteFurnace, BlackEmittingWallsGiveTheSameAnswer)
{
  Scene s = cubeScene(8);
  const double E = 1.0;
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.5, 12.0, 0.4); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.0, 8.0, 2.0); });
  for (Index v = 0; v < s.grid.voxelCount(); ++v)
  {
    s.emissionI[v] = float(E);
  }
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  wall.emission = uniformChannels(E);
  setAllFaces(s, wall);
  const Solution sol = solveDense(s);
  const double errG = maxRelativeError(sol.G, 4.0 * E);
  const double errH = maxRelativeError(sol.H, E);
  std::printf("[measured] furnace with black walls 8^3: max |G/4E - 1| = %.3g, max |H/E - 1| = %.3g\n", errG, errH);
  EXPECT_LT(errG, 1e-3);
  EXPECT_LT(errH, 1e-3);
}

TEST(WhiteFurnace, PureScattering)
{
  Scene s = cubeScene(12);
  const double E = 1.0;
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.1, 40.0, 0.7); });
  BoundaryCondition open;
  open.radiance = uniformChannels(E / kPi);
  setAllFaces(s, open);
  const Solution sol = solveDense(s);
  const double errG = maxRelativeError(sol.G, 4.0 * E);
  std::printf("[measured] pure-scattering furnace 12^3: max |G/4E - 1| = %.3g\n", errG);
  EXPECT_LT(errG, 1e-3);
  // Nothing is absorbed: all that enters escapes.
  EXPECT_NEAR(sol.energy[0].escaped / sol.energy[0].enteringEnvironment, 1.0, 1e-6);
}
