// SPDX-License-Identifier: BSD-3-Clause
/// @file Solution.h
/// @brief What a solve returns: the fields of physics.md section 6 and the
/// energy terms of section 5.2.
#pragma once

#include "volrad/Grid.h"

#include <cstddef>
#include <string>
#include <vector>

namespace volrad {

/// Power balance of one channel [W] (physics.md 5.2):
/// emitted() = absorbedVoxels + absorbedWalls + escaped for an exact solve.
struct EnergyTerms
{
  double emittedVoxels = 0.0;       ///< sum of (4 kappa_a E_I + 2 kappa_a E_D) V
  double emittedWalls = 0.0;        ///< sum of A E_w over wall patches
  double enteringLights = 0.0;      ///< directional and point light that entered
  double enteringEnvironment = 0.0; ///< pi L_env A over open patches
  double absorbedVoxels = 0.0;      ///< sum of (kappa_a G + sigma_d (G - G+)) V
  double absorbedWalls = 0.0;       ///< sum of (1 - rho) H A over wall patches
  double escaped = 0.0;             ///< H A over open patches

  double emitted() const
  {
    return emittedVoxels + emittedWalls + enteringLights + enteringEnvironment;
  }
  double removed() const { return absorbedVoxels + absorbedWalls + escaped; }
  /// |emitted - removed| / emitted (0 for a dark scene).
  double relativeResidual() const;
};

struct SolveStatistics
{
  std::string method; ///< "dense", "hierarchical"
  bool converged = false;
  long long iterations = 0; ///< linear-solver iterations (all channels)
  long long links = 0;      ///< exchange factors stored (all channels)
  double seconds = 0.0;
  double finalUnshot = 0.0;     ///< largest remaining change of a radiosity [W/m^2]
  double quadratureError = 0.0; ///< largest relative correction the smoothing made
  std::size_t estimatedBytes = 0;
};

/// Per voxel arrays are voxelCount * channels (index v * channels + c), per
/// patch arrays patchCount * channels.
struct Solution
{
  int channels = 1;
  std::vector<double> G;           ///< incident radiation [W/m^2]
  std::vector<double> Gplus;       ///< from the front half-space (0 where no normal)
  std::vector<double> QI;          ///< isotropic radiosity [W/m^2]
  std::vector<double> QD;          ///< diffuse radiosity [W/m^2]
  std::vector<double> absorbed;    ///< absorbed power density [W/length^3]
  std::vector<double> B;           ///< patch radiosity [W/m^2]
  std::vector<double> H;           ///< patch irradiance [W/m^2]
  std::vector<EnergyTerms> energy; ///< per channel
  SolveStatistics stats;
};

} // namespace volrad
