// SPDX-License-Identifier: BSD-3-Clause
/// @file Transmittance.h
/// @brief Optical depth and transmittance along a segment through the
/// piecewise-constant medium, exact by voxel traversal. Outside the domain
/// is vacuum.
#pragma once

#include "volrad/Scene.h"

namespace volrad {

/// Integral of kappa_t along the segment from a to b, channel c [1].
double opticalDepth(const Scene& scene, int channel, const Vec3& a, const Vec3& b);

/// exp(-opticalDepth): the fraction of light from a that reaches b unscattered.
double transmittance(const Scene& scene, int channel, const Vec3& a, const Vec3& b);

} // namespace volrad
