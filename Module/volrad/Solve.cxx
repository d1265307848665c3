// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Solve.h"

#include "volrad/DenseSolver.h"
#include "volrad/Error.h"
#include "volrad/HierarchicalSolver.h"

#include <algorithm>
#include <limits>

namespace volrad {

Solution solve(const Scene& scene,
               const SolverSettings& settings,
               int threads,
               const ProgressCallback& progress)
{
  if (settings.method == "dense") {
    DenseSolverOptions o;
    o.threads = threads;
    o.progress = progress;
    if (settings.memoryBudgetBytes > 0.0) {
      o.memoryLimitBytes = settings.memoryBudgetBytes;
    }
    return solveDense(scene, o);
  }
  if (settings.method != "hierarchical") {
    throw Error("unknown solver method '" + settings.method + "'");
  }
  HierarchicalOptions o;
  o.epsilon = settings.epsilon;
  o.maxIterations =
    int(std::min<long long>(settings.maxIterations, std::numeric_limits<int>::max()));
  o.threads = threads;
  o.progress = progress;
  o.memoryLimitBytes = settings.memoryBudgetBytes;
  o.emptySpaceFields = settings.emptySpaceFields;
  return solveHierarchical(scene, o);
}

} // namespace volrad
