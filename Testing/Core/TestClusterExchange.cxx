// SPDX-License-Identifier: BSD-3-Clause
// Cluster exchange areas against the dense solver's: the sum of S over the
// voxel pairs of two clusters, for clusters further and further apart, along
// an axis and diagonals. A link's exchange is sigma_A(w) sigma_B(-w) gamma
// (LinkSet.h, ClusterTree::sigmaTowards).
#include "TestScenes.h"
#include "volrad/ClusterTree.h"
#include "volrad/ExchangeAreas.h"
#include "volrad/LinkSet.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

/// Sum over all cell pairs of `level` offset by `offset` cells of
/// (cluster estimate, dense sum).
std::pair<double, double> meanExchange(const Scene& s,
                                       const ExchangeAreas& dense,
                                       const ClusterTree& tree,
                                       const VoxelPyramid& pyramid,
                                       int level,
                                       const std::array<int, 3>& offset)
{
  const Grid& cg = pyramid.grid(level);
  const int size = 1 << level;
  double estimate = 0.0, exact = 0.0;
  for (Index a = 0; a < cg.voxelCount(); ++a) {
    const auto ca = cg.ijk(a);
    if (ca[0] + offset[0] >= cg.dims[0] || ca[1] + offset[1] >= cg.dims[1] ||
        ca[2] + offset[2] >= cg.dims[2]) {
      continue;
    }
    const Index b = cg.index(ca[0] + offset[0], ca[1] + offset[1], ca[2] + offset[2]);
    const Index na = tree.voxelNode(level, a), nb = tree.voxelNode(level, b);
    const Vec3 w = (tree.centroid(nb) - tree.centroid(na)).normalized();
    estimate +=
      tree.sigmaTowards(na, w) * tree.sigmaTowards(nb, -w) * linkGamma(tree, na, nb, 1e-3);
    const auto cb = cg.ijk(b);
    for (Index u = 0; u < s.grid.voxelCount(); ++u) {
      const auto cu = s.grid.ijk(u);
      if (cu[0] / size != ca[0] || cu[1] / size != ca[1] || cu[2] / size != ca[2]) {
        continue;
      }
      for (Index v = 0; v < s.grid.voxelCount(); ++v) {
        const auto cv = s.grid.ijk(v);
        if (cv[0] / size == cb[0] && cv[1] / size == cb[1] && cv[2] / size == cb[2]) {
          exact += dense.S(dense.elements.full[u], dense.elements.full[v]);
        }
      }
    }
  }
  return { estimate, exact };
}

} // namespace

TEST(ClusterExchange, EffectiveCrossSectionLimits)
{
  const Vec3 h(0.5, 1.0, 2.0);
  EXPECT_NEAR(effectiveCrossSection(1e-6, h) / (1e-6 * h.prod()), 1.0, 1e-5); // thin: kappa V
  EXPECT_NEAR(effectiveCrossSection(1e6, h), 0.5 * (0.5 + 2.0 + 1.0), 1e-9);  // thick: S / 4
}

