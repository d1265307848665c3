// SPDX-License-Identifier: BSD-3-Clause
// A closed box of Lambertian walls with no medium: the exchange areas summed
// over whole faces are the analytic form factors of the unit cube's faces.
#include "TestScenes.h"
#include "volrad/DenseSolver.h"
#include "volrad/ExchangeAreas.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

// Two parallel unit squares at distance 1, and two perpendicular unit
// squares sharing an edge (Hottel; Howell's catalogue, C-11 and C-14).
constexpr double kParallel = 0.199825;
constexpr double kPerpendicular = 0.200044;

double faceToFace(const Scene& s, const ExchangeAreas& ex, Face a, Face b)
{
  const Grid& g = s.grid;
  double sum = 0.0;
  for (Index i = 0; i < g.facePatchCount(a); ++i) {
    for (Index j = 0; j < g.facePatchCount(b); ++j) {
      sum += ex.S(ex.elements.patchElement(g.facePatchOffset(a) + i),
                  ex.elements.patchElement(g.facePatchOffset(b) + j));
    }
  }
  return sum / g.faceArea(a);
}

} // namespace

TEST(WallEnclosure, FaceFormFactorsOfAnEmptyCube)
{
  Scene s = cubeScene(8);
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  setAllFaces(s, wall);
  const ProgressCallback none;
  const ExchangeAreas ex =
    computeExchangeAreas(s, 0, QuadratureSettings{}, {}, ProgressRange(none, 0, 1));
  const double parallel = faceToFace(s, ex, Face::ZMin, Face::ZMax);
  const double perpendicular = faceToFace(s, ex, Face::ZMin, Face::XMax);
  std::printf(
    "[measured] cube faces: parallel %.5f (exact %.5f), perpendicular %.5f (exact %.5f)\n",
    parallel,
    kParallel,
    perpendicular,
    kPerpendicular);
  EXPECT_NEAR(parallel / kParallel, 1.0, 0.01);
  EXPECT_NEAR(perpendicular / kPerpendicular, 1.0, 0.01);
}

TEST(WallEnclosure, ReflectingBoxConservesEnergy)
{
  // Emission on one face, reflectance 0.7 everywhere: every watt emitted is
  // absorbed by the walls, and the total radiosity follows from the
  // geometric series of the enclosure's reflections.
  Scene s = cubeScene(6);
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  wall.reflectance = uniformChannels(0.7);
  setAllFaces(s, wall);
  s.boundary[static_cast<int>(Face::ZMin)].emission = uniformChannels(1.0);
  const Solution sol = solveDense(s);
  const EnergyTerms& e = sol.energy[0];
  EXPECT_NEAR(e.emittedWalls, 1.0, 1e-12);
  EXPECT_NEAR(e.absorbedWalls / e.emittedWalls, 1.0, 1e-9);
  // In a closed uniform-rho enclosure: sum A H = sum A B (all light lands on
  // walls), and sum A B = emitted + rho sum A H, so sum A H = E/(1-rho).
  double totalH = 0.0;
  for (Index p = 0; p < s.grid.patchCount(); ++p) {
    totalH += sol.H[p] * s.grid.patchArea(s.grid.patchLocation(p).face);
  }
  EXPECT_NEAR(totalH, 1.0 / 0.3, 1e-8);
}
