// SPDX-License-Identifier: BSD-3-Clause
/// @file Solve.h
/// @brief One entry point for every solver: the method, epsilon and
/// iteration limit of a scene file's `solver` settings, plus threads and a
/// progress callback, to solveHierarchical or solveDense.
#pragma once

#include "volrad/Progress.h"
#include "volrad/SceneDescription.h"
#include "volrad/Solution.h"

namespace volrad {

/// Validates the scene and solves it with `settings.method`.
/// Throws volrad::Error or volrad::Aborted.
Solution solve(const Scene& scene,
               const SolverSettings& settings,
               int threads = 0,
               const ProgressCallback& progress = {});

} // namespace volrad
