// SPDX-License-Identifier: BSD-3-Clause
/// @file ExchangeAreas.h
/// @brief All pairwise exchange factors of one channel, as symmetric
/// exchange areas (physics.md section 4; Hottel's zonal method).
///
/// Elements ("sides") that exchange power:
///  * the full side of each voxel with kappa_t > 0: isotropic emitter of
///    power 4 kappa_t V Q_I, receiver of everything that collides in it;
///  * the front side of each such voxel whose sigma_d or E_D is non-zero in
///    some channel (it has a normal then): hemispherical emitter
///    (2 kappa_t V Q_D, travel directions with n.w > 0) and receiver of the
///    light arriving from the front (what G+ counts);
///  * every boundary patch (wall or open face): Lambertian emitter A B,
///    receiver of what hits it.
///
/// S(a, b) is the power emitted by a per unit radiosity of a that has its
/// first collision in b [length^2]. Reciprocity makes S symmetric, and
/// conservation fixes the row sums over the partition (full sides and
/// patches): 4 kappa_t V (full), 2 kappa_t V (front), A (patch). The
/// self terms S(a, a) are part of S and enter the solve implicitly.
///
/// Quadrature: each row is integrated by gathering rays from stratified
/// points of the element (exact voxel traversal; the probability of a first
/// collision in each crossed voxel is exact along a ray, including in the
/// element itself). The raw matrix is then made symmetric and smoothed
/// (Larsen & Howell 1985: the least change, relative to each entry, that
/// restores the row sums), so reciprocity and conservation hold to round-off
/// and the remaining error is the quadrature's, reported in `quadratureError`.
#pragma once

#include "volrad/Progress.h"
#include "volrad/Quadrature.h"
#include "volrad/Scene.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace volrad {

/// Index of the sides of one channel. Layout: [full | patches | front]; the
/// first `partitionSize()` elements partition space.
struct ExchangeElements
{
  /// Elements and voxels are numbered in 32 bits (makeExchangeElements
  /// refuses more): these per-voxel maps were 0.4 GB in 64 bits at 256^3.
  using Number = std::int32_t;
  std::vector<Number> full;    ///< voxel -> element, -1 where kappa_t = 0
  std::vector<Number> front;   ///< voxel -> element, -1 where no front side is needed
  std::vector<Number> voxelOf; ///< element -> voxel (full and front sides), -1 for patches
  Index fullCount = 0, patchCount = 0, frontCount = 0;

  Index patchElement(Index patch) const { return fullCount + patch; }
  Index partitionSize() const { return fullCount + patchCount; }
  Index size() const { return fullCount + patchCount + frontCount; }
  bool isFront(Index e) const { return e >= partitionSize(); }
  bool isPatch(Index e) const { return e >= fullCount && e < partitionSize(); }
};

ExchangeElements makeExchangeElements(const Scene& scene, int channel);

struct ExchangeOptions
{
  bool symmetrize = true; ///< average S with its transpose
  bool smooth = true;     ///< restore exact row sums (needs symmetrize)
};

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct ExchangeAreas
{
  ExchangeElements elements;
  RowMatrix S; ///< symmetric exchange areas, size elements.size()^2
  /// Fields of voxels that are not elements, gathered by rays from interior
  /// points: G of voxels with kappa_t = 0 (they exchange nothing) and G+ of
  /// voxels with a normal but no front side. G = row . x over the element
  /// radiosities x. Rows indexed by gatherFullRow / gatherFrontRow.
  RowMatrix gatherRows;
  std::vector<Index> gatherFullRow, gatherFrontRow; ///< voxel -> row or -1
  /// Largest relative change the smoothing made to an entry: the size of
  /// the quadrature's conservation error.
  double quadratureError = 0.0;
};

/// Row sum over the partition that conservation requires of element e.
double exchangeRowTarget(const Scene& scene, int channel, const ExchangeElements& el, Index e);

/// Whether voxel v needs a front side (sigma_d or E_D > 0 in some channel).
bool needsFrontSide(const Scene& scene, Index v);

ExchangeAreas computeExchangeAreas(const Scene& scene,
                                   int channel,
                                   const QuadratureSettings& q,
                                   const ExchangeOptions& options,
                                   const ProgressRange& progress);

} // namespace volrad
