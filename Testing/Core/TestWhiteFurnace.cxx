// SPDX-License-Identifier: BSD-3-Clause
// physics.md 5.1: in a white furnace G = 4E and Q_I = E exactly, whatever
// the medium.
#include "TestScenes.h"
#include "volrad/DenseSolver.h"
#include "volrad/HierarchicalSolver.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

/// Emission E in every voxel of a medium with the given absorption and scattering.
template<class FA, class FS>
void emittingMedium(Scene& s, double E, FA kappaA, FS sigmaI)
{
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    s.kappaA[v] = float(kappaA(x));
    s.sigmaI[v] = float(sigmaI(x));
    s.emissionI[v] = float(E);
  }
}

double maxRelativeError(const std::vector<double>& a, double expected)
{
  double worst = 0.0;
  for (double x : a) {
    worst = std::max(worst, std::abs(x - expected) / expected);
  }
  return worst;
}

/// Solves s with both solvers and checks G = 4E and that `field` (Q_I or
/// H) equals E: to 1e-3 for the dense solver, 0.5% for the hierarchical one.
void expectFurnace(const char* name, const Scene& s, double E, std::vector<double> Solution::*field)
{
  for (const bool dense : { true, false }) {
    HierarchicalOptions ho;
    const Solution sol = dense ? solveDense(s) : solveHierarchical(s, ho);
    const double errG = maxRelativeError(sol.G, 4.0 * E);
    const double errField = maxRelativeError(sol.*field, E);
    std::printf("[measured] %s (%s): max |G/4E - 1| = %.3g, max |field/E - 1| = %.3g\n",
                name,
                sol.stats.method.c_str(),
                errG,
                errField);
    EXPECT_LT(errG, dense ? 1e-3 : 5e-3) << sol.stats.method;
    EXPECT_LT(errField, dense ? 1e-3 : 5e-3) << sol.stats.method;
  }
}

} // namespace

TEST(WhiteFurnace, EmittingAbsorbingScatteringMediumInOpenSpace)
{
  Scene s = cubeScene(10);
  const double E = 2.5;
  emittingMedium(
    s,
    E,
    [](const Vec3& x) { return lumpy(x, 0.05, 30.0); },
    [](const Vec3& x) { return lumpy(x, 0.0, 20.0, 1.3); });
  BoundaryCondition open;
  open.radiance = uniformChannels(E / kPi);
  setAllFaces(s, open);
  expectFurnace("furnace 10^3, open faces (field Q_I)", s, E, &Solution::QI);
}

TEST(WhiteFurnace, BlackEmittingWallsGiveTheSameAnswer)
{
  Scene s = cubeScene(8);
  const double E = 1.0;
  emittingMedium(
    s,
    E,
    [](const Vec3& x) { return lumpy(x, 0.5, 12.0, 0.4); },
    [](const Vec3& x) { return lumpy(x, 0.0, 8.0, 2.0); });
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  wall.emission = uniformChannels(E);
  setAllFaces(s, wall);
  expectFurnace("furnace 8^3, black emitting walls (field H)", s, E, &Solution::H);
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
