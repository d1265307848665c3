// SPDX-License-Identifier: BSD-3-Clause
/// @file FarField.h
/// @brief The exchange the links carry, applied to element radiosities:
/// pull (each node gathers its elements' emission, front sides as an
/// order-1 mask), gather over the links into each receiving node, push
/// (each node hands what it received down to its elements).
///
/// A cluster sends and receives through its sides facing the link
/// (ClusterTree): what its children let out of each side is pulled up
/// through the siblings in front of them, and what arrives at a side is
/// pushed down the same way. To first order in the offsets of its elements
/// from its centroid, 1/r^2 along a link grows by 2/r per length towards
/// the other end: each cluster also pulls its emission's moment and pushes
/// the gradient of what it received (the slope limited to 1 / its radius).
/// Both keep the exchange symmetric. The moment is of the emission before
/// the sides' transmittance (measured: that of the emission through the
/// sides gave 2x the error of G at coarse link tolerances), so an element
/// hidden behind others in a thick cluster may get a slightly negative
/// weight: with the balancing's limits, the known slightly negative G in
/// deep shadow.
///
/// The links' operator F is then balanced symmetrically, D F D with D
/// diagonal within [1/2, 2], towards each element receiving exactly its far
/// weight from the near field (NearField::far) for radiosity 1 on every
/// full side and patch: by reciprocity that is what all its far partners
/// send it, and by symmetry what it sends them. The rest of each row's
/// difference is added to the element's self exchange, so every row and
/// column of the whole operator is exact and symmetric: the far field
/// neither loses nor makes energy (white furnace, energy balance), while
/// the links decide where the far light comes from.
#pragma once

#include "volrad/ClusterTree.h"
#include "volrad/LinkSet.h"
#include "volrad/NearField.h"
#include "volrad/Progress.h"

#include <vector>

namespace volrad {

class FarField
{
public:
  /// Balancing sweeps every link a few times: `progress` hears after each
  /// (and may abort).
  FarField(const Scene& scene,
           const ClusterTree& tree,
           const LinkSet& links,
           const NearField& near,
           const ProgressRange& progress = {});

  /// y[e] += far collided power of element e for element radiosities x.
  /// With viewOut, also the far G of voxels that are not elements.
  /// `progress` hears between blocks of the sweep over the links (a second
  /// at tens of millions of links) and may abort.
  void apply(const double* x,
             double* y,
             double* viewOut = nullptr,
             const ProgressRange& progress = {}) const;
  /// The balancing D, per element (front sides: their row's scale).
  const std::vector<double>& scale() const { return scale_; }
  /// What each element's self exchange gained to make its row exact.
  const std::vector<double>& selfCorrection() const { return self_; }
  std::size_t bytes() const;

private:
  void gather(const double* x,
              double* y,
              double* viewOut,
              bool normalised,
              const ProgressRange& progress) const;

  const Scene& scene_;
  const ClusterTree& tree_;
  const LinkSet& links_;
  const ExchangeElements& el_;
  bool fronts_ = false;
  static constexpr int kBalanceSteps = 6;
  std::vector<double> scale_, self_;
  /// Per node past the voxels (clusters, patches), its centroid (the
  /// gather's directions: ClusterTree::centroid finds a node's level first,
  /// at every link). A voxel's is its centre, computed: stored, the voxels'
  /// were 0.2 GB at 256^3. Rounded to float like the stored ones.
  std::vector<Vec3f> centroid_;
  Index voxels_ = 0;
  Vec3 centroid(Index node) const
  {
    const Vec3f c =
      node < voxels_ ? Vec3f(tree_.grid(0).voxelCentre(node).cast<float>()) : centroid_[node - voxels_];
    return c.cast<double>();
  }
  /// Voxel clusters are the nodes [voxel count, voxel count + clusters_):
  /// the arrays indexed by cluster (node - voxel count) hold them only,
  /// since leaves have no extent and patch nodes no slope.
  Index clusters_ = 0;
  bool isVoxelCluster(Index node, Index voxels) const
  {
    return node >= voxels && node - voxels < clusters_;
  }
  /// Per voxel cluster: 1 / its radius, the limit of the first-order
  /// variation of a link's exchange across it.
  std::vector<float> slopeLimit_;
  // Work arrays, per tree node (mutable: apply is logically const), in
  // float: at 256^3 voxels the far field's arrays in double were 2.6 GB, a
  // third of the solve's peak; every sum is taken in double.
  mutable std::vector<double> scaled_; // per element
  mutable std::vector<float> emit_, phi_;
  mutable std::vector<float> frontEmit_, leafDirect_, leafFront_;
  mutable std::vector<Vec3f> frontMoment_, psi_;
  /// With front sides: per node, what its clusters received, without the
  /// sides' transmittance (front sides' share; they emit the same way).
  mutable std::vector<float> open_;
  /// Per voxel cluster: its elements' emission moment about its centroid
  /// (pull) and the gradient of what it received (push).
  mutable std::vector<Vec3f> moment_, gradient_;
  /// Per voxel cluster (node - voxel count): its emission through, and what
  /// it received on, each of its six sides (ClusterTree::side).
  mutable std::vector<std::array<float, 6>> sideEmit_, sidePhi_;
};

} // namespace volrad