// A cluster shows towards a partner what its sides facing it let out (its
// voxels seen through the ones in front), from the plane through its box's
// foremost corner, and the link takes 1/r^2 and the transmittance between
// over the lines joining the boxes its light comes from. Before, a link ran
// from half a voxel chord off each centroid with every voxel's mean cross-
// section: 14% too weak for 2^3 clusters two cells apart in the lumpy medium,
// 22% for 4^3; in homogeneous media 17% and 38% at half a mean free path per
// voxel, 72% and 98% at two.
TEST(ClusterExchange, MatchesTheDenseSumsAlongAxesAndDiagonals)
{
  const ProgressCallback none;
  {
    Scene s = cubeScene(16);
    fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.5, 4.0); });
    fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.5, 4.0, 1.0); });
    const ExchangeAreas dense =
      computeExchangeAreas(s, 0, QuadratureSettings{}, {}, ProgressRange(none, 0, 1));
    const VoxelPyramid pyramid(s, 0);
    const ClusterTree tree(s, 0, pyramid);
    for (const auto& [level, offset] : std::vector<std::pair<int, int>>{
           { 1, 2 }, { 1, 3 }, { 1, 5 }, { 1, 7 }, { 2, 2 }, { 2, 3 } }) {
      const auto [estimate, exact] = meanExchange(s, dense, tree, pyramid, level, { offset, 0, 0 });
      std::printf("[measured] lumpy medium, %d^3 clusters %d cells apart: cluster S / dense S - 1 "
                  "= %+.4f\n",
                  1 << level,
                  offset,
                  estimate / exact - 1.0);
      EXPECT_LT(std::abs(estimate / exact - 1.0), 0.08);
    }
  }
  for (const double kappaH : { 0.5, 2.0 }) {
    Scene s = cubeScene(12);
    for (auto& k : s.kappaA) {
      k = float(0.3 * kappaH * 12);
    }
    for (auto& k : s.sigmaI) {
      k = float(0.7 * kappaH * 12);
    }
    QuadratureSettings fine;
    fine.voxelPointsPerAxis = 8;
    fine.voxelDirections = 16;
    const ExchangeAreas dense = computeExchangeAreas(s, 0, fine, {}, ProgressRange(none, 0, 1));
    const VoxelPyramid pyramid(s, 0);
    const ClusterTree tree(s, 0, pyramid);
    for (const auto& [level, offset] :
         std::vector<std::pair<int, int>>{ { 1, 2 }, { 1, 3 }, { 2, 2 } }) {
      for (int diagonal = 0; diagonal < 3; ++diagonal) {
        const std::array<int, 3> o{ offset, diagonal > 0 ? offset : 0, diagonal > 1 ? offset : 0 };
        const auto [estimate, exact] = meanExchange(s, dense, tree, pyramid, level, o);
        const double err = estimate / exact - 1.0;
        std::printf("[measured] kappa h %.1f, %d^3 clusters (%d, %d, %d) cells apart: cluster S / "
                    "dense S - 1 = %+.4f\n",
                    kappaH,
                    1 << level,
                    o[0],
                    o[1],
                    o[2],
                    err);
        // Along an axis every line crosses the same medium; obliquely the
        // sides' mix and the corner plane leave thick clusters too weak
        // (the known limit: 10-20% at half a mean free path per voxel, a
        // third to a half at two; the fine dense sums themselves move by
        // a few points between builds along the diagonals).
        EXPECT_LT(std::abs(err), diagonal == 0 ? 0.08 : (kappaH < 1.0 ? 0.3 : 0.6));
      }
    }
  }
}

/// The voxel-to-voxel links the refinement makes, sigma_a sigma_b gamma,
/// against the dense exchange areas of the same pairs, summed per distance,
/// in homogeneous media half a mean free path and two mean free paths per
/// voxel (where a voxel's own attenuation matters most). Close links (2-5
/// voxels apart, several lines each) must agree within 5% and 15%, and
/// meet the single-line links past them without a jump. Before the voxel-
/// end gain (VoxelGain.h, LinkSet.cxx leafEnd) they were 11-17% and 50-67% too strong, and
/// jumped by 13% and 80% at 6 voxels: that biased G near a point light by
/// 2% at 24^3. (Further apart, a pair's dense value rests on few of the
/// dense quadrature's lines and is not compared.)
TEST(ClusterExchange, CloseVoxelLinksMatchTheDenseExchangeAreas)
{
  for (const double kappaH : { 0.5, 2.0 }) {
    Scene s = cubeScene(10);
    const double kappa = kappaH * 10.0;
    for (auto& k : s.kappaA) {
      k = float(0.3 * kappa);
    }
    for (auto& k : s.sigmaI) {
      k = float(0.7 * kappa);
    }
    QuadratureSettings fine;
    fine.voxelPointsPerAxis = 8;
    fine.voxelDirections = 16;
    const ProgressCallback none;
    const ExchangeAreas dense = computeExchangeAreas(s, 0, fine, {}, ProgressRange(none, 0, 1));
    const VoxelPyramid pyramid(s, 0);
    const ClusterTree tree(s, 0, pyramid);
    LinkRefinement refinement;
    refinement.tolerance = 0.0; // every pair down to the voxels
    refinement.radiosity.assign(tree.size(), 1.f);
    const LinkSet links = refineLinks(tree, refinement);
    const Grid& g = s.grid;
    double link[7] = {}, exact[7] = {};
    for (Index b = 0; b < g.voxelCount(); ++b) {
      links.forEachInto(b, [&](Index a, double gamma) {
        const int gap = a < g.voxelCount() ? tree.gap(a, b) : 0;
        if (gap >= 2 && gap <= 6) {
          link[gap] += tree.sigma(a) * tree.sigma(b) * gamma;
          exact[gap] += dense.S(dense.elements.full[a], dense.elements.full[b]);
        }
      });
    }
    for (int gap = 2; gap <= 6; ++gap) {
      std::printf("[measured] kappa h %.1f, voxels %d apart: links S / dense S - 1 = %+.4f\n",
                  kappaH,
                  gap,
                  link[gap] / exact[gap] - 1.0);
      if (gap <= 5) {
        EXPECT_LT(std::abs(link[gap] / exact[gap] - 1.0), kappaH < 1.0 ? 0.05 : 0.15) << gap;
      }
    }
    EXPECT_LT(std::abs(link[6] / exact[6] - link[5] / exact[5]), 0.05) << kappaH;
  }
}
