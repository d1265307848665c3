// SPDX-License-Identifier: BSD-3-Clause
/// @file DenseSolver.h
/// @brief The reference solver: every pairwise exchange factor, one linear
/// system per channel, solved to a tight tolerance.
///
/// Equations (physics.md sections 3-4), for the element radiosities x
/// (Q_I of full sides, Q_D of front sides, B of patches), collided powers
/// C = S x + D (S the exchange areas, D the direct light):
///   Q_I = (kappa_a E_I + sigma_i C_full  / (4 kappa_t V)) / kappa_t
///   Q_D = (kappa_a E_D + sigma_d C_front / (2 kappa_t V)) / kappa_t
///   B   = E_w + rho C_patch / A   (walls),   B = pi L_env (open faces)
/// The system (I - diag(c) S) x = e + diag(c) D is solved by BiCGSTAB with
/// Jacobi scaling (which takes the self terms implicitly), with an LU
/// fallback. Memory grows as the square of the element count; above
/// `memoryLimitBytes` the solver refuses before allocating.
#pragma once

#include "volrad/Progress.h"
#include "volrad/Quadrature.h"
#include "volrad/Scene.h"
#include "volrad/Solution.h"

#include <cstddef>

namespace volrad {

struct DenseSolverOptions
{
  QuadratureSettings quadrature;
  double tolerance = 1e-11; ///< relative residual of the linear solve
  int maxIterations = 5000;
  /// Default 4 GiB: about 20^3 voxels with normals, 22^3 without.
  double memoryLimitBytes = 4.0 * 1024 * 1024 * 1024;
  int threads = 0;           ///< 0: all cores
  ProgressCallback progress; ///< may be empty
};

/// Peak bytes the dense solve of this scene needs (exchange areas, system).
double estimateDenseSolverBytes(const Scene& scene);

/// Validates the scene, checks the memory estimate, solves.
/// Throws volrad::Error (bad scene, too large) or volrad::Aborted.
Solution solveDense(const Scene& scene, const DenseSolverOptions& options = {});

} // namespace volrad
