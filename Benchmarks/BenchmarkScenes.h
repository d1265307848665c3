// SPDX-License-Identifier: BSD-3-Clause
// The three benchmark scenes of the hierarchical solver (issue 4), at any
// resolution n^3 over the same physical box (a unit cube):
//  (a) a CT-like phantom: air around a head-like ellipsoid with a bone shell
//      (surface-like scattering, normals from the density gradient) around
//      soft tissue, lit by a directional light;
//  (b) a cloud: thresholded smooth noise, albedo 0.99, sun and blue sky;
//  (c) a homogeneous cube, albedo 0.99, 61 mean free paths across, with an
//      isotropic point light at its centre.
#pragma once

#include "volrad/Error.h"
#include "volrad/Normals.h"
#include "volrad/Scene.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace volrad::bench {

inline Scene unitCube(int n)
{
  Scene s;
  s.grid.dims = { n, n, n };
  s.grid.spacing = Vec3::Constant(1.0 / n);
  s.grid.origin = Vec3::Constant(0.5 / n);
  s.allocate();
  return s;
}

inline Scene phantomScene(int n)
{
  Scene s = unitCube(n);
  std::vector<double> density(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v) - Vec3(0.5, 0.5, 0.5);
    const double r = std::sqrt(std::pow(x[0] / 0.36, 2) + std::pow(x[1] / 0.42, 2) + std::pow(x[2] / 0.40, 2));
    // Units: lengths in dm, coefficients per dm (soft tissue ~ 10/dm).
    double d = 0.0;
    if (r < 0.88) {
      d = 1.0; // soft tissue
      s.kappaA[v] = 0.5f;
      s.sigmaI[v] = 10.0f;
    } else if (r < 1.0) {
      d = 2.0; // bone
      s.kappaA[v] = 5.0f;
      s.sigmaI[v] = 5.0f;
      s.sigmaD[v] = 40.0f;
    }
    density[v] = d;
  }
  s.normals = gradientNormals(s.grid, density);
  // Bone voxels with no gradient (none here, but keep the scene valid).
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    if (s.sigmaD[v] > 0.f && !s.hasNormal(v)) {
      s.sigmaD[v] = 0.f;
    }
  }
  s.directionalLights.push_back({ Vec3(0.3, -0.4, -1.0), uniformChannels(1.0) });
  return s;
}

inline Scene cloudScene(int n)
{
  Scene s = unitCube(n);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    const double noise = std::sin(11.0 * x[0] + 1.0) * std::sin(13.0 * x[1] + 2.0) * std::sin(9.0 * x[2]) +
                         0.5 * std::sin(23.0 * x[0] + 17.0 * x[1]) * std::cos(19.0 * x[2] + 3.0);
    const double envelope = 1.0 - (x - Vec3(0.5, 0.5, 0.45)).squaredNorm() / 0.2;
    const double density = std::max(0.0, 0.6 * envelope + 0.4 * noise);
    const double kt = 200.0 * density; // up to ~100 mean free paths across
    s.sigmaI[v] = float(0.99 * kt);
    s.kappaA[v] = float(0.01 * kt);
  }
  s.directionalLights.push_back({ Vec3(0.4, 0.2, -1.0), uniformChannels(1.0) });
  s.boundary[static_cast<int>(Face::ZMax)].radiance = uniformChannels(0.1);
  return s;
}

inline Scene cubeScene61(int n)
{
  Scene s = unitCube(n);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    s.sigmaI[v] = float(0.99 * 61.0);
    s.kappaA[v] = float(0.01 * 61.0);
  }
  s.pointLights.push_back({ Vec3::Constant(0.5), uniformChannels(1.0) });
  return s;
}

/// A grid size read from `program`'s command line (n for n^3 voxels,
/// 1-4096), or 0, said on stderr, when the text is not one.
inline int gridSize(const char* program, const char* text)
{
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  if (end != text && *end == '\0' && n >= 1 && n <= 4096) {
    return int(n);
  }
  std::fprintf(stderr,
               "%s: not an option or a grid size (1-4096): %s (--help lists the options)\n",
               program,
               text);
  return 0;
}

/// The benchmark scene of that name; any other name is an error (not a
/// cube measured under the wrong name).
inline Scene benchmarkScene(const std::string& name, int n)
{
  if (name == "phantom") {
    return phantomScene(n);
  }
  if (name == "cloud") {
    return cloudScene(n);
  }
  if (name == "cube") {
    return cubeScene61(n);
  }
  throw Error("no benchmark scene '" + name + "' (phantom, cloud or cube)");
}

} // namespace volrad::bench
