// SPDX-License-Identifier: BSD-3-Clause
// The near field is the dense solver's own quadrature cut at the
// neighbourhood box: its values are the dense raw rows' values there, and
// near + far adds up to the whole row.
#include "TestScenes.h"
#include "volrad/NearField.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

TEST(NearField, EqualsTheDenseRowsInsideTheBoxAndConservesTheRest)
{
  Scene s = cubeScene(8);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.0, 6.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.0, 9.0, 0.8); });
  s.boundary[static_cast<int>(Face::ZMin)].type = BoundaryCondition::Type::Wall;
  const ProgressCallback none;
  ExchangeOptions raw;
  raw.symmetrize = false;
  const ExchangeAreas dense =
    computeExchangeAreas(s, 0, QuadratureSettings{}, raw, ProgressRange(none, 0, 1));
  const int r = 2;
  const NearField near = computeNearField(s, 0, QuadratureSettings{}, r);
  const auto& el = dense.elements;
  double worstValue = 0.0, worstSum = 0.0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    if (el.full[v] < 0) {
      continue;
    }
    const auto c = s.grid.ijk(v);
    const double target = exchangeRowTarget(s, 0, el, el.full[v]);
    double nearSum = near.far[v];
    for (int dz = -r; dz <= r; ++dz) {
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const int i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
          const double value = near.value(v, dx, dy, dz);
          nearSum += value;
          if (i < 0 || j < 0 || k < 0 || i >= 8 || j >= 8 || k >= 8 ||
              el.full[s.grid.index(i, j, k)] < 0) {
            EXPECT_EQ(value, 0.0);
            continue;
          }
          const double expected = dense.S(el.full[v], el.full[s.grid.index(i, j, k)]);
          worstValue = std::max(worstValue, std::abs(value - expected) / target);
        }
      }
    }
    for (const auto& [patch, value] : near.patches[v]) {
      nearSum += value;
      EXPECT_LE(value, dense.S(el.full[v], el.patchElement(patch)) * (1 + 1e-12));
    }
    const double denseSum = dense.S.row(el.full[v]).head(el.partitionSize()).sum();
    worstSum = std::max(worstSum, std::abs(nearSum - denseSum) / target);
  }
  std::printf("[measured] near field (radius 2) vs dense rows: worst value diff %.2g, worst "
              "row-sum diff %.2g "
              "(relative to 4 kappa_t V)\n",
              worstValue,
              worstSum);
  EXPECT_LT(worstValue, 1e-9);
  EXPECT_LT(worstSum, 1e-9);
}

TEST(NearField, RefusesFrontSidesForNow)
{
  Scene s = cubeScene(4);
  radialNormals(s);
  for (auto& x : s.sigmaD) {
    x = 1.f;
  }
  for (auto& x : s.kappaA) {
    x = 1.f;
  }
  EXPECT_THROW(computeNearField(s, 0, QuadratureSettings{}, 1), Error);
}
