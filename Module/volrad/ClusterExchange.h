// SPDX-License-Identifier: BSD-3-Clause
/// @file ClusterExchange.h
/// @brief Exchange areas between clusters of voxels (cells of the voxel
/// pyramid) far apart, the links of the hierarchical solver (issue 4):
///
///   S(A, B) ~ sigma_A sigma_B tau(A, B) / (pi r^2)
///
/// with sigma_X the sum over X's voxels of their effective extinction
/// cross-section (direction-averaged), r the distance between the clusters'
/// sigma-weighted centroids and tau the transmittance along the line between
/// the centroids (from the pyramid, within a tolerance) less half a mean
/// voxel chord at each end, the part each voxel's cross-section holds. It is the
/// point-to-point form of physics.md section 4 with each voxel's own
/// attenuation built into its cross-section; its error falls as the clusters
/// get small against their distance and optically thin (Sillion 1995,
/// isotropic clusters).
#pragma once

#include "volrad/VoxelPyramid.h"

#include <vector>

namespace volrad {

/// Mean extinction cross-section of a voxel over all directions [length^2]:
/// (S/4)(1 - exp(-kappa_t 4V/S)), S the voxel's surface: kappa_t V when thin,
/// the mean projected area S/4 when thick (Cauchy).
double effectiveCrossSection(double kappaT, const Vec3& spacing);

class ClusterExchange
{
public:
  ClusterExchange(const Scene& scene, int channel, const VoxelPyramid& pyramid);

  double sigma(int level, Index cell) const { return sigma_[level][cell]; }
  const Vec3& centroid(int level, Index cell) const { return centroid_[level][cell]; }

  /// S(A, B) between cell a of level la and cell b of level lb (distinct,
  /// non-overlapping cells); depthTolerance bounds the optical-depth error.
  double exchange(int la, Index a, int lb, Index b, double depthTolerance) const;

private:
  const VoxelPyramid& pyramid_;
  std::vector<std::vector<double>> sigma_;
  std::vector<std::vector<Vec3>> centroid_;
  double voxelVolume_ = 0.0, voxelSurface_ = 0.0;
};

} // namespace volrad
