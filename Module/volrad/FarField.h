// SPDX-License-Identifier: BSD-3-Clause
/// @file FarField.h
/// @brief The exchange the links carry, applied to element radiosities:
/// pull (each node gathers its elements' emission, front sides as an
/// order-1 mask), gather over the links into each receiving node, push
/// (each node hands what it received down to its elements).
///
/// Every element's far gathering is then scaled so that, for radiosity 1
/// on every full side and patch, it receives exactly its far weight from
/// the near field (NearField::far, exact up to quadrature): by reciprocity
/// that is what all its far partners send it. This removes the links'
/// systematic error (the 1/r^2 and transmittance averages over clusters)
/// from each element's total, which keeps the white furnace and the energy
/// balance close while the links decide only where the far light comes from.
#pragma once

#include "volrad/ClusterTree.h"
#include "volrad/LinkSet.h"
#include "volrad/NearField.h"

#include <vector>

namespace volrad {

class FarField
{
public:
  FarField(const Scene& scene,
           const ClusterTree& tree,
           const LinkSet& links,
           const NearField& near);

  /// y[e] += far collided power of element e for element radiosities x.
  /// With viewOut, also the far G of voxels that are not elements.
  void apply(const double* x, double* y, double* viewOut = nullptr) const;
  /// The normalisation, per element (1 where nothing is known).
  const std::vector<double>& scale() const { return scale_; }
  std::size_t bytes() const;

private:
  void gather(const double* x, double* y, double* viewOut, bool normalised) const;

  const Scene& scene_;
  const ClusterTree& tree_;
  const LinkSet& links_;
  const ExchangeElements& el_;
  bool fronts_ = false;
  std::vector<double> scale_;
  // Work arrays, per tree node (mutable: apply is logically const).
  mutable std::vector<double> emit_, phi_;
  mutable std::vector<double> frontEmit_, leafDirect_, leafFront_;
  mutable std::vector<Vec3> frontMoment_, psi_;
};

} // namespace volrad
