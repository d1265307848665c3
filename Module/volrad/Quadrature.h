// SPDX-License-Identifier: BSD-3-Clause
/// @file Quadrature.h
/// @brief Settings of the ray quadratures behind the exchange factors and
/// the direct light. Larger values: smaller quadrature error, longer solves
/// (the cost is linear in each). Many points with few directions each
/// (every point gets its own random spin) stratify the 4-D integrals over
/// lines better than few points with many directions.
#pragma once

#include <cstdint>

namespace volrad {

struct QuadratureSettings
{
  /// Voxels: stratified points per face of the voxel, n^2 on each of its 6 faces.
  int voxelPointsPerAxis = 6;
  /// Cosine-weighted outgoing directions per voxel face point (a voxel
  /// sends 6 n^2 times this many rays).
  int voxelDirections = 8;
  /// Stratified points per wall or open patch: n^2.
  int patchPointsPerAxis = 12;
  /// Cosine-weighted directions per patch point.
  int patchDirections = 16;
  /// Directional lights: n^2 parallel rays through each boundary patch they enter by.
  int lightRaysPerPatchAxis = 8;
  /// Point lights: rays per steradian are chosen so that a voxel at the far
  /// side of the domain is crossed by about this many rays.
  int pointLightRaysPerVoxel = 64;
  /// Seed of every random stream (rotations, jitter): same seed, same result.
  std::uint64_t seed = 0x766f6c726164ULL;
  /// The exchange areas' counts (voxel and patch points and directions) all >= 1.
  bool exchangeCountsValid() const
  {
    return voxelPointsPerAxis >= 1 && voxelDirections >= 1 && patchPointsPerAxis >= 1 &&
           patchDirections >= 1;
  }
};

} // namespace volrad
