// SPDX-License-Identifier: BSD-3-Clause
/// @file Normals.h
/// @brief Default normals: the normalised negative gradient of a scalar
/// field (physics.md section 2: from dense to less dense).
#pragma once

#include "volrad/Scene.h"

#include <vector>

namespace volrad {

/// Gradient of a scalar field, per voxel in world units: central
/// differences inside, one-sided at the grid's edges.
std::vector<Vec3> scalarGradient(const Grid& grid, const std::vector<double>& scalars);

/// The normalised negative gradient (scalarGradient). Where |gradient| <= threshold (relative to
/// the largest gradient magnitude in the field) the normal is zero: no normal there.
std::vector<Normal> gradientNormals(const Grid& grid,
                                    const std::vector<double>& scalars,
                                    double relativeThreshold = 1e-6);

} // namespace volrad
