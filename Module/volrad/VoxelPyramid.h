// SPDX-License-Identifier: BSD-3-Clause
/// @file VoxelPyramid.h
/// @brief The voxel hierarchy of the hierarchical solver (issue 4, first
/// part): voxels clustered 2x2x2 level by level up to a single root cell,
/// each cell keeping the mean, minimum and maximum extinction of the voxels
/// it covers, and transmittance marched at a chosen or adaptive resolution
/// with guaranteed bounds and empty-space skipping.
///
/// Level 0 is the voxel grid itself. A cell of level l covers 2^l voxels
/// along each axis; cells on the far edges may reach past the domain, where
/// the medium is vacuum (kappa_t = 0).
#pragma once

#include "volrad/Scene.h"

#include <vector>

namespace volrad {

class VoxelPyramid
{
public:
  /// Builds the levels for one channel of the scene (which must be valid).
  VoxelPyramid(const Scene& scene, int channel);

  int levels() const { return int(grids_.size()); }
  const Grid& grid(int level) const { return grids_[level]; }
  double meanKappaT(int level, Index cell) const { return mean_[level][cell]; }
  double minKappaT(int level, Index cell) const { return lowest(level)[cell]; }
  double maxKappaT(int level, Index cell) const { return highest(level)[cell]; }

  /// Optical depth of the segment a -> b with guaranteed bounds:
  /// lower <= exact <= upper, and |estimate - exact| <= upper - lower.
  struct Depth
  {
    double estimate = 0.0, lower = 0.0, upper = 0.0;
    long long cellsVisited = 0;
  };

  /// Marches the cells of one level (level 0: exact, lower = upper).
  Depth opticalDepth(const Vec3& a, const Vec3& b, int level) const;
  /// The same, and in `lowerWithin` the lower bound of the part of the
  /// segment between distances s0 and s1 from a (one march for both).
  Depth opticalDepth(const Vec3& a,
                     const Vec3& b,
                     int level,
                     double s0,
                     double s1,
                     double& lowerWithin) const;

  /// Marches from the root down, refining only cells whose bounds are
  /// wider than their share of `tolerance` and skipping empty cells whole:
  /// the result is within `tolerance` of the exact optical depth.
  Depth opticalDepthAdaptive(const Vec3& a, const Vec3& b, double tolerance) const;

private:
  /// The march's decision on one cell of `level` crossed for length l:
  /// true when it is settled there (empty, voxels, or bounds within the
  /// per-length tolerance; added to out), false when it is walked finer.
  bool settleCell(int level, Index cell, double l, double tolerancePerLength, Depth& out) const;
  void march(int level,
             const Vec3& o,
             const Vec3& d,
             double t0,
             double t1,
             double tolerancePerLength,
             Depth& out) const;

  /// A level's minima and maxima: on level 0 the voxels' own extinction.
  const std::vector<float>& lowest(int level) const { return level == 0 ? mean_[0] : min_[level]; }
  const std::vector<float>& highest(int level) const { return level == 0 ? mean_[0] : max_[level]; }

  std::vector<Grid> grids_;
  /// Per level; min_ and max_ are empty on level 0 (its one value a voxel,
  /// kept once: 8 bytes a voxel fewer).
  std::vector<std::vector<float>> mean_, min_, max_;
};

} // namespace volrad
