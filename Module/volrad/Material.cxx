// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Material.h"

#include "volrad/Error.h"
#include "volrad/Normals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace volrad {

double TransferFunction::operator()(double x) const
{
  if (points.empty()) {
    return 0.0;
  }
  if (x <= points.front().first) {
    return points.front().second;
  }
  if (x >= points.back().first) {
    return points.back().second;
  }
  const auto hi = std::upper_bound(
    points.begin(), points.end(), x, [](double v, const auto& p) { return v < p.first; });
  const auto lo = hi - 1;
  const double w = hi->first > lo->first ? (x - lo->first) / (hi->first - lo->first) : 1.0;
  return lo->second + w * (hi->second - lo->second);
}

namespace {

TransferFunction tf(std::initializer_list<std::pair<double, double>> p)
{
  return TransferFunction{ std::vector<std::pair<double, double>>(p) };
}

struct Preset
{
  const char* name;
  const char* description;
  MaterialMap (*make)();
};

// CT in Hounsfield units, spacing in mm. Real tissue scatters visible light
// over about 0.1 mm; these mean free paths are stretched so that a head is
// translucent (soft tissue 20 mm, bone 0.5 mm), with albedos and colours of
// the tissues: fat and soft tissue highly scattering and reddish, bone a
// whiter, more absorbing and surface-like scatterer; air and lung empty.
MaterialMap ctPreset()
{
  MaterialMap m;
  m.extinction = tf({ { -1000, 0.0 },
                      { -500, 0.0 },
                      { -100, 0.02 },
                      { 40, 0.05 },
                      { 200, 0.2 },
                      { 700, 2.0 },
                      { 3000, 2.0 } });
  m.albedo = tf({ { -500, 0.98 }, { 40, 0.95 }, { 300, 0.8 }, { 1000, 0.7 } });
  m.color[0] = tf({ { 0, 1.0 } });
  m.color[1] = tf({ { -100, 0.9 }, { 40, 0.65 }, { 300, 0.9 } });
  m.color[2] = tf({ { -100, 0.7 }, { 40, 0.55 }, { 300, 0.85 } });
  m.surfaceGradient = 100.0; // HU per mm: bone and skin edges
  return m;
}

// CT, bone only: soft tissue nearly clear (mean free path 500 mm), so the
// skull and skeleton stand out, lit through the tissue around them.
MaterialMap ctBonePreset()
{
  MaterialMap m = ctPreset();
  m.extinction =
    tf({ { -1000, 0.0 }, { 40, 0.0 }, { 150, 0.002 }, { 300, 0.5 }, { 700, 2.0 }, { 3000, 2.0 } });
  return m;
}

// MR intensities have no absolute scale: fractions of the range, background
// (the lowest 10%) empty, brighter tissue denser; 0.3 optical depth per voxel
// at the top of the range, albedo 0.95, boundaries surface-like.
MaterialMap mrPreset()
{
  MaterialMap m;
  m.relative = true;
  m.perVoxel = true;
  m.extinction = tf({ { 0.0, 0.0 }, { 0.1, 0.0 }, { 0.3, 0.05 }, { 1.0, 0.3 } });
  m.albedo = tf({ { 0.0, 0.95 } });
  m.surfaceGradient = 0.05; // fraction of the range per unit length
  return m;
}

// Smoke or cloud density (relative): extinction proportional to density,
// half an optical depth per voxel at the densest, albedo 0.99 (water
// droplets barely absorb), white, isotropic.
MaterialMap cloudPreset()
{
  MaterialMap m;
  m.relative = true;
  m.perVoxel = true;
  m.extinction = tf({ { 0.0, 0.0 }, { 1.0, 0.5 } });
  m.albedo = tf({ { 0.0, 0.99 } });
  return m;
}

const Preset kPresets[] = {
  { "ct",
    "CT in Hounsfield units (spacing in mm): air and lung empty, soft tissue (mean free path 20 "
    "mm, "
    "albedo 0.95, reddish), bone (0.5 mm, albedo 0.7, whitish, surface-like at edges)",
    &ctPreset },
  { "ct-bone",
    "CT in Hounsfield units (spacing in mm), bone only: soft tissue nearly clear (mean free path "
    "500 mm), bone as in 'ct'",
    &ctBonePreset },
  { "mr",
    "MR intensity relative to its range: background empty, up to 0.3 optical depth per voxel, "
    "albedo "
    "0.95, surface-like at boundaries",
    &mrPreset },
  { "cloud",
    "smoke or cloud density relative to its range: up to 0.5 optical depth per voxel, albedo 0.99, "
    "isotropic",
    &cloudPreset },
};

const Preset& findPreset(const std::string& name)
{
  for (const Preset& p : kPresets) {
    if (name == p.name) {
      return p;
    }
  }
  std::string known;
  for (const Preset& p : kPresets) {
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  throw Error("unknown material preset '" + name + "' (known: " + known + ")");
}

void checkFunction(const TransferFunction& f, const std::string& where, double lo, double hi)
{
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    const auto& [x, y] = f.points[i];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw Error(where + ": point " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && x < f.points[i - 1].first) {
      throw Error(where + ": points must be sorted by scalar value");
    }
    if (y < lo || y > hi) {
      std::ostringstream msg;
      msg << where << ": value " << y << " at " << x << " is outside [" << lo << ", " << hi << "]";
      throw Error(msg.str());
    }
  }
}

} // namespace

std::vector<std::string> materialPresetNames()
{
  std::vector<std::string> names;
  for (const Preset& p : kPresets) {
    names.push_back(p.name);
  }
  return names;
}

