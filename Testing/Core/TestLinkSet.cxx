// SPDX-License-Identifier: BSD-3-Clause
// The link rows (LinkSet.h): every link is stored in the rows of both its
// ends with the same gamma, each row in increasing order of sources, also
// where a source is farther than a 16-bit step from the one before it and
// where a slice of nodes is written in pieces; and gamma's 16-bit code
// (GammaCode) within its rounding of the value.
#include "TestScenes.h"
#include "volrad/ClusterTree.h"
#include "volrad/LinkSet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
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
  // Some slice's rows hold more than their share of the entries (the
  // clusters'), so that they are written in pieces.
  const LinkPacking packing(tree.size());
  Index most = 0;
  for (int j = 0; j < packing.slices; ++j) {
    const Index n0 = std::min(tree.size(), j * packing.sliceSize),
                n1 = std::min(tree.size(), (j + 1) * packing.sliceSize);
    most = std::max(most, links.start[n1] - links.start[n0]);
  }
  EXPECT_GT(most, 2 * links.start.back() / LinkPacking::kFewestSlices);

  std::vector<std::vector<std::pair<Index, double>>> rows(tree.size());
  for (Index b = 0; b < tree.size(); ++b) {
    links.forEachInto(b, [&](Index a, double gamma) { rows[b].emplace_back(a, gamma); });
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
        other.begin(), other.end(), std::make_pair(b, -1.0), [](const auto& x, const auto& y) {
          return x.first < y.first;
        });
      ASSERT_TRUE(it != other.end() && it->first == b) << "link " << a << " - " << b;
      ASSERT_EQ(it->second, gamma);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2 * links.pairs);
}

TEST(LinkSet, GammaCodeIsWithinItsRoundingAndKeepsTheOrder)
{
  // Gammas over 2^60 below the largest: each decoded within 2^-11 of
  // itself (a 10-bit mantissa rounded to nearest), in the same order.
  const double largest = 3.7e4;
  const GammaCode code = GammaCode::forLargest(largest);
  EXPECT_EQ(code.decode(code.encode(0.0)), 0.0);
  EXPECT_EQ(code.decode(code.encode(-1.0)), 0.0);
  double worst = 0.0, previousValue = 0.0;
  std::uint16_t previousCode = 0;
  for (double g = largest * std::ldexp(1.0, -60); g <= largest; g *= 1.0 + 1.0 / 997) {
    const std::uint16_t c = code.encode(g);
    const double back = code.decode(c);
    ASSERT_GT(back, 0.0) << g;
    worst = std::max(worst, std::abs(back - g) / g);
    ASSERT_GE(c, previousCode) << g;
    ASSERT_GE(back, previousValue) << g;
    previousCode = c;
    previousValue = back;
  }
  EXPECT_LE(worst, std::ldexp(1.0, -11));
  EXPECT_GT(worst, std::ldexp(1.0, -12)); // the code does round: not a float
  EXPECT_NEAR(code.decode(code.encode(largest)), largest, largest * std::ldexp(1.0, -11));
  // Far below the largest: 0; a value just below a power of two rounds up into it.
  EXPECT_EQ(code.decode(code.encode(largest * std::ldexp(1.0, -70))), 0.0);
  const double justBelow = std::nextafter(std::ldexp(1.0, 10), 0.0);
  EXPECT_EQ(code.decode(code.encode(justBelow)), std::ldexp(1.0, 10));
}

TEST(LinkSet, PackedLinksGiveBackTheirNodesAndTheRowsGammaCodes)
{
  // From a handful of nodes to the 32-bit limit (2^31 - 1, where the slices
  // multiply): every node, by its slice or a piece of it, and a gamma whose stored code (GammaCode, rounded
  // from its top 11 mantissa bits) is that of the whole float.
  std::uint64_t state = 12345;
  auto next = [&] { // a 64-bit linear congruential generator
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 11;
  };
  const GammaCode code = GammaCode::forLargest(1e3);
  for (const Index nodes : { Index(1), Index(37), Index(3'100'000), Index(19'200'000),
                             Index(40'000'000), Index(2'147'483'647) }) {
    const LinkPacking p(nodes);
    EXPECT_GE(p.gammaBits, 19) << nodes;
    EXPECT_GE(p.slices, LinkPacking::kFewestSlices) << nodes;
    EXPECT_EQ(p.slices & (p.slices - 1), 0) << nodes;
    EXPECT_GE(Index(p.slices) * p.sliceSize, nodes);
    for (int k = 0; k < 20000; ++k) {
      const Index row = Index(next() % std::uint64_t(nodes)),
                  other = k == 0 ? nodes - 1 : Index(next() % std::uint64_t(nodes));
      const float gamma =
        float(std::ldexp(1.0 + double(next() % 1000000) / 1e6, int(next() % 120) - 100));
      const int slice = p.sliceOf(row);
      const PackedLink x = p.pack(row, slice, other, gamma);
      ASSERT_LT(slice, p.slices);
      ASSERT_EQ(p.row(x, slice), row) << nodes;
      ASSERT_EQ(p.other(x), other) << nodes;
      // From a node up to sliceSize - 1 before the row (a piece of a slice).
      const Index first = row - Index(next() % std::uint64_t(std::min(row + 1, p.sliceSize)));
      const PackedLink y = p.packFrom(first, row, other, gamma);
      ASSERT_EQ(p.rowFrom(first, y), row) << nodes;
      ASSERT_EQ(p.other(y), other) << nodes;
      ASSERT_EQ(p.gamma(y), p.gamma(x)) << nodes;
      const float back = p.gamma(x);
      ASSERT_LE(back, gamma);
      ASSERT_LE(gamma - back, gamma * std::ldexp(1.0, 8 - p.gammaBits)) << nodes;
      ASSERT_EQ(code.encode(back), code.encode(gamma)) << nodes << " " << gamma;
    }
  }
}
