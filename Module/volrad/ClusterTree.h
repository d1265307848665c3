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
/// holds their exchange.
///
/// Clusters are not transparent: light leaving a voxel towards a partner
/// crosses the voxels between it and its cluster's side. Each voxel node
/// keeps, per side of its parent (+-x, +-y, +-z), the mean transmittance
/// from it to that side, through the sibling in between (the sibling's mean
/// transmittance straight across, built up from its own children's columns);
/// a cluster's emission or cross-section towards a direction then weighs its
/// children by it, level by level, and adds up its three sides facing the
/// direction (sideWeights). Voxel nodes are numbered first, level by level
/// from the voxels (node = voxel index on level 0), then patch nodes.
#pragma once

#include "volrad/VoxelPyramid.h"

#include <array>
#include <cmath>
#include <cstdint>
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
  int level(Index node) const { return level_[node]; }
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

  /// The side of a box facing along axis a, positive or negative.
  static int side(int axis, bool positive) { return 2 * axis + (positive ? 1 : 0); }
  /// Mean transmittance from voxel node n to its parent's side `side`
  /// (1 for the root and for patch nodes); for a voxel, times what it shows
  /// along that axis relative to its cross-section (face area times
  /// opacity over sigma, above 1 for thick, flat voxels).
  float toParentSide(Index n, int side) const
  {
    return isPatch(n) ? 1.0f : float(exitTransmittance_[std::size_t(n) * 6 + side]);
  }
  /// Weights of the three sides facing unit w (side(a, w_a > 0)) in what a
  /// cluster shows towards w, from the fraction of its cross-section each
  /// side shows (open = side sigma / sigma, in [0, 1]): |w_a| / (1 + (|w|_1 - 1) t),
  /// t = sum w_a^2 open_a: |w_a|, the sides' projected areas, when the
  /// cluster is opaque, and |w_a| / |w|_1, all of it whatever w, when it is
  /// transparent.
  static void sideWeights(const Vec3& w, const float* open, double weight[3])
  {
    const double l1 = std::abs(w[0]) + std::abs(w[1]) + std::abs(w[2]);
    double t = 0.0;
    for (int a = 0; a < 3; ++a) {
      t += w[a] * w[a] * open[side(a, w[a] > 0.0)];
    }
    const double norm = 1.0 / (1.0 + (l1 - 1.0) * t);
    for (int a = 0; a < 3; ++a) {
      weight[a] = std::abs(w[a]) * norm;
    }
  }
  /// What a cluster shows towards unit w of per-side values (its sides'
  /// sigma, emission, ...): the three sides facing w, weighted by
  /// sideWeights.
  template<class T>
  static double towards(const Vec3& w, const float* open, const std::array<T, 6>& sides)
  {
    double weight[3], s = 0.0;
    sideWeights(w, open, weight);
    for (int a = 0; a < 3; ++a) {
      s += weight[a] * double(sides[side(a, w[a] > 0.0)]);
    }
    return s;
  }
  /// Per cluster node (levels >= 1), side sigma / sigma for each side (1
  /// for voxels and patches); computed once, with the sides.
  const std::array<float, 6>& sideOpenness(Index node) const
  {
    static const std::array<float, 6> kOpen{ 1.f, 1.f, 1.f, 1.f, 1.f, 1.f };
    const Index nv = grids_[0].voxelCount();
    return isPatch(node) || node < nv ? kOpen : sideOpen_[node - nv];
  }
  /// What a cluster's light towards unit w keeps from its sides to the
  /// plane normal to w through its box's foremost corner (where every line
  /// parallel to w has left it): a point of side a crosses w_b u_b + w_c u_c
  /// of the medium around it (extinction kappa), u its distances to the
  /// side's far edges, whose mean of e^-x is a product of (1 - e^-x) / x;
  /// 1 for voxels, patches and along the axes.
  double frontFactor(Index node, const Vec3& w, double kappa) const;
  /// The cross-section a node shows towards unit direction w (pointing to
  /// the partner), its voxels seen through the ones in front of them;
  /// sigma() for voxels and patches (whose cosine the caller applies).
  double sigmaTowards(Index node, const Vec3& w) const;
  /// The box what a node shows towards unit w comes from: its own box,
  /// centred where that light leaves from on average and as much thinner
  /// along each axis (a thick cluster's light leaves from its surface);
  /// for voxels and patches their centroid (half = 0).
  void emissionBox(Index node, const Vec3& w, Vec3& centre, Vec3& half) const;

  double sigma(Index node) const;
  Vec3 centroid(Index node) const;
  double radius(Index node) const;
  double meanKappaT(Index node) const;
  Face face(Index node) const; ///< patch nodes only
  /// Inclusive voxel-index box (patch nodes: the voxels behind them).
  void box(Index node, std::array<int, 3>& lo, std::array<int, 3>& hi) const;
  /// The same box, for a caller that asks several of the queries below of
  /// one node (the links' refinement: a box costs two integer divisions).
  struct Box
  {
    std::array<int, 3> lo, hi;
    /// Voxels it spans along each axis.
    std::array<int, 3> extent() const
    {
      return { hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1 };
    }
  };
  Box box(Index node) const
  {
    Box b;
    box(node, b.lo, b.hi);
    return b;
  }
  /// radius() of a node whose box() is b.
  double radius(Index node, const Box& b) const;
  /// The box's corners in space (voxel nodes: the faces of its voxels).
  void spaceBox(Index node, Vec3& lo, Vec3& hi) const { spaceBox(box(node), lo, hi); }
  void spaceBox(const Box& b, Vec3& lo, Vec3& hi) const;
  /// Chebyshev gap between two boxes: 0 when they overlap, 1 when they touch.
  int gap(Index a, Index b) const { return gap(box(a), box(b)); }
  static int gap(const Box& a, const Box& b);
  /// The voxel grid of a level (its patches are that level's patch nodes).
  const Grid& grid(int level) const { return grids_[level]; }
  const VoxelPyramid& pyramid() const { return pyramid_; }
  std::size_t bytes() const;

private:
  void buildSideTransmittance(const Scene& scene, int channel);

  const VoxelPyramid& pyramid_;
  std::vector<Grid> grids_;
  std::vector<Index> voxelOffset_, patchOffset_; ///< per level, plus the total
  /// Per node (one byte: a node's level is asked several times per link
  /// candidate, and finding it from the offsets was a loop each time).
  std::vector<std::uint8_t> level_;
  std::vector<float> voxelSigma_;          ///< level 0
  std::vector<std::vector<double>> sigma_; ///< levels >= 1 (voxels), [0] unused
  /// Per voxel node, 6 sides of its parent; in half precision (0.05%, far
  /// below a link's error): 24 bytes a voxel in float, the tree's largest
  /// array.
  std::vector<Eigen::half> exitTransmittance_;
  std::vector<std::vector<std::array<float, 6>>> sideSigma_; ///< levels >= 1 (voxels)
  std::vector<std::array<float, 6>> sideOpen_; ///< per cluster node, from the first cluster on
  /// Per side, where along its axis the light leaving through it comes
  /// from on average, less the centroid (levels >= 1, voxels).
  std::vector<std::vector<std::array<float, 6>>> sideShift_;
  std::vector<std::vector<Vec3>> centroid_;      ///< levels >= 1 (voxels)
  std::vector<std::vector<double>> patchArea_;   ///< all levels
  std::vector<std::vector<Vec3>> patchCentroid_; ///< all levels
};

} // namespace volrad
