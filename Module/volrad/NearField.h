// SPDX-License-Identifier: BSD-3-Clause
/// @file NearField.h
/// @brief Exact exchange areas between each voxel and its neighbourhood, the
/// near and self interactions of the hierarchical solver (issue 4): the
/// dense solver's line quadrature, with every line followed only to the
/// boundary of the neighbourhood box (Chebyshev distance `radius` voxels).
///
/// What a line still carries when it leaves the box is the voxel's far
/// exchange, for links between clusters to distribute; the near values plus
/// the far weight add up to the voxel's whole row, so the split conserves
/// energy exactly. This first version covers the full (isotropic) sides;
/// front sides stay with the dense solver for now.
#pragma once

#include "volrad/ExchangeAreas.h"

#include <utility>
#include <vector>

namespace volrad {

struct NearField
{
  int radius = 1;
  ExchangeElements elements;
  /// Per voxel, (2 radius + 1)^3 values of S(v, v + offset), offset index
  /// (dx + r) + (2r + 1)((dy + r) + (2r + 1)(dz + r)); zero past the domain
  /// and for voxels with kappa_t = 0 (and for v itself if kappa_t = 0).
  std::vector<double> stencil;
  /// Per voxel: boundary patches reached inside the box, and S to them.
  std::vector<std::vector<std::pair<Index, double>>> patches;
  /// Per voxel: the exchange that leaves the box (sum of S to everything
  /// farther than `radius`).
  std::vector<double> far;

  int stencilSize() const { return (2 * radius + 1) * (2 * radius + 1) * (2 * radius + 1); }
  int offsetIndex(int dx, int dy, int dz) const
  {
    const int w = 2 * radius + 1;
    return (dx + radius) + w * ((dy + radius) + w * (dz + radius));
  }
  double value(Index v, int dx, int dy, int dz) const
  {
    return stencil[std::size_t(v) * stencilSize() + offsetIndex(dx, dy, dz)];
  }
};

/// Needs a scene without front sides (sigma_d = E_D = 0) in this version.
NearField computeNearField(const Scene& scene,
                           int channel,
                           const QuadratureSettings& q,
                           int radius);

} // namespace volrad
