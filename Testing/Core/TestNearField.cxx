// SPDX-License-Identifier: BSD-3-Clause
// The near field is the dense solver's own quadrature cut at the
// neighbourhood box: its values are the dense symmetric values there, and
// near + far adds up to every element's whole row.
#include "TestScenes.h"
#include "volrad/NearField.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>

using namespace volrad;
using namespace volrad::test;

namespace {

Scene heterogeneousWithEverything(int n)
{
  Scene s = cubeScene(n);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.0, 6.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.0, 9.0, 0.8); });
  radialNormals(s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v) - Vec3::Constant(0.5);
    s.sigmaD[v] = x.norm() > 0.3 ? 4.f : 0.f; // a shell of surface-like voxels
    if (v % 7 == 0) {
      s.kappaA[v] = s.sigmaI[v] = s.sigmaD[v] = 0.f; // scattered empty voxels
    }
  }
  s.boundary[static_cast<int>(Face::ZMin)].type = BoundaryCondition::Type::Wall;
  return s;
}

} // namespace

TEST(NearField, EqualsTheDenseValuesInsideTheBoxAndConservesEveryRow)
{
  const Scene s = heterogeneousWithEverything(8);
  ExchangeOptions symmetricOnly;
  symmetricOnly.smooth = false;
  const ExchangeAreas dense =
    computeExchangeAreas(s, 0, QuadratureSettings{}, symmetricOnly, ProgressRange());
  NearFieldOptions opt;
  opt.radius = 2;
  opt.reuseHomogeneous = false;
  const NearField near = computeNearField(s, 0, opt);
  const auto& el = dense.elements;
  ASSERT_EQ(el.size(), near.elements.size());
  ASSERT_GT(el.frontCount, 0);
  const Grid& g = s.grid;
  auto voxelOf = [&](Index e) {
    return el.isPatch(e) ? g.patchVoxel(e - el.fullCount) : el.voxelOf[e];
  };
  auto chebyshev = [&](Index a, Index b) {
    const auto p = g.ijk(voxelOf(a)), q = g.ijk(voxelOf(b));
    return std::max({ std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2]) });
  };
  // Near rows as a dense matrix.
  const Index n = el.size();
  RowMatrix N = RowMatrix::Zero(n, n);
  for (Index e = 0; e < n; ++e) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(n);
    unit[e] = 1.0;
    Eigen::VectorXd col = Eigen::VectorXd::Zero(n);
    near.apply(g, unit.data(), col.data(), false);
    N.col(e) = col;
  }
  double worstValue = 0.0, worstSum = 0.0, worstSymmetry = 0.0;
  for (Index a = 0; a < n; ++a) {
    const double target = exchangeRowTarget(s, 0, el, a);
    double nearSum = near.far[a];
    for (Index b = 0; b < n; ++b) {
      if (chebyshev(a, b) > opt.radius) {
        EXPECT_EQ(N(a, b), 0.0);
        continue;
      }
      worstValue = std::max(worstValue, std::abs(N(a, b) - dense.S(a, b)) / target);
      worstSymmetry = std::max(worstSymmetry, std::abs(N(a, b) - N(b, a)) / target);
      if (!el.isFront(b)) {
        nearSum += N(a, b);
      }
    }
    if (near.far[a] > 0.0) { // not clamped
      worstSum = std::max(worstSum, std::abs(nearSum - target) / target);
    }
  }
  std::printf("[measured] near field (radius 2; full, front and patch rows) vs dense: worst value "
              "diff %.2g, worst |near + far - target| %.2g, worst asymmetry %.2g (relative to the "
              "row target)\n",
              worstValue,
              worstSum,
              worstSymmetry);
  EXPECT_LT(worstValue, 1e-6); // float storage
  EXPECT_LT(worstSum, 1e-5);
  EXPECT_LT(worstSymmetry, 1e-7);
}

TEST(NearField, SharedHomogeneousRowsMatchTheirOwnQuadrature)
{
  Scene s = cubeScene(7);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    s.kappaA[v] = 2.f;
    s.sigmaI[v] = s.grid.ijk(v)[0] < 5 ? 10.f : 3.f; // two materials
  }
  NearFieldOptions own;
  own.reuseHomogeneous = false;
  own.quadrature = own.homogeneousQuadrature;
  const NearField a = computeNearField(s, 0, own);
  const NearField b = computeNearField(s, 0, NearFieldOptions{});
  double worst = 0.0;
  int shared = 0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const auto c = s.grid.ijk(v);
    const bool interior =
      c[0] >= 2 && c[0] <= 3 && c[1] >= 2 && c[1] <= 4 && c[2] >= 2 && c[2] <= 4;
    shared += interior;
    const double target = 4.0 * s.kappaTAt(v, 0) * s.grid.voxelVolume();
    const Index e = a.elements.full[v]; // rows are per element
    ASSERT_GE(e, 0);
    for (int o = 0; o < a.stencilSize(); ++o) {
      worst = std::max(
        worst, std::abs(a.stencilEntry(s.grid, e, o) - b.stencilEntry(s.grid, e, o)) / target);
    }
    EXPECT_NEAR(a.far[e], b.far[e], 2e-2 * target); // default-quadrature noise in b
  }
  std::printf("[measured] shared homogeneous near rows vs each voxel's own quadrature: worst "
              "difference %.2g of 4 kappa_t V over %d shared voxels\n",
              worst,
              shared);
  EXPECT_GT(shared, 0);
  EXPECT_LT(worst, 3e-2); // the neighbours' own rows are coarser in b
}

