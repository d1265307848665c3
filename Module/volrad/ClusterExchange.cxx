// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/ClusterExchange.h"

#include "volrad/Sampling.h"
#include "volrad/VoxelTraversal.h"

#include <cmath>

namespace volrad {

double effectiveCrossSection(double kappaT, const Vec3& h)
{
  const double surface = 2.0 * (h[0] * h[1] + h[1] * h[2] + h[0] * h[2]);
  const double meanChord = 4.0 * h.prod() / surface;
  return 0.25 * surface * -std::expm1(-kappaT * meanChord);
}

ClusterExchange::ClusterExchange(const Scene& scene, int channel, const VoxelPyramid& pyramid)
  : pyramid_(pyramid)
{
  const Grid& g = scene.grid;
  voxelVolume_ = g.voxelVolume();
  voxelSurface_ = 2.0 * (g.spacing[0] * g.spacing[1] + g.spacing[1] * g.spacing[2] + g.spacing[0] * g.spacing[2]);
  sigma_.resize(pyramid.levels());
  centroid_.resize(pyramid.levels());
  sigma_[0].resize(g.voxelCount());
  centroid_[0].resize(g.voxelCount());
  for (Index v = 0; v < g.voxelCount(); ++v) {
    sigma_[0][v] = effectiveCrossSection(scene.kappaTAt(v, channel), g.spacing);
    centroid_[0][v] = g.voxelCentre(v);
  }
  for (int l = 1; l < pyramid.levels(); ++l) {
    const Grid& coarse = pyramid.grid(l);
    const Grid& fine = pyramid.grid(l - 1);
    sigma_[l].assign(coarse.voxelCount(), 0.0);
    centroid_[l].assign(coarse.voxelCount(), Vec3::Zero());
    for (Index f = 0; f < fine.voxelCount(); ++f) {
      const auto c = fine.ijk(f);
      const Index parent = coarse.index(c[0] / 2, c[1] / 2, c[2] / 2);
      sigma_[l][parent] += sigma_[l - 1][f];
      centroid_[l][parent] += sigma_[l - 1][f] * centroid_[l - 1][f];
    }
    for (Index p = 0; p < coarse.voxelCount(); ++p) {
      centroid_[l][p] =
        sigma_[l][p] > 0.0 ? Vec3(centroid_[l][p] / sigma_[l][p]) : coarse.voxelCentre(p);
    }
  }
}

double ClusterExchange::exchange(int la, Index a, int lb, Index b, double depthTolerance) const
{
  const double sa = sigma_[la][a], sb = sigma_[lb][b];
  if (sa <= 0.0 || sb <= 0.0) {
    return 0.0;
  }
  const Vec3& ca = centroid_[la][a];
  const Vec3& cb = centroid_[lb][b];
  const Vec3 ab = cb - ca;
  const double r = ab.norm();
  const Vec3 w = ab / r;
  // Each voxel's own attenuation is in its cross-section: about half its
  // mean chord at each end; the rest of the path, through the clusters'
  // other voxels and the medium between, is marched.
  const double halfChord = 2.0 * voxelVolume_ / voxelSurface_;
  const double t0 = halfChord;
  const double t1 = r - halfChord;
  double tau = 1.0;
  if (t1 > t0) {
    tau =
      std::exp(-pyramid_.opticalDepthAdaptive(ca + t0 * w, ca + t1 * w, depthTolerance).estimate);
  }
  return sa * sb * tau / (kPi * r * r);
}

} // namespace volrad
