// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Normals.h"

#include "volrad/Error.h"

#include <cmath>

namespace volrad {

std::vector<Normal> gradientNormals(const Grid& g,
                                    const std::vector<double>& s,
                                    double relativeThreshold)
{
  const Index nv = g.voxelCount();
  if (Index(s.size()) != nv) {
    throw Error("normals: the scalar field has " + std::to_string(s.size()) + " values, expected " +
                std::to_string(nv));
  }
  std::vector<Vec3> grad(nv, Vec3::Zero());
  double largest = 0.0;
  for (Index v = 0; v < nv; ++v) {
    const auto c = g.ijk(v);
    for (int a = 0; a < 3; ++a) {
      if (g.dims[a] < 2) {
        continue;
      }
      auto c0 = c, c1 = c;
      c0[a] = std::max(0, c[a] - 1);
      c1[a] = std::min(g.dims[a] - 1, c[a] + 1);
      const double h = (c1[a] - c0[a]) * g.spacing[a];
      grad[v][a] = (s[g.index(c1[0], c1[1], c1[2])] - s[g.index(c0[0], c0[1], c0[2])]) / h;
    }
    largest = std::max(largest, grad[v].norm());
  }
  std::vector<Normal> n(nv, Normal{ 0.f, 0.f, 0.f });
  const double threshold = relativeThreshold * largest;
  for (Index v = 0; v < nv; ++v) {
    const double m = grad[v].norm();
    if (m > threshold && m > 0.0) {
      const Vec3 d = -grad[v] / m;
      n[v] = Normal{ float(d[0]), float(d[1]), float(d[2]) };
    }
  }
  return n;
}

} // namespace volrad
