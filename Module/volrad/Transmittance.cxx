// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Transmittance.h"

#include "volrad/VoxelTraversal.h"

#include <cmath>

namespace volrad {

double opticalDepth(const Scene& scene, int channel, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double length = ab.norm();
  if (length <= 0.0) {
    return 0.0;
  }
  double tau = 0.0;
  traverseVoxels(scene.grid, a, ab / length, length, [&](Index v, double l, double) {
    tau += scene.kappaTAt(v, channel) * l;
    return true;
  });
  return tau;
}

double transmittance(const Scene& scene, int channel, const Vec3& a, const Vec3& b)
{
  return std::exp(-opticalDepth(scene, channel, a, b));
}

} // namespace volrad
