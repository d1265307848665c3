// SPDX-License-Identifier: BSD-3-Clause
// A voxel's gain towards a direction (VoxelGain.h) against its definition,
// the mean over the voxel of exp(tau(c) - tau(x)), integrated by the
// midpoint rule on a fine grid; its axis-aligned closed form; its thick
// limit, the projected area of a surface.
#include "volrad/VoxelGain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace volrad;

namespace {

/// Distance from x (relative to the voxel's centre) along w to the boundary.
double exitDistance(const Vec3& x, const Vec3& h, const Vec3& w)
{
  double d = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (w[a] != 0.0) {
      d = std::min(d, ((w[a] > 0.0 ? 0.5 : -0.5) * h[a] - x[a]) / w[a]);
    }
  }
  return d;
}

/// The mean over the voxel of exp(tau(c) - tau(x)), tau the depth from a
/// point along w to far away, with the medium outside of extinction
/// kappaOut: tau(x) - tau(c) = kappa (d_x - d_c) + kappaOut ((d_c - d_x) - w.x).
double midpointGain(double kappa, double kappaOut, const Vec3& h, const Vec3& w, int n = 96)
{
  const double dc = exitDistance(Vec3::Zero(), h, w);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const Vec3 x(((i + 0.5) / n - 0.5) * h[0], ((j + 0.5) / n - 0.5) * h[1],
                     ((k + 0.5) / n - 0.5) * h[2]);
        const double dx = exitDistance(x, h, w);
        sum += std::exp(-kappa * (dx - dc) - kappaOut * ((dc - dx) - w.dot(x)));
      }
    }
  }
  return sum / (double(n) * n * n);
}

const Vec3 kDirections[] = { Vec3(1.0, 0.0, 0.0), Vec3(0.8, -0.6, 0.0), Vec3(0.6, 0.6, 0.53),
                             Vec3(-0.577, 0.577, -0.577), Vec3(0.2, 0.3, -0.93) };

} // namespace

TEST(VoxelGain, MatchesItsDefinitionInBothLimits)
{
  const Vec3 h(1.0, 0.7, 1.3); // anisotropic spacing
  for (Vec3 w : kDirections) {
    w.normalize();
    for (double kappa : { 0.05, 0.5, 2.0, 6.0 }) {
      const double hom = std::exp(logVoxelGainHomogeneous(kappa, h, w));
      const double iso = std::exp(logVoxelGainIsolated(kappa, h, w));
      EXPECT_NEAR(hom, midpointGain(kappa, kappa, h, w), 2e-3 * hom) << kappa << " " << w.transpose();
      EXPECT_NEAR(iso, midpointGain(kappa, 0.0, h, w), 2e-3 * iso) << kappa << " " << w.transpose();
      // Nothing outside: no line from the voxel is more attenuated than
      // the same medium all round would make it, so the gain is larger.
      EXPECT_GE(iso, hom * (1.0 - 1e-12));
      // The weighted form is exact at both ends and lies between them.
      EXPECT_EQ(logVoxelGain(kappa, 1.0, h, w), logVoxelGainHomogeneous(kappa, h, w));
      EXPECT_EQ(logVoxelGain(kappa, 0.0, h, w), logVoxelGainIsolated(kappa, h, w));
      const double half = std::exp(logVoxelGain(kappa, 0.5, h, w));
      EXPECT_GE(half, hom * (1.0 - 1e-12));
      EXPECT_LE(half, iso * (1.0 + 1e-12));
    }
  }
}

TEST(VoxelGain, AlongAnAxisBothLimitsAreTheSlabs)
{
  // Every line leaves through the same face: sinh(z) / z, z = kappa h / 2.
  for (double kh : { 1e-6, 0.3, 3.0, 40.0 }) {
    const Vec3 h(kh, 2.0, 3.0);
    const double z = 0.5 * kh;
    const double expected = z + std::log(-std::expm1(-2.0 * z) / (2.0 * z));
    EXPECT_NEAR(logVoxelGainHomogeneous(1.0, h, Vec3(1, 0, 0)), expected, 1e-9 * std::max(1.0, z));
    EXPECT_NEAR(logVoxelGainIsolated(1.0, h, Vec3(1, 0, 0)), expected, 1e-9 * std::max(1.0, z));
  }
}

TEST(VoxelGain, ThickVoxelsShineLikeTheirSurface)
{
  // kappa V gain exp(-kappa d_c), what leaves towards w per unit of the
  // light outside, tends to the voxel's projected area sum_a |w_a| A_a.
  const Vec3 h(1.0, 0.7, 1.3);
  for (Vec3 w : kDirections) {
    w.normalize();
    const double projected =
      std::abs(w[0]) * h[1] * h[2] + std::abs(w[1]) * h[0] * h[2] + std::abs(w[2]) * h[0] * h[1];
    const double dc = exitDistance(Vec3::Zero(), h, w);
    for (double kappa : { 1e3, 1e5 }) {
      const double leaving =
        kappa * h.prod() * std::exp(logVoxelGainIsolated(kappa, h, w) - kappa * dc);
      EXPECT_NEAR(leaving, projected, 1e-2 * projected * 1e3 / kappa + 1e-9) << w.transpose();
      EXPECT_LE(leaving, projected * (1.0 + 1e-9));
    }
  }
}
