// SPDX-License-Identifier: BSD-3-Clause
// The link rows (LinkSet.h): every link is stored in the rows of both its
// ends with the same gamma, each row in increasing order of sources, also
// where a source is farther than a 16-bit step from the one before it.
#include "TestScenes.h"
#include "volrad/ClusterTree.h"
#include "volrad/LinkSet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

using namespace volrad;
using namespace volrad::test;

TEST(LinkSet, RowsHoldEachLinkBothWaysInOrderAcrossFarSteps)
{
  // More nodes than a 16-bit step spans, so that rows jump by far steps
  // (from the voxels to the clusters and the patches).
  Scene s;
  s.grid.dims = { 70, 70, 14 };
  s.grid.spacing = Vec3::Constant(1.0 / 70);
  s.grid.origin = Vec3::Constant(0.5 / 70);
  s.allocate();
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.1, 2.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.5, 4.0, 0.9); });
  const VoxelPyramid pyramid(s, 0);
  const ClusterTree tree(s, 0, pyramid);
  ASSERT_GT(tree.size(), Index(LinkSet::kFarStep));
  LinkRefinement refinement;
  refinement.tolerance = 1e-5;
  refinement.radiosity.assign(tree.size(), 1.f);
  const LinkSet links = refineLinks(tree, refinement);
  ASSERT_GT(links.pairs, 100000);
  EXPECT_EQ(links.start.back(), 2 * links.pairs);
  EXPECT_GT(links.farSource.size(), 0u); // the far steps are exercised

  std::vector<std::vector<std::pair<Index, float>>> rows(tree.size());
  for (Index b = 0; b < tree.size(); ++b) {
    links.forEachInto(b, [&](Index a, float gamma) { rows[b].emplace_back(a, gamma); });
    ASSERT_EQ(Index(rows[b].size()), links.start[b + 1] - links.start[b]);
  }
  long long checked = 0;
  for (Index b = 0; b < tree.size(); ++b) {
    for (std::size_t k = 0; k < rows[b].size(); ++k) {
      const auto [a, gamma] = rows[b][k];
      ASSERT_TRUE(a >= 0 && a < tree.size() && a != b) << "node " << b << " source " << a;
      if (k > 0) {
        ASSERT_LT(rows[b][k - 1].first, a) << "node " << b << ": sources out of order";
      }
      // The same link in a's row, to b, with the same gamma.
      const auto& other = rows[a];
      const auto it = std::lower_bound(
        other.begin(), other.end(), std::make_pair(b, -1.f), [](const auto& x, const auto& y) {
          return x.first < y.first;
        });
      ASSERT_TRUE(it != other.end() && it->first == b) << "link " << a << " - " << b;
      ASSERT_EQ(it->second, gamma);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2 * links.pairs);
}
