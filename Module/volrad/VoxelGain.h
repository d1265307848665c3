// SPDX-License-Identifier: BSD-3-Clause
/// @file VoxelGain.h
/// @brief What a homogeneous voxel sends towards a direction, per unit of the
/// transmittance of the line from its centre (the links' voxel ends).
///
/// A link between voxels marches one line from each voxel's centre; the
/// light of the rest of the voxel travels other lines. For a voxel of
/// extinction kappa and spacing h, seen from afar along the unit w, the
/// gain is the mean over the voxel of exp(tau(c) - tau(x)), tau the optical
/// depth from a point to the far end. It depends on the medium just
/// outside the voxel:
///  * the same medium all round (tau linear): prod_a sinh(z_a) / z_a,
///    z_a = kappa h_a |w_a| / 2;
///  * nothing outside (a voxel at a surface, a thick voxel beside a thin
///    medium): exp(kappa d_c) times the mean of exp(-kappa d_x), d_x the
///    distance from x to the voxel's boundary along w (d_c from the
///    centre). Its thick limit is the projected area over kappa V times
///    exp(kappa d_c): a thick voxel shines from its skin, like a surface.
/// The two differ by orders of magnitude for thick voxels (tens of optical
/// depths per voxel in bone: 1e8 against 1e11 along a diagonal).
#pragma once

#include "volrad/Grid.h"

namespace volrad {

/// log of the gain with the same medium all round.
double logVoxelGainHomogeneous(double kappa, const Vec3& h, const Vec3& w);

/// log of the gain with nothing outside the voxel.
double logVoxelGainIsolated(double kappa, const Vec3& h, const Vec3& w);

/// log of the gain when the medium outside has `share` (0 to 1) of the
/// voxel's extinction: the logs of the two limits weighted by it (exact at
/// both ends; the logarithm is convex in the share, so between them this
/// errs high, by 2% at 2 optical depths per voxel and half the extinction
/// outside).
double logVoxelGain(double kappa, double share, const Vec3& h, const Vec3& w);

} // namespace volrad
