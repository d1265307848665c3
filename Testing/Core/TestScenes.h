// SPDX-License-Identifier: BSD-3-Clause
// Scenes shared by the core tests.
#pragma once

#include "volrad/Sampling.h"
#include "volrad/Scene.h"

#include <array>
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

/// A grey lumpy medium (kappa_a up to kappaA, sigma_i up to 3) on the given
/// grid, empty where voxel index `axis` lies in [emptyFrom, emptyTo).
inline Scene lumpySlabScene(const std::array<int, 3>& dims,
                            const Vec3& spacing,
                            const Vec3& origin,
                            int axis,
                            int emptyFrom,
                            int emptyTo,
                            double kappaA)
{
  Scene s;
  s.grid.dims = dims;
  s.grid.spacing = spacing;
  s.grid.origin = origin;
  s.allocate();
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    const int i = s.grid.ijk(v)[axis];
    const bool empty = i >= emptyFrom && i < emptyTo;
    s.kappaA[v] = empty ? 0.f : float(lumpy(x, 0.0, kappaA));
    s.sigmaI[v] = empty ? 0.f : float(lumpy(x, 0.0, 3.0, 1.0));
  }
  return s;
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

/// Two reflecting walls, an emitting one and a faint sky on the top face.
inline void addMixedBoundary(Scene& s)
{
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  wall.reflectance = uniformChannels(0.6);
  s.boundary[static_cast<int>(Face::ZMin)] = wall;
  s.boundary[static_cast<int>(Face::XMin)] = wall;
  wall.reflectance = uniformChannels(0.3);
  wall.emission = uniformChannels(0.5);
  s.boundary[static_cast<int>(Face::YMax)] = wall;
  s.boundary[static_cast<int>(Face::ZMax)].radiance = uniformChannels(0.2);
}

/// A scattering medium with a surface-like shell around the centre (normals
/// pointing outwards), lit by a sun.
inline Scene shellTestScene(int n)
{
  Scene s = cubeScene(n);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.1, 2.0); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 0.5, 4.0, 0.9); });
  fill(s, s.sigmaD, 0, [](const Vec3& x) {
    const double r = (x - Vec3::Constant(0.5)).norm();
    return (r > 0.25 && r < 0.4) ? 6.0 : 0.0;
  });
  radialNormals(s);
  s.directionalLights.push_back({ Vec3(0.3, -0.5, -1.0), uniformChannels(2.0) });
  return s;
}

/// An RGB medium, every coefficient differing per channel, with an emitting
/// bottom layer and a sun.
inline Scene rgbTestScene(int n)
{
  Scene s = cubeScene(n, 3);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    for (int c = 0; c < 3; ++c) {
      s.kappaA[v * 3 + c] = float(lumpy(x, 0.1, 1.5 + c, 0.5 * c));
      s.sigmaI[v * 3 + c] = float(lumpy(x, 0.5, 5.0 - c, 1.0 + c));
      s.emissionI[v * 3 + c] = float(x[2] < 0.3 ? 0.5 * (c + 1) : 0.0);
    }
  }
  s.directionalLights.push_back({ Vec3(-1.0, 0.2, -0.4), { 1.0, 0.8, 0.5 } });
  return s;
}

/// Walls (reflecting and emitting), volume emission at the bottom, sky.
inline Scene wallsScene(int n)
{
  Scene s = cubeScene(n);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.05, 1.0, 0.3); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 1.0, 6.0, 2.1); });
  fill(s, s.emissionI, 0, [](const Vec3& x) { return x[2] < 0.25 ? 1.0 : 0.0; });
  addMixedBoundary(s);
  return s;
}

/// A point light inside a lumpy scattering medium.
inline Scene pointLightScene(int n)
{
  Scene s = cubeScene(n);
  fill(s, s.kappaA, 0, [](const Vec3& x) { return lumpy(x, 0.2, 1.0, 1.3); });
  fill(s, s.sigmaI, 0, [](const Vec3& x) { return lumpy(x, 4.0, 12.0, 0.4); });
  s.pointLights.push_back({ Vec3(0.47, 0.52, 0.5), uniformChannels(1.0) });
  return s;
}

/// One extinction for all channels, coloured albedo, light, sky and wall:
/// the channels share the near field, the hierarchy and the links.
inline Scene greyColouredScene(int n)
{
  Scene s = cubeScene(n, 3);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    const double kt = lumpy(x, 1.0, 6.0, 0.7);
    for (int c = 0; c < 3; ++c) {
      const double albedo = 0.9 - 0.2 * c;
      s.kappaA[v * 3 + c] = float((1.0 - albedo) * kt);
      s.sigmaI[v * 3 + c] = float(albedo * kt);
    }
  }
  s.directionalLights.push_back({ Vec3(0.3, 0.2, -1.0), { 1.0, 0.7, 0.4 } });
  s.boundary[static_cast<int>(Face::ZMax)].radiance = { 0.02, 0.04, 0.08 };
  s.boundary[static_cast<int>(Face::ZMin)].type = BoundaryCondition::Type::Wall;
  s.boundary[static_cast<int>(Face::ZMin)].reflectance = { 0.6, 0.5, 0.4 };
  return s;
}

inline void setAllFaces(Scene& s, const BoundaryCondition& bc)
{
  for (auto& b : s.boundary) {
    b = bc;
  }
}

} // namespace volrad::test
