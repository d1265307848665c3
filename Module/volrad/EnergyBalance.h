// SPDX-License-Identifier: BSD-3-Clause
/// @file EnergyBalance.h
/// @brief The energy terms of physics.md section 5.2 from a solution's fields.
#pragma once

#include "volrad/Scene.h"
#include "volrad/Solution.h"

namespace volrad {

/// Terms of channel `ch` from the solution's G, G+ (voxels) and H (patches);
/// `lightsEntering` is the direct light power that entered the domain.
EnergyTerms computeEnergyTerms(const Scene& scene,
                               int ch,
                               const Solution& sol,
                               double lightsEntering);

} // namespace volrad
