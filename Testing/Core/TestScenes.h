// SPDX-License-Identifier: BSD-3-Clause
// Scenes shared by the core tests.
#pragma once

#include "volrad/Sampling.h"
#include "volrad/Scene.h"

#include <cmath>

namespace volrad::test {

/// An n^3 grid over the unit cube (spacing 1/n), all coefficients zero.
inline Scene cubeScene(int n, int channels = 1)
{
  Scene s;
  s.grid.dims = { n, n, n };
  s.grid.spacing = Vec3::Constant(1.0 / n);
  s.grid.origin = Vec3::Constant(0.5 / n);
  s.channels = channels;
  s.allocate();
  return s;
}

/// A smooth, strongly varying positive field in [lo, hi] (deterministic).
inline double lumpy(const Vec3& x, double lo, double hi, double phase = 0.0)
{
  const double f = 0.5 + 0.5 * std::sin(7.0 * x[0] + phase) * std::cos(5.0 * x[1] - 2.0 * phase) *
                           std::sin(6.0 * x[2] + 1.0 + phase);
  return lo + (hi - lo) * f;
}

inline void fill(Scene& s, std::vector<float>& a, int c, double (*f)(const Vec3&))
{
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    a[std::size_t(v) * s.channels + c] = float(f(s.grid.voxelCentre(v)));
  }
}

/// Outward-ish normals everywhere: from the cube's centre to the voxel.
inline void radialNormals(Scene& s)
{
  s.normals.resize(s.grid.voxelCount());
  const Vec3 c = 0.5 * (s.grid.lower() + s.grid.upper());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    Vec3 d = s.grid.voxelCentre(v) - c;
    if (d.norm() < 1e-9) {
      d = Vec3::UnitZ();
    }
    d.normalize();
    s.normals[v] = { float(d[0]), float(d[1]), float(d[2]) };
  }
}

inline void setAllFaces(Scene& s, const BoundaryCondition& bc)
{
  for (auto& b : s.boundary) {
    b = bc;
  }
}

} // namespace volrad::test
