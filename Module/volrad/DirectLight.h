// SPDX-License-Identifier: BSD-3-Clause
/// @file DirectLight.h
/// @brief Light from directional and point lights before any scattering:
/// attenuated by the medium, entering through open faces only (walls block
/// it), reaching voxels and the inner side of boundary patches.
///
/// Per voxel it returns the track integral T_v = sum over rays of
/// power * transmittance-weighted length in v, so that the direct incident
/// radiation is G_v = T_v / V and the power colliding in v is kappa_t T_v
/// (exact along each ray, also where kappa_t = 0).
#pragma once

#include "volrad/Progress.h"
#include "volrad/Quadrature.h"
#include "volrad/Scene.h"

#include <string>
#include <vector>

namespace volrad {

struct DirectLighting
{
  std::vector<double> track;      ///< per voxel [W * length]
  /// The part arriving from the voxel's front (n . w < 0); empty when the
  /// scene has no normals (only voxels with a normal have a front).
  std::vector<double> trackFront;
  std::vector<double> patchPower; ///< per boundary patch: power arriving from inside [W]
  double entering = 0.0;          ///< power that entered the domain [W]
};

/// `progress` hears after every million rays or so (and may abort).
DirectLighting computeDirectLight(const Scene& scene,
                                  int channel,
                                  const QuadratureSettings& q,
                                  const ProgressRange& progress = {});

/// One message per light that walls keep out entirely: a directional light
/// whose every entering face is a wall, a point light outside the volume
/// that faces only walls. Not errors (the answer, no light from it, is
/// right), but rarely what the scene's author meant.
std::vector<std::string> lightsWallsKeepOut(const Scene& scene);

} // namespace volrad
