// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Normals.h"

#include "volrad/Error.h"

#include <algorithm>
#include <cmath>

namespace volrad {

std::vector<Vec3> scalarGradient(const Grid& g, const std::vector<double>& s)
{
  const Index nv = g.voxelCount();
  if (Index(s.size()) != nv) {
    throw Error("gradient: the scalar field has " + std::to_string(s.size()) +
                " values, expected " + std::to_string(nv));
  }
  std::vector<Vec3> grad(nv, Vec3::Zero());
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
  }
  return grad;
}

std::vector<Normal> gradientNormals(const Grid& g,
                                    const std::vector<double>& s,
                                    double relativeThreshold)
{
  const std::vector<Vec3> grad = scalarGradient(g, s);
  double largest = 0.0;
  for (const Vec3& d : grad) {
    largest = std::max(largest, d.norm());
  }
  std::vector<Normal> n(grad.size(), Normal{ 0.f, 0.f, 0.f });
  const double threshold = relativeThreshold * largest;
  for (std::size_t v = 0; v < grad.size(); ++v) {
    const double m = grad[v].norm();
    if (m > threshold && m > 0.0) {
      const Vec3 d = -grad[v] / m;
      n[v] = Normal{ float(d[0]), float(d[1]), float(d[2]) };
    }
  }
  return n;
}

} // namespace volrad
