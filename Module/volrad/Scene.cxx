// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Scene.h"

#include "volrad/Error.h"

#include <cmath>
#include <sstream>

namespace volrad {

namespace {

std::string voxelName(const Grid& g, Index v)
{
  const auto c = g.ijk(v);
  std::ostringstream s;
  s << "voxel " << v << " (i=" << c[0] << ", j=" << c[1] << ", k=" << c[2] << ")";
  return s.str();
}

void checkArray(const Scene& s, const std::vector<float>& a, const char* name)
{
  if (a.empty()) {
    return;
  }
  const std::size_t expected = std::size_t(s.grid.voxelCount()) * s.channels;
  if (a.size() != expected) {
    std::ostringstream m;
    m << name << " has " << a.size() << " values, expected " << expected << " (voxels x channels)";
    throw Error(m.str());
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    const float x = a[i];
    if (!std::isfinite(x) || x < 0.f) {
      std::ostringstream m;
      m << name << " = " << x << " at " << voxelName(s.grid, Index(i / s.channels)) << ", channel "
        << i % s.channels << ": must be finite and >= 0";
      throw Error(m.str());
    }
  }
}

void checkChannels(const ChannelValues& v, int channels, const std::string& what, bool belowOne)
{
  for (int c = 0; c < channels; ++c) {
    if (!std::isfinite(v[c]) || v[c] < 0.0 || (belowOne && v[c] >= 1.0)) {
      std::ostringstream m;
      m << what << " = " << v[c] << " (channel " << c << ") must be finite and "
        << (belowOne ? "in [0, 1)" : ">= 0");
      throw Error(m.str());
    }
  }
}

} // namespace

void Scene::allocate()
{
  const std::size_t n = std::size_t(grid.voxelCount()) * channels;
  for (auto* a : { &kappaA, &sigmaI, &sigmaD, &emissionI, &emissionD }) {
    a->assign(n, 0.f);
  }
}

std::vector<double> Scene::extinction(int c) const
{
  std::vector<double> kt(std::size_t(grid.voxelCount()));
  for (Index v = 0; v < grid.voxelCount(); ++v) {
    kt[v] = kappaTAt(v, c);
  }
  return kt;
}

bool Scene::hasWalls() const
{
  for (const auto& b : boundary) {
    if (b.type == BoundaryCondition::Type::Wall) {
      return true;
    }
  }
  return false;
}

void Scene::validate() const
{
  for (int a = 0; a < 3; ++a) {
    if (grid.dims[a] < 1) {
      throw Error("the grid is empty: dimensions must be >= 1 along every axis");
    }
    if (!std::isfinite(grid.spacing[a]) || grid.spacing[a] <= 0.0) {
      std::ostringstream m;
      m << "spacing[" << a << "] = " << grid.spacing[a] << " must be finite and > 0";
      throw Error(m.str());
    }
    if (!std::isfinite(grid.origin[a])) {
      throw Error("the grid origin must be finite");
    }
  }
  // Lengths in any unit, from nanometres to gigametres; beyond, areas and
  // the inverse squares of the exchange factors leave double's range.
  const double hMin = grid.spacing.minCoeff(), hMax = grid.spacing.maxCoeff();
  if (hMin < 1e-9 || hMax > 1e9 || hMax > 1e4 * hMin) {
    std::ostringstream m;
    m << "spacing (" << grid.spacing[0] << ", " << grid.spacing[1] << ", " << grid.spacing[2]
      << ") must lie in [1e-9, 1e9], its largest at most 1e4 times its smallest (change the "
         "length unit)";
    throw Error(m.str());
  }
  if (channels != 1 && channels != 3) {
    throw Error("channels = " + std::to_string(channels) + " must be 1 or 3");
  }
  checkArray(*this, kappaA, "kappa_a");
  checkArray(*this, sigmaI, "sigma_i");
  checkArray(*this, sigmaD, "sigma_d");
  checkArray(*this, emissionI, "E_I");
  checkArray(*this, emissionD, "E_D");
  if (!normals.empty() && normals.size() != std::size_t(grid.voxelCount())) {
    throw Error("normals has " + std::to_string(normals.size()) +
                " entries, expected one per voxel");
  }
  for (Index v = 0; v < grid.voxelCount(); ++v) {
    if (!normals.empty()) {
      const Normal& n = normals[v];
      if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) {
        throw Error("normal at " + voxelName(grid, v) + " is not finite");
      }
    }
    for (int c = 0; c < channels; ++c) {
      const double thickness = kappaTAt(v, c) * grid.spacing.maxCoeff();
      if (thickness > kMaxVoxelOpticalThickness) {
        std::ostringstream m;
        m << "kappa_t * spacing = " << thickness << " at " << voxelName(grid, v) << ", channel "
          << c << ": above " << kMaxVoxelOpticalThickness
          << ", the voxel is opaque to machine precision"
          << " (check the units of the coefficients)";
        throw Error(m.str());
      }
      if ((sigmaDAt(v, c) > 0.0 || emissionDAt(v, c) > 0.0) && !hasNormal(v)) {
        throw Error("sigma_d or E_D > 0 at " + voxelName(grid, v) +
                    " but the voxel has no normal (give a normals array, or scalars whose gradient "
                    "is non-zero there)");
      }
    }
  }
  for (int f = 0; f < kFaceCount; ++f) {
    const BoundaryCondition& b = boundary[f];
    const std::string face = std::string("boundary ") + faceName(Face(f));
    if (b.type == BoundaryCondition::Type::Open) {
      checkChannels(b.radiance, channels, face + " radiance", false);
    } else {
      checkChannels(b.reflectance, channels, face + " reflectance", true);
      checkChannels(b.emission, channels, face + " emission", false);
    }
  }
  for (std::size_t i = 0; i < directionalLights.size(); ++i) {
    const auto& l = directionalLights[i];
    const std::string what = "directional light " + std::to_string(i);
    if (!l.direction.allFinite() || !(l.direction.stableNorm() > 0.0) ||
        !l.direction.stableNormalized().allFinite()) {
      throw Error(what + ": direction must be finite and non-zero");
    }
    checkChannels(l.irradiance, channels, what + " irradiance", false);
  }
  for (std::size_t i = 0; i < pointLights.size(); ++i) {
    const auto& l = pointLights[i];
    const std::string what = "point light " + std::to_string(i);
    if (!l.position.allFinite()) {
      throw Error(what + ": position must be finite");
    }
    checkChannels(l.intensity, channels, what + " intensity", false);
  }
}

} // namespace volrad