// Rows shared by class along the walls: a voxel's patch entries, a patch's
// row and an empty voxel's view, translated from the class's first member,
// match each one's own quadrature (a wrong translation would put a wall's
// light on another patch).
TEST(NearField, RowsSharedAlongTheWallsMatchTheirOwnQuadrature)
{
  Scene s; // not a cube, so that a translation mixing up the axes shows
  s.grid.dims = { 7, 6, 5 };
  s.grid.spacing = Vec3(0.1, 0.12, 0.15);
  s.grid.origin = 0.5 * s.grid.spacing;
  s.allocate();
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    // The rest empty, two layers of it without medium near.
    const bool medium = s.grid.ijk(v)[0] < 4;
    s.kappaA[v] = medium ? 2.f : 0.f;
    s.sigmaI[v] = medium ? 6.f : 0.f;
  }
  NearFieldOptions own;
  own.reuseHomogeneous = false;
  own.quadrature = own.homogeneousQuadrature;
  NearFieldOptions sharing = own; // the same quadrature: only the sharing differs
  sharing.reuseHomogeneous = true;
  const NearField a = computeNearField(s, 0, own);
  const NearField b = computeNearField(s, 0, sharing);
  const Grid& g = s.grid;
  const ExchangeElements& el = a.elements;
  auto rowOf = [](const std::vector<Index>& start,
                  const std::vector<NearField::Column>& column,
                  const std::vector<float>& value,
                  Index r) {
    std::map<std::int64_t, double> row;
    for (Index k = start[r]; k < start[r + 1]; ++k) {
      row[column[k]] += value[k];
    }
    return row;
  };
  auto difference = [](const std::map<std::int64_t, double>& x,
                       const std::map<std::int64_t, double>& y) {
    double worst = 0.0;
    for (const auto& [c, v] : x) {
      const auto it = y.find(c);
      worst = std::max(worst, std::abs(v - (it == y.end() ? 0.0 : it->second)));
    }
    for (const auto& [c, v] : y) {
      if (x.find(c) == x.end()) {
        worst = std::max(worst, std::abs(v));
      }
    }
    return worst;
  };
  double worstElement = 0.0, worstView = 0.0;
  int compared = 0, views = 0;
  for (Index e = 0; e < el.partitionSize(); ++e) {
    const double target = el.isPatch(e) ? g.patchArea(g.patchLocation(e - el.fullCount).face)
                                        : 4.0 * s.kappaTAt(el.voxelOf[e], 0) * g.voxelVolume();
    const auto x = rowOf(a.extraStart, a.extraColumn, a.extraValue, e);
    compared += !x.empty();
    worstElement = std::max(
      worstElement, difference(x, rowOf(b.extraStart, b.extraColumn, b.extraValue, e)) / target);
  }
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const auto x = rowOf(a.views.start, a.views.column, a.views.value, v);
    double sum = 0.0;
    for (const auto& [c, w] : x) {
      sum += w;
    }
    if (sum > 0.0) {
      ++views;
      worstView =
        std::max(worstView, difference(x, rowOf(b.views.start, b.views.column, b.views.value, v)) / sum);
    }
  }
  std::printf("[measured] rows shared along the walls vs each one's own quadrature: worst "
              "difference %.2g of the row target over %d patch and voxel rows, %.2g of the "
              "row sum over %d views\n",
              worstElement,
              compared,
              worstView,
              views);
  EXPECT_GT(compared, 0);
  EXPECT_GT(views, 0);
  EXPECT_GT(worstElement, 0.0); // rows were shared (the same rows otherwise)
  EXPECT_GT(worstView, 0.0);
  EXPECT_LT(worstElement, 2e-2); // quadrature noise
  EXPECT_LT(worstView, 2e-2);
}

// Issue 6's sparse solve: without the empty voxels' views the near field
// has no view rows at all, and its element rows (kept per element, so empty
// voxels cost none) are the same.
TEST(NearField, WithoutEmptyViewsEmptySpaceCostsNothing)
{
  Scene s = cubeScene(6);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    if (s.grid.ijk(v)[0] < 3) { // the other half is empty
      s.kappaA[v] = 1.f;
      s.sigmaI[v] = 4.f;
    }
  }
  const NearField with = computeNearField(s, 0, NearFieldOptions{});
  NearFieldOptions sparse;
  sparse.emptyViews = false;
  const NearField without = computeNearField(s, 0, sparse);
  EXPECT_GT(with.views.column.size(), 0u); // the empty voxels next to the medium see it
  EXPECT_EQ(without.views.column.size(), 0u);
  EXPECT_EQ(without.stencil.size(),
            std::size_t(without.elements.fullCount) * without.stencilHalf());
  EXPECT_EQ(without.elements.fullCount, s.grid.voxelCount() / 2);
  EXPECT_EQ(without.stencil, with.stencil);
  EXPECT_EQ(without.extraValue, with.extraValue);
  EXPECT_EQ(without.far, with.far);
  EXPECT_LT(without.bytes(), with.bytes());
  // The views on their own (a solve computes them after its links) are the
  // near field's.
  const ViewRows alone = computeViewRows(s, 0, without.elements, sparse);
  EXPECT_EQ(alone.start, with.views.start);
  EXPECT_EQ(alone.column, with.views.column);
  EXPECT_EQ(alone.value, with.views.value);
  EXPECT_THROW(computeViewRows(cubeScene(4), 0, without.elements, sparse), Error);

}
