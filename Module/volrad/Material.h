// SPDX-License-Identifier: BSD-3-Clause
/// @file Material.h
/// @brief From a scalar field (CT Hounsfield units, MR intensity, density)
/// to the optical coefficients of physics.md section 2, with transfer
/// functions in the idiom of vtkVolumeProperty, or a named preset.
///
/// Per voxel with scalar s and scalar gradient magnitude |grad s|:
///   kappa_t = extinction(s)                    [1/length]
///   a_c     = albedo(s) * color_c(s)           scattering albedo of channel c
///   f       = 1 - exp(-|grad s| / surfaceGradient)   surface-like share
///   sigma_d = f a_c kappa_t,  sigma_i = (1 - f) a_c kappa_t,
///   kappa_a = (1 - a_c) kappa_t,  E_I = emission_c(s)
/// So extinction is grey, the colour is the albedo's (what a white light
/// leaves after scattering), and scattering becomes surface-like (about the
/// gradient normal) where the scalar changes fast: at tissue boundaries, not
/// inside homogeneous tissue (the rule of hybrid-scattering volume
/// renderers). f is 0 where the voxel has no normal, or surfaceGradient is 0.
#pragma once

#include "volrad/Scene.h"

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace volrad {

/// Piecewise-linear in the scalar, constant before its first and after its
/// last point (vtkPiecewiseFunction with clamping on). Points sorted by x.
struct TransferFunction
{
  std::vector<std::pair<double, double>> points;

  bool empty() const { return points.empty(); }
  double operator()(double x) const;
};

/// The material of one label of a segmentation.
struct LabelMaterial
{
  double extinction = 0.0;                                    ///< kappa_t [1/length] (or per voxel)
  double albedo = 0.0;                                        ///< in [0, 1]
  std::array<double, kMaxChannels> color{ 1.0, 1.0, 1.0 };    ///< albedo factor per channel
  std::array<double, kMaxChannels> emission{ 0.0, 0.0, 0.0 }; ///< E_I [W/m^2]
};

struct MaterialMap
{
  /// A segmentation's label table (instead of the functions): the scalar,
  /// rounded to the nearest integer, picks its label's material; labels not
  /// listed are empty. Label materials scatter isotropically (a label's
  /// number says nothing of a gradient).
  std::map<long long, LabelMaterial> labels;
  TransferFunction extinction; ///< kappa_t [1/length] (or per voxel, see perVoxel)
  TransferFunction albedo;     ///< in [0, 1]; empty: 0 (absorbing only)
  /// Per channel (red, green, blue) factor of the albedo in [0, 1]; empty: 1.
  std::array<TransferFunction, kMaxChannels> color;
  /// Per channel E_I [W/m^2]; empty: no emission.
  std::array<TransferFunction, kMaxChannels> emission;
  /// Gradient magnitude [scalar units / length] at which 63% of the
  /// scattering is surface-like; 0: all isotropic.
  double surfaceGradient = 0.0;
  /// Stored values to the functions' units first: s = slope * value +
  /// intercept (DICOM's RescaleSlope and RescaleIntercept; e.g. intercept
  /// -1024 for CT stored without its offset).
  double rescaleSlope = 1.0, rescaleIntercept = 0.0;
  /// The functions' x are fractions of the volume's scalar range (MR, densities
  /// without absolute units) rather than scalar values.
  bool relative = false;
  /// extinction gives the optical thickness of one voxel (its smallest
  /// spacing), so that a preset looks alike at every resolution.
  bool perVoxel = false;

  /// Whether it gives coefficients at all (an extinction function or labels).
  bool active() const { return !extinction.empty() || !labels.empty(); }
};

/// The named presets: "ct" and "ct-bone" (Hounsfield units, spacing in mm),
/// "mr" and "cloud" (relative scalars); see materialPresetDescription.
std::vector<std::string> materialPresetNames();
/// A preset by name; throws volrad::Error naming the known ones.
MaterialMap materialPreset(const std::string& name);
/// One line on what a preset means physically.
std::string materialPresetDescription(const std::string& name);

/// Throws volrad::Error naming `where` if a function has unsorted,
/// non-finite or out-of-range points (extinction and emission >= 0, albedo
/// and colour in [0, 1]) or surfaceGradient < 0.
void validateMaterial(const MaterialMap& m, const std::string& where = "material");

/// Fills the scene's kappaA, sigmaI, sigmaD and emissionI (allocated) from
/// the scalars (one per voxel) as above. Normals must already be set where
/// surface-like scattering is wanted (scene.normals, e.g. gradientNormals).
void applyMaterial(const MaterialMap& m, const std::vector<double>& scalars, Scene& scene);

} // namespace volrad
