// SPDX-License-Identifier: BSD-3-Clause
/// @file RenderColors.h
/// @brief A render-ready RGBA per voxel from a solution, for VTK's volume
/// mappers with dependent components (IndependentComponents off: the first
/// three components are the colour, the fourth goes through the scalar
/// opacity function).
///
/// Colour: the radiance a voxel sends towards a viewer, averaged over
/// directions, (Q_I + Q_D / 2) / pi per channel (a grey solution gives grey),
/// tone-mapped for 8 bits: divided by `white` (by default the 99.5th
/// percentile of the voxels' largest channel, so that a few hot voxels do
/// not darken the rest), clamped to 1 and gamma-encoded (1/2.2).
/// Alpha: the voxel's opacity along one spacing, 1 - exp(-kappa_t h) with h
/// the mean spacing and kappa_t the mean over channels, times 255: an
/// identity scalar opacity function (0 -> 0, 255 -> 1) then renders the
/// medium as dense as it is.
#pragma once

#include "volrad/Scene.h"
#include "volrad/Solution.h"

#include <cstdint>
#include <vector>

namespace volrad {

struct RenderColorOptions
{
  double white = 0.0; ///< radiance mapped to full intensity (0: the 99.5th percentile)
  double gamma = 2.2; ///< display gamma
};

/// 4 bytes per voxel (R, G, B, A); `white` receives the radiance used.
std::vector<std::uint8_t> renderColors(const Scene& scene,
                                       const Solution& solution,
                                       const RenderColorOptions& options = {},
                                       double* white = nullptr);

} // namespace volrad
