// SPDX-License-Identifier: BSD-3-Clause
// Exchange factors: reciprocity of the raw ray quadrature (each row is
// integrated independently of its mirror), exact conservation after
// smoothing, and values against direct integration of physics.md section 4.
#include "TestScenes.h"
#include "volrad/ExchangeAreas.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

Scene heterogeneousScene(int n)
{
  Scene s = cubeScene(n);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.2, 6.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.0, 4.0, 1.1); });
  return s;
}

const ProgressCallback noProgress;

} // namespace

TEST(ExchangeAreas, RawQuadratureIsReciprocal)
{
  const Scene s = heterogeneousScene(6);
  ExchangeOptions raw;
  raw.symmetrize = false;
  const ExchangeAreas ex =
    computeExchangeAreas(s, 0, QuadratureSettings{}, raw, ProgressRange(noProgress, 0, 1));
  const auto& el = ex.elements;
  // Face neighbours: S(i, j) from i's rays against S(j, i) from j's rays.
  double worstNeighbour = 0.0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const auto c = s.grid.ijk(v);
    if (c[0] + 1 < s.grid.dims[0]) {
      const Index i = el.full[v], j = el.full[s.grid.index(c[0] + 1, c[1], c[2])];
      worstNeighbour = std::max(worstNeighbour, std::abs(ex.S(i, j) / ex.S(j, i) - 1.0));
    }
  }
  // Every column sum (what all others' rays send to i) against i's row sum.
  double worstColumn = 0.0;
  for (Index i = 0; i < el.partitionSize(); ++i) {
    const double row = ex.S.row(i).head(el.partitionSize()).sum();
    const double col = ex.S.col(i).head(el.partitionSize()).sum();
    worstColumn = std::max(worstColumn, std::abs(col / row - 1.0));
  }
  std::printf(
    "[measured] raw reciprocity 6^3: face neighbours max %.3g, column vs row sums max %.3g\n",
    worstNeighbour,
    worstColumn);
  // Single pairs carry a few thousand rays (a few per cent of noise); whole
  // columns, integrated by every other element's rays, agree closer.
  EXPECT_LT(worstNeighbour, 0.25);
  EXPECT_LT(worstColumn, 0.06);
}

TEST(ExchangeAreas, SmoothedAreasAreSymmetricAndConserve)
{
  Scene s = heterogeneousScene(6);
  radialNormals(s);
  fill(s, s.sigmaD, 0, [](const Vec3& x) { return lumpy(x, 0.1, 3.0, 2.2); });
  const ExchangeAreas ex =
    computeExchangeAreas(s, 0, QuadratureSettings{}, {}, ProgressRange(noProgress, 0, 1));
  const auto& el = ex.elements;
  EXPECT_EQ(el.frontCount, s.grid.voxelCount());
  EXPECT_DOUBLE_EQ((ex.S - ex.S.transpose()).cwiseAbs().maxCoeff(), 0.0);
  for (Index e = 0; e < el.size(); ++e) {
    const double target = exchangeRowTarget(s, 0, el, e);
    EXPECT_NEAR(ex.S.row(e).head(el.partitionSize()).sum(), target, 1e-10 * target)
      << "element " << e;
  }
  EXPECT_GT(ex.S.minCoeff(), -1e-15);
  std::printf("[measured] smoothing: largest relative correction %.3g\n", ex.quadratureError);
  EXPECT_LT(ex.quadratureError, 0.1);
  // A front side cannot send light into its own front.
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    EXPECT_EQ(ex.S(el.front[v], el.front[v]), 0.0);
  }
}

TEST(ExchangeAreas, MatchDirectIntegrationOfTheVolumeKernel)
{
  // A thin homogeneous medium: the exchange area of two voxels two
  // apart (one voxel between them) against (1/pi) int int kappa^2 tau / r^2
  // dV dV by 6^3 x 6^3 Gauss-Legendre points. Single far pairs carry few
  // rays, so the mean over every such pair of a 10^3 grid is compared.
  Scene s = cubeScene(10);
  const double h = s.grid.spacing[0];
  const double kappa = 0.5;
  for (auto& k : s.kappaA) {
    k = float(kappa);
  }
  const ExchangeAreas ex =
    computeExchangeAreas(s, 0, QuadratureSettings{}, {}, ProgressRange(noProgress, 0, 1));
  const double xg[6] = { 0.033765242898424, 0.169395306766868, 0.380690406958402,
                         0.619309593041598, 0.830604693233132, 0.966234757101576 };
  const double wg[6] = { 0.085662246189585, 0.180380786524069, 0.233956967286346,
                         0.233956967286346, 0.180380786524069, 0.085662246189585 };
  double ref = 0.0;
  for (int a = 0; a < 216; ++a) {
    const Vec3 y = h * Vec3(xg[a % 6], xg[(a / 6) % 6], xg[a / 36]);
    const double wa = wg[a % 6] * wg[(a / 6) % 6] * wg[a / 36];
    for (int b = 0; b < 216; ++b) {
      const Vec3 x = h * Vec3(2.0 + xg[b % 6], xg[(b / 6) % 6], xg[b / 36]);
      const double r = (x - y).norm();
      ref += wa * wg[b % 6] * wg[(b / 6) % 6] * wg[b / 36] * kappa * kappa * std::exp(-kappa * r) /
             (kPi * r * r);
    }
  }
  ref *= std::pow(h, 6);
  double sum = 0.0;
  int pairs = 0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const auto c = s.grid.ijk(v);
    if (c[0] + 2 < s.grid.dims[0]) {
      sum += ex.S(ex.elements.full[v], ex.elements.full[s.grid.index(c[0] + 2, c[1], c[2])]);
      ++pairs;
    }
  }
  const double got = sum / pairs;
  std::printf("[measured] S at offset (2,0,0), mean of %d pairs: %.6g vs direct integration %.6g "
              "(rel. err %.3g)\n",
              pairs,
              got,
              ref,
              got / ref - 1.0);
  EXPECT_NEAR(got / ref, 1.0, 0.03);
}
