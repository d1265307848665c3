// SPDX-License-Identifier: BSD-3-Clause
/// @file HierarchicalSolver.h
/// @brief The hierarchical iterative shooting solver (physics.md section 1):
/// exact near and self interactions (NearField), links between clusters of
/// voxels and patches found by error-driven refinement (LinkSet, ClusterTree)
/// for everything farther, and progressive shooting of unshot radiosity
/// through near field and links with push/pull through the hierarchy.
///
/// Shooting: every element keeps its radiosity and the part not yet shot,
/// both starting at its emission plus its response to the direct light.
/// Each sweep shoots all unshot radiosity at once (deterministic, parallel:
/// every receiver gathers what its partners shoot), each receiver's self
/// term taken implicitly; the sweeps stop when the largest unshot radiosity
/// dQ_max, relative to each element's radiosity and with the tail the
/// convergence rate promises, falls below epsilon, and the unshot power
/// below epsilon of the power first shot.
/// Links are refined twice: from the emission and direct light, then again
/// from the first solution, which then continues with the finer links.
///
/// In high-albedo, optically thick media plain sweeps converge slowly (each
/// removes only the light that leaks or is absorbed, 1 - albedo of it);
/// Method::Automatic then switches to BiCGSTAB on the same operator (a
/// Krylov gathering over the same near field and links) once sweeps are
/// slow (three in a row shoot less than 40% of the unshot radiosity).
#pragma once

#include "volrad/Progress.h"
#include "volrad/Quadrature.h"
#include "volrad/Scene.h"
#include "volrad/Solution.h"

#include <vector>

namespace volrad {

struct HierarchicalOptions
{
  enum class Iteration
  {
    Shooting, ///< sweeps of shooting only
    Krylov,   ///< BiCGSTAB from the start
    Automatic ///< shooting, BiCGSTAB when the sweeps are slow
  };
  /// Stop when every element's unshot radiosity, times the geometric tail
  /// the observed convergence rate still promises (rate / (1 - rate)), is
  /// below epsilon times its radiosity (plus 1e-3 of the largest, so that
  /// dark elements do not rule; BiCGSTAB: its residual, without a tail), and
  /// the power still unshot (BiCGSTAB: the residual's) is below epsilon of
  /// the power first shot (the emission and the direct light's first
  /// scattering): the share of the light whose absorption or escape the
  /// fields would still miss. Links are refined until the power a link
  /// may carry wrongly is below linkTolerance times the total power leaving
  /// all elements; by default linkTolerance = 3e-4 epsilon. A view of empty
  /// space (a link whose end holds no medium: only that voxel's G) is also
  /// fine enough when that power is below linkTolerance / 3e-4 (epsilon, by
  /// default) of the direct light's power on the empty end, taken as if it
  /// held the mean medium.
  double epsilon = 1e-3;
  double linkTolerance = 0.0; ///< 0: 3e-4 epsilon
  int maxIterations = 1000000;
  Iteration iteration = Iteration::Automatic;
  int nearRadius = 1;
  /// Empty voxels (kappa_t = 0, per channel) only let light through, yet their fields
  /// (G of empty space) cost views and links like the medium's. false: a
  /// sparse solve that skips them: their fields are 0 (like the inactive
  /// background of an OpenVDB grid), empty space costs no links, no views
  /// and no iterations, and the medium's fields and the energy terms are
  /// those of the full solve (the links between medium and walls are the
  /// same ones).
  bool emptySpaceFields = true;
  /// The solve refuses with volrad::Error, before it allocates what would
  /// pass it, when its structures would need more (0: half the machine's
  /// physical memory).
  double memoryLimitBytes = 0.0;
  QuadratureSettings quadrature;
  int threads = 0; ///< 0: all cores; 1: single-threaded (bit-for-bit repeatable, as is any count)
  ProgressCallback progress;
};

struct HierarchicalReport
{
  /// Per sweep or Krylov step, the largest change relative to each element's
  /// radiosity (plus 1e-3 of the largest), as the stopping test reads it.
  std::vector<double> dQmaxHistory;
  long long shots = 0;              ///< element shots (an element with unshot radiosity, per sweep)
  std::vector<long long> linksPerLevel;
  std::size_t peakBytes = 0; ///< the solver's largest structures at once (estimate)
  double nearSeconds = 0.0, linkSeconds = 0.0, iterationSeconds = 0.0;
  bool usedKrylov = false;
};

/// Validates the scene and solves. Throws volrad::Error or volrad::Aborted.
Solution solveHierarchical(const Scene& scene,
                           const HierarchicalOptions& options = {},
                           HierarchicalReport* report = nullptr);

} // namespace volrad
