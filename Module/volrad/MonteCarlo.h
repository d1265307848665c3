// SPDX-License-Identifier: BSD-3-Clause
/// @file MonteCarlo.h
/// @brief An independent, unbiased estimate of G and G+ for the same
/// piecewise-constant scene (physics.md 5.6): analog photon tracing with
/// the track-length estimator, exact voxel traversal, seeded streams.
///
/// Use it to check a solve. Standard errors come from independent batches;
/// the result depends only on (scene, photons, batches, seed), not on the
/// number of threads.
#pragma once

#include "volrad/Scene.h"

#include <cstdint>
#include <vector>

namespace volrad {

struct MonteCarloOptions
{
  long long photons = 1000000; ///< per channel
  int batches = 16;            ///< for the standard errors (>= 2)
  std::uint64_t seed = 1;
  int threads = 0; ///< 0: all cores
  /// false: the transport equation in the piecewise-constant medium (the
  /// exact answer the grid converges to). true: the zonal model the
  /// radiosity solvers discretise, where light scattered in a voxel leaves
  /// from a uniformly distributed point of it, as the solvers assume; this
  /// isolates their quadrature error from the zonal discretisation error.
  bool zonal = false;
};

struct MonteCarloEstimate
{
  int channels = 1;
  /// Per voxel and channel (v * channels + c), with standard errors.
  std::vector<double> G, GStdErr, Gplus, GplusStdErr;
  double seconds = 0.0;
};

MonteCarloEstimate estimateMonteCarlo(const Scene& scene, const MonteCarloOptions& options = {});

} // namespace volrad
