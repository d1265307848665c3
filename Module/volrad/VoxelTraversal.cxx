// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/VoxelTraversal.h"

namespace volrad {

bool clipToDomain(const Grid& g, const Vec3& o, const Vec3& d, double& t0, double& t1, Face* entry)
{
  const Vec3 lo = g.lower();
  const Vec3 hi = g.upper();
  t0 = -std::numeric_limits<double>::infinity();
  t1 = std::numeric_limits<double>::infinity();
  Face entryFace = Face::XMin;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) {
        return false;
      }
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a];
    double tb = (hi[a] - o[a]) / d[a];
    // Entering through the min face when travelling in +a.
    Face fa = makeFace(a, d[a] < 0.0);
    if (ta > tb) {
      std::swap(ta, tb);
    }
    if (ta > t0) {
      t0 = ta;
      entryFace = fa;
    }
    t1 = std::min(t1, tb);
  }
  if (entry) {
    *entry = entryFace;
  }
  return t0 <= t1;
}

} // namespace volrad
