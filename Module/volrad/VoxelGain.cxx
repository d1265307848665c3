// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/VoxelGain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace volrad {

double logVoxelGainHomogeneous(double kappa, const Vec3& h, const Vec3& w)
{
  double log = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double z = 0.5 * kappa * h[a] * std::abs(w[a]);
    // log(sinh(z) / z), without overflow for thick voxels.
    log += z < 1e-4 ? z * z / 6.0 : z + std::log(-std::expm1(-2.0 * z) / (2.0 * z));
  }
  return log;
}

double logVoxelGainIsolated(double kappa, const Vec3& h, const Vec3& w)
{
  // With v_a = (distance from x to the exit face of axis a) / |w_a|,
  // uniform on [0, l_a], l_a = h_a / |w_a|: d_x = min_a v_a, and
  // P(d_x > s) = prod_a (1 - s / l_a) on [0, L], L = min_a l_a. So
  // E[exp(-kappa d_x)] = exp(-x) + x sum_k (-1)^(k+1) e_k g_k(x), x = kappa L,
  // e_k the elementary symmetric polynomials of r_a = L / l_a and
  // g_k(x) = int_0^1 t^k exp(-x t) dt.
  double r[3], L = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (w[a] != 0.0) {
      L = std::min(L, h[a] / std::abs(w[a]));
    }
  }
  if (!(L < std::numeric_limits<double>::infinity())) {
    return 0.0; // no direction
  }
  for (int a = 0; a < 3; ++a) {
    r[a] = std::abs(w[a]) * L / h[a];
  }
  const double e1 = r[0] + r[1] + r[2];
  const double e2 = r[0] * r[1] + r[1] * r[2] + r[0] * r[2];
  const double e3 = r[0] * r[1] * r[2];
  const double x = kappa * L;
  double g[4];
  if (x < 1.0) {
    // The series (the recurrence below loses digits for small x): 18 terms
    // leave less than x^18 / 18! < 2e-16.
    constexpr int kTerms = 18;
    static const auto inverse = [] {
      std::array<double, kTerms + 4> r{};
      for (int n = 1; n < kTerms + 4; ++n) {
        r[n] = 1.0 / n;
      }
      return r;
    }();
    g[1] = g[2] = g[3] = 0.0;
    double term = 1.0; // (-x)^n / n!
    for (int n = 0; n < kTerms; ++n) {
      g[1] += term * inverse[n + 2];
      g[2] += term * inverse[n + 3];
      g[3] += term * inverse[n + 4];
      term *= -x * inverse[n + 1];
    }
  } else {
    const double e = std::exp(-x);
    g[0] = -std::expm1(-x) / x;
    for (int k = 1; k < 4; ++k) {
      g[k] = (k * g[k - 1] - e) / x;
    }
  }
  const double mean = std::exp(-x) + x * (e1 * g[1] - e2 * g[2] + e3 * g[3]);
  return 0.5 * x + std::log(mean); // d_c = L / 2
}

double logVoxelGain(double kappa, double share, const Vec3& h, const Vec3& w)
{
  if (share >= 1.0) {
    return logVoxelGainHomogeneous(kappa, h, w);
  }
  if (share <= 0.0) {
    return logVoxelGainIsolated(kappa, h, w);
  }
  return share * logVoxelGainHomogeneous(kappa, h, w) +
         (1.0 - share) * logVoxelGainIsolated(kappa, h, w);
}

} // namespace volrad
