// SPDX-License-Identifier: BSD-3-Clause
// The hierarchical solver's accuracy yardstick, shared by its tests and by
// BenchAccuracy: the dense solver at a finer quadrature than its default,
// and the RMS relative difference of G over the voxels that matter.
#pragma once

#include "volrad/DenseSolver.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace volrad::test {

/// The dense solver with a finer quadrature than its default, whose own
/// noise (about 0.6% rms in G at the default) would otherwise take a large
/// share of the 1% budget.
inline DenseSolverOptions fineDenseOptions()
{
  DenseSolverOptions o;
  o.quadrature.voxelPointsPerAxis = 10;
  o.quadrature.voxelDirections = 16;
  return o;
}

/// f(index, relative difference) for each voxel whose reference G is above
/// 1% of the largest: the voxels the accuracy figures speak of.
template<class F>
void forEachRelative(const std::vector<double>& ref, const std::vector<double>& x, F&& f)
{
  const double big = *std::max_element(ref.begin(), ref.end());
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (ref[i] >= 0.01 * big) {
      f(i, (x[i] - ref[i]) / ref[i]);
    }
  }
}

/// RMS relative difference of G over voxels with G above 1% of the largest
/// (and, given `keep`, over those of them for which keep(index) holds).
template<class Keep>
double rmsRelative(const std::vector<double>& ref, const std::vector<double>& x, Keep&& keep)
{
  double sum = 0.0;
  long long n = 0;
  forEachRelative(ref, x, [&](std::size_t i, double r) {
    if (keep(i)) {
      sum += r * r;
      ++n;
    }
  });
  return std::sqrt(sum / double(std::max(n, 1LL)));
}

inline double rmsRelative(const std::vector<double>& ref, const std::vector<double>& x)
{
  return rmsRelative(ref, x, [](std::size_t) { return true; });
}

/// Largest relative difference of G over the same voxels.
inline double maxRelative(const std::vector<double>& ref, const std::vector<double>& x)
{
  double worst = 0.0;
  forEachRelative(ref, x, [&](std::size_t, double r) { worst = std::max(worst, std::abs(r)); });
  return worst;
}

} // namespace volrad::test
