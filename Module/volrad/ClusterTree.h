// SPDX-License-Identifier: BSD-3-Clause
/// @file ClusterTree.h
/// @brief The element hierarchy of the hierarchical solver: the voxel
/// pyramid's cells (voxels clustered 2x2x2 up to one root) and, on each
/// face of the domain, a quadtree of boundary patches aligned with them.
///
/// Every node knows what a link needs of it: its extinction cross-section
/// (voxel cells: the sum of its voxels' effective cross-sections, below;
/// patch nodes: their area, which a link multiplies by the
/// cosine towards the other end), its centroid (sigma- or area-weighted),
/// the radius of a sphere around it, and its box in voxel indices, whose
/// distance to another node's box decides whether the near field already
/// holds their exchange. Voxel nodes are numbered first, level by level
/// from the voxels (node = voxel index on level 0), then patch nodes.
#pragma once

#include "volrad/VoxelPyramid.h"

#include <array>
#include <vector>

namespace volrad {

/// Mean extinction cross-section of a voxel over all directions [length^2]:
/// (S/4)(1 - exp(-kappa_t 4V/S)), S the voxel's surface: kappa_t V when thin,
/// the mean projected area S/4 when thick (Cauchy). A cluster's is the sum
/// of its voxels'; links place it at the sigma-weighted centroid.
double effectiveCrossSection(double kappaT, const Vec3& spacing);

class ClusterTree
{
public:
  ClusterTree(const Scene& scene, int channel, const VoxelPyramid& pyramid);

  Index size() const { return patchOffset_.back(); }
  int levels() const { return int(grids_.size()); }
  Index voxelNode(int level, Index cell) const { return voxelOffset_[level] + cell; }
  Index patchNode(int level, Index patch) const { return patchOffset_[level] + patch; }
  bool isPatch(Index node) const { return node >= patchOffset_[0]; }
  int level(Index node) const;
  /// Cell index within its level (the voxel or patch index on level 0).
  Index cell(Index node) const
  {
    return node - (isPatch(node) ? patchOffset_ : voxelOffset_)[level(node)];
  }
  bool isLeaf(Index node) const { return level(node) == 0; }
  /// The voxel root, then the root patch node of each face.
  std::vector<Index> roots() const;
  /// Children into out; returns their number (0 for leaves, up to 8).
  int children(Index node, std::array<Index, 8>& out) const;

  double sigma(Index node) const;
  Vec3 centroid(Index node) const;
  double radius(Index node) const;
  double meanKappaT(Index node) const;
  Face face(Index node) const; ///< patch nodes only
  /// Inclusive voxel-index box (patch nodes: the voxels behind them).
  void box(Index node, std::array<int, 3>& lo, std::array<int, 3>& hi) const;
  /// Chebyshev gap between two boxes: 0 when they overlap, 1 when they touch.
  int gap(Index a, Index b) const;
  /// The voxel grid of a level (its patches are that level's patch nodes).
  const Grid& grid(int level) const { return grids_[level]; }
  const VoxelPyramid& pyramid() const { return pyramid_; }
  std::size_t bytes() const;

private:
  const VoxelPyramid& pyramid_;
  std::vector<Grid> grids_;
  std::vector<Index> voxelOffset_, patchOffset_; ///< per level, plus the total
  std::vector<float> voxelSigma_;                ///< level 0
  std::vector<std::vector<double>> sigma_;       ///< levels >= 1 (voxels), [0] unused
  std::vector<std::vector<Vec3>> centroid_;      ///< levels >= 1 (voxels)
  std::vector<std::vector<double>> patchArea_;   ///< all levels
  std::vector<std::vector<Vec3>> patchCentroid_; ///< all levels
};

} // namespace volrad
