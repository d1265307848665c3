// SPDX-License-Identifier: BSD-3-Clause
/// @file ZonalSystem.h
/// @brief The per-element equations both solvers solve (physics.md 3-4):
/// x = e + c (C), C = S x + D the collided power, with
///   full side:  e = kappa_a E_I / kappa_t, c = sigma_i / (4 kappa_t^2 V)
///   front side: e = kappa_a E_D / kappa_t, c = sigma_d / (2 kappa_t^2 V)
///   wall patch: e = E_w, c = rho / A;  open patch: e = pi L_env, c = 0
/// and D the direct light's collided power.
#pragma once

#include "volrad/DirectLight.h"
#include "volrad/ExchangeAreas.h"

#include "volrad/Solution.h"

#include <Eigen/Core>

#include <functional>

namespace volrad {

struct ZonalSystem
{
  Eigen::VectorXd e, c, D;
};

ZonalSystem buildZonalSystem(const Scene& scene,
                             int channel,
                             const ExchangeElements& el,
                             const DirectLighting& dl);

/// A zero solution of the scene's size, for `method`; without its fields
/// (allocateFields later) when withFields is false.
Solution emptySolution(const Scene& scene, const char* method, bool withFields = true);
/// The voxel and patch fields of a solution, zero, at the scene's size.
void allocateFields(const Scene& scene, Solution& sol);

/// Writes the voxel and patch fields of one channel from the element
/// radiosities x and collided powers C; G of voxels that are not elements
/// and G+ of voxels with a normal but no front side come from the solver.
void storeChannelFields(const Scene& scene,
                        int channel,
                        const ExchangeElements& el,
                        const Eigen::VectorXd& x,
                        const Eigen::VectorXd& collided,
                        const std::function<double(Index)>& otherG,
                        const std::function<double(Index)>& otherGplus,
                        Solution& sol);

} // namespace volrad