MaterialMap materialPreset(const std::string& name)
{
  return findPreset(name).make();
}

std::string materialPresetDescription(const std::string& name)
{
  return findPreset(name).description;
}

void validateMaterial(const MaterialMap& m, const std::string& where)
{
  const double inf = std::numeric_limits<double>::infinity();
  checkFunction(m.extinction, where + ".extinction", 0.0, inf);
  checkFunction(m.albedo, where + ".albedo", 0.0, 1.0);
  for (int c = 0; c < kMaxChannels; ++c) {
    checkFunction(m.color[c], where + ".color", 0.0, 1.0);
    checkFunction(m.emission[c], where + ".emission", 0.0, inf);
  }
  if (!m.labels.empty() && !m.extinction.empty()) {
    throw Error(where + ": give either a label table or transfer functions, not both");
  }
  for (const auto& [label, lm] : m.labels) {
    const std::string at = where + ".labels." + std::to_string(label);
    auto check = [&](double v, const char* what, double hi) {
      if (!std::isfinite(v) || v < 0.0 || v > hi) {
        throw Error(at + "." + what + " must be finite, >= 0" + (hi < 2.0 ? " and <= 1" : ""));
      }
    };
    const double inf = std::numeric_limits<double>::infinity();
    check(lm.extinction, "extinction", inf);
    check(lm.albedo, "albedo", 1.0);
    for (int c = 0; c < kMaxChannels; ++c) {
      check(lm.color[c], "color", 1.0);
      check(lm.emission[c], "emission", inf);
    }
  }
  if (!std::isfinite(m.rescaleSlope) || m.rescaleSlope == 0.0 ||
      !std::isfinite(m.rescaleIntercept)) {
    throw Error(where + ".rescale_slope must be finite and non-zero, rescale_intercept finite");
  }
  if (!(m.surfaceGradient >= 0.0) || !std::isfinite(m.surfaceGradient)) {
    throw Error(where + ".surface_gradient must be a finite number >= 0");
  }
}

void applyMaterial(const MaterialMap& m, const std::vector<double>& scalars, Scene& scene)
{
  validateMaterial(m);
  const Grid& g = scene.grid;
  const Index nv = g.voxelCount();
  if (Index(scalars.size()) != nv) {
    throw Error("material: the scalar field has " + std::to_string(scalars.size()) +
                " values, expected " + std::to_string(nv));
  }
  // Scalars as the functions see them: rescaled, then relative to the range.
  double lo = -m.rescaleIntercept / m.rescaleSlope, scale = m.rescaleSlope;
  if (m.relative) {
    const auto [mn, mx] = std::minmax_element(scalars.begin(), scalars.end());
    lo = *mn;
    scale = *mx > *mn ? 1.0 / (*mx - *mn) : 0.0;
  }
  for (double s : scalars) {
    if (!std::isfinite(s)) {
      throw Error("material: the scalar field has a non-finite value");
    }
  }
  const double lengthScale = m.perVoxel ? 1.0 / g.spacing.minCoeff() : 1.0;
  std::vector<Vec3> gradient;
  if (m.surfaceGradient > 0.0) {
    gradient = scalarGradient(g, scalars);
  }
  const int C = scene.channels;
  if (!m.labels.empty()) {
    for (Index v = 0; v < nv; ++v) {
      const auto it = m.labels.find(std::llround(scalars[v] * m.rescaleSlope + m.rescaleIntercept));
      const LabelMaterial none;
      const LabelMaterial& lm = it == m.labels.end() ? none : it->second;
      const double kt = lm.extinction * lengthScale;
      for (int c = 0; c < C; ++c) {
        const double colour =
          C == kMaxChannels ? lm.color[c] : (lm.color[0] + lm.color[1] + lm.color[2]) / 3.0;
        const double emission = C == kMaxChannels
                                  ? lm.emission[c]
                                  : (lm.emission[0] + lm.emission[1] + lm.emission[2]) / 3.0;
        const double a = lm.albedo * colour;
        const std::size_t o = std::size_t(v) * C + c;
        scene.kappaA[o] = float((1.0 - a) * kt);
        scene.sigmaI[o] = float(a * kt);
        scene.sigmaD[o] = 0.f;
        scene.emissionI[o] = float(emission);
      }
    }
    return;
  }
  for (Index v = 0; v < nv; ++v) {
    const double s = (scalars[v] - lo) * scale;
    const double kt = m.extinction(s) * lengthScale;
    double share = 0.0;
    if (!gradient.empty() && scene.hasNormal(v)) {
      share = -std::expm1(-gradient[v].norm() * std::abs(scale) / m.surfaceGradient);
    }
    const double albedo = m.albedo.empty() ? 0.0 : m.albedo(s);
    for (int c = 0; c < C; ++c) {
      // Grey scenes take the mean of the three colour channels.
      auto perChannel = [&](const std::array<TransferFunction, kMaxChannels>& f, double none) {
        if (C == kMaxChannels) {
          return f[c].empty() ? none : f[c](s);
        }
        double sum = 0.0;
        for (const TransferFunction& fc : f) {
          sum += fc.empty() ? none : fc(s);
        }
        return sum / kMaxChannels;
      };
      const double a = albedo * perChannel(m.color, 1.0);
      const std::size_t o = std::size_t(v) * C + c;
      scene.kappaA[o] = float((1.0 - a) * kt);
      scene.sigmaI[o] = float((1.0 - share) * a * kt);
      scene.sigmaD[o] = float(share * a * kt);
      scene.emissionI[o] = float(perChannel(m.emission, 0.0));
    }
  }
}

} // namespace volrad
