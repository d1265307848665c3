// SPDX-License-Identifier: BSD-3-Clause
/// @file Scene.h
/// @brief The scene of physics.md section 2: grid, optical coefficients per
/// voxel and channel, normals, boundary faces and lights.
///
/// Units: lengths in the units of the grid spacing; kappa_a, sigma_i,
/// sigma_d in [1/length]; E_I, E_D, wall emission in emissive-power units
/// [W/m^2] (pi times the emitted radiance); radiance [W/(m^2 sr)];
/// directional irradiance [W/m^2]; point intensity [W/sr].
#pragma once

#include "volrad/Grid.h"

#include <array>
#include <string>
#include <vector>

namespace volrad {

constexpr int kMaxChannels = 3;
/// Largest optical thickness of one voxel the solvers accept: beyond it
/// exp(-kappa_t h) underflows and the voxel is a wall in all but name.
constexpr double kMaxVoxelOpticalThickness = 1e6;
/// One value per channel (1 grey, or 3 RGB); entries past `channels` unused.
using ChannelValues = std::array<double, kMaxChannels>;

inline ChannelValues uniformChannels(double v)
{
  return { v, v, v };
}

struct BoundaryCondition
{
  enum class Type
  {
    Open, ///< vacuum, with uniform incoming radiance L_env
    Wall  ///< opaque Lambertian wall
  };
  Type type = Type::Open;
  ChannelValues radiance{ 0, 0, 0 };    ///< L_env of an open face [W/(m^2 sr)]
  ChannelValues reflectance{ 0, 0, 0 }; ///< rho of a wall, in [0, 1)
  ChannelValues emission{ 0, 0, 0 };    ///< E_w of a wall [W/m^2]
};

struct DirectionalLight
{
  Vec3 direction{ 0, 0, -1 };                ///< travel direction of the light
  ChannelValues irradiance{ 1.0, 1.0, 1.0 }; ///< on a plane normal to it [W/m^2]
};

struct PointLight
{
  Vec3 position{ 0, 0, 0 };                 ///< world coordinates
  ChannelValues intensity{ 1.0, 1.0, 1.0 }; ///< isotropic [W/sr]
};

/// A normal of zero length means "no normal here".
using Normal = std::array<float, 3>;

struct Scene
{
  Grid grid;
  int channels = 1;
  /// Per voxel and channel, index v * channels + c; an empty array means zero.
  std::vector<float> kappaA, sigmaI, sigmaD, emissionI, emissionD;
  /// Per voxel; empty means no normals anywhere.
  std::vector<Normal> normals;
  std::array<BoundaryCondition, kFaceCount> boundary{};
  std::vector<DirectionalLight> directionalLights;
  std::vector<PointLight> pointLights;

  /// Allocates every coefficient array, filled with zeros.
  void allocate();

  double kappaAAt(Index v, int c) const { return at(kappaA, v, c); }
  double sigmaIAt(Index v, int c) const { return at(sigmaI, v, c); }
  double sigmaDAt(Index v, int c) const { return at(sigmaD, v, c); }
  double emissionIAt(Index v, int c) const { return at(emissionI, v, c); }
  double emissionDAt(Index v, int c) const { return at(emissionD, v, c); }
  double kappaTAt(Index v, int c) const { return kappaAAt(v, c) + sigmaIAt(v, c) + sigmaDAt(v, c); }
  bool hasNormal(Index v) const
  {
    if (normals.empty()) {
      return false;
    }
    const Normal& n = normals[v];
    return n[0] != 0.f || n[1] != 0.f || n[2] != 0.f;
  }
  /// n_v . d with the stored (not necessarily unit) normal: its sign says
  /// whether d points to the voxel's front.
  double normalDot(Index v, const Vec3& d) const
  {
    const Normal& n = normals[v];
    return n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  }
  /// kappa_t of every voxel for channel c, the array the ray walks read.
  std::vector<double> extinction(int c) const;
  Vec3 normalAt(Index v) const
  {
    const Normal& n = normals[v];
    return Vec3(n[0], n[1], n[2]);
  }
  bool hasWalls() const;

  /// Throws volrad::Error naming the first invalid value (and its voxel):
  /// empty grid, non-positive spacing, channels not 1 or 3, arrays of the
  /// wrong size, negative or non-finite coefficients, missing normals where
  /// sigma_d > 0 or E_D > 0, reflectance outside [0, 1), bad lights.
  void validate() const;

private:
  double at(const std::vector<float>& a, Index v, int c) const
  {
    return a.empty() ? 0.0 : double(a[std::size_t(v) * channels + c]);
  }
};

} // namespace volrad
