// SPDX-License-Identifier: BSD-3-Clause
/// @file NearField.h
/// @brief Exact exchange areas between each element and its neighbourhood,
/// the near and self interactions of the hierarchical solver: the dense
/// solver's line quadrature, with every line followed only to the boundary
/// of the neighbourhood box (Chebyshev distance `radius` voxels around the
/// element's voxel; a boundary patch's voxel is the one behind it).
///
/// All element kinds take part: full sides, front sides and boundary
/// patches. The rows are made symmetric like the dense ones (inverse-
/// variance weights), so the near field is reciprocal on its own. What the
/// lines still carry when they leave the box is the element's far
/// exchange, `far`, for the links between clusters to distribute: near
/// values plus far weight add up to the element's whole row (4 kappa_t V,
/// 2 kappa_t V or A), so the split conserves energy.
///
/// Voxels whose neighbourhood (clipped to the domain) is homogeneous (one
/// extinction, no front sides) and which lie as far from each of the
/// domain's sides (counted up to radius + 1) have the same rows up to a
/// translation and quadrature noise; with `reuseHomogeneous` they share
/// one, integrated with the finer `homogeneousQuadrature`, and so do the
/// patches on such voxels (their own quadrature) and the views of empty
/// voxels with no medium near: CT-like volumes of a few materials, uniform
/// media and the empty space along the walls then cost one quadrature per
/// material and place (the 61-mfp cube at 64^3: 22 s -> 0.9 s).
#pragma once

#include "volrad/ExchangeAreas.h"

#include <cstdint>
#include <vector>

namespace volrad {

struct NearFieldOptions
{
  int radius = 1;
  QuadratureSettings quadrature;
  bool reuseHomogeneous = true;
  QuadratureSettings homogeneousQuadrature{ 12, 16, 12, 16, 8, 64 };
  /// The view rows of empty voxels (their G); without them empty space
  /// costs nothing here (a sparse solve).
  bool emptyViews = true;
};

/// View rows of voxels that are not elements (kappa_t = 0) but see
/// elements inside their box: G = row . x over element radiosities.
struct ViewRows
{
  std::vector<Index> start; ///< per voxel + 1
  std::vector<ExchangeElements::Number> column;
  std::vector<float> value;
  std::size_t bytes() const;
};

struct NearField
{
  /// An element's number in the rows' columns: 32 bits
  /// (makeExchangeElements refuses more elements), a third less than 64-bit
  /// columns beside the 32-bit values.
  using Column = ExchangeElements::Number;

  int radius = 1;
  ExchangeElements elements;
  /// Full side to full side, per full side e (voxel v = elements.voxelOf[e],
  /// so empty voxels cost nothing) the stencilHalf() values of
  /// S(v, v + offset) for the offsets from (0, 0, 0) on in offset index
  /// (dx + r) + (2r + 1)((dy + r) + (2r + 1)(dz + r)); zero past the domain
  /// and where the other voxel has kappa_t = 0. S is exactly symmetric, so
  /// the lower offsets are the neighbours' (stencilEntry): half the memory.
  std::vector<float> stencil;
  /// The other near pairs (a front side or a patch at one end or both), as
  /// rows over elements: row e is [extraStart[e], extraStart[e + 1]).
  std::vector<Index> extraStart;
  std::vector<Column> extraColumn;
  std::vector<float> extraValue;
  /// Per element: its row target less its near row over the partition
  /// (full sides and patches), >= 0: the exchange links must carry.
  std::vector<double> far;
  /// With NearFieldOptions::emptyViews, the views of the empty voxels.
  ViewRows views;

  static int stencilSizeFor(int r) { return (2 * r + 1) * (2 * r + 1) * (2 * r + 1); }
  /// Offsets stored per full side: (0, 0, 0) and those after it.
  static int stencilHalfFor(int r) { return (stencilSizeFor(r) + 1) / 2; }
  int stencilSize() const { return stencilSizeFor(radius); }
  int stencilHalf() const { return stencilHalfFor(radius); }
  /// S(e, f) for full sides e and f at offset index o from e: e's own entry
  /// from the centre on, f's for the mirrored offset before it.
  float entryTowards(Index e, Index f, int o) const
  {
    const int size = stencilSize(), half = stencilHalfFor(radius), centre = size - half;
    return o >= centre ? stencil[std::size_t(e) * half + (o - centre)]
                       : stencil[std::size_t(f) * half + (size - 1 - o - centre)];
  }
  /// S(v, v + offset) of full side e at offset index o, any offset (0 past
  /// the domain and towards voxels that are not full sides).
  float stencilEntry(const Grid& grid, Index e, int o) const;
  int offsetIndex(int dx, int dy, int dz) const
  {
    const int w = 2 * radius + 1;
    return (dx + radius) + w * ((dy + radius) + w * (dz + radius));
  }
  /// S(e, e), the self term.
  double diagonal(Index e) const;
  /// y[e] += sum over near j of S(e, j) x[j], for every element e; with
  /// skipDiagonal the self terms are left out. Deterministic, parallel.
  void apply(const Grid& grid, const double* x, double* y, bool skipDiagonal) const;
  std::size_t bytes() const;
};

NearField computeNearField(const Scene& scene,
                           int channel,
                           const NearFieldOptions& options,
                           const ProgressRange& progress = ProgressRange());

/// The views of the empty voxels next to the elements (or to the walls),
/// whatever options.emptyViews says: computeNearField's with it, and on
/// their own for a solve that needs them only for its fields, after the
/// memory of its links is free.
ViewRows computeViewRows(const Scene& scene,
                         int channel,
                         const ExchangeElements& elements,
                         const NearFieldOptions& options,
                         const ProgressRange& progress = ProgressRange());

} // namespace volrad
