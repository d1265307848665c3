// SPDX-License-Identifier: BSD-3-Clause
/// @file Sampling.h
/// @brief Deterministic random numbers and the point and direction sets the
/// quadratures and the Monte Carlo estimator draw from.
///
/// Every stream is seeded from (seed, element or batch id), so results do not
/// depend on how work is split between threads.
#pragma once

#include "volrad/Grid.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <vector>

namespace volrad {

constexpr double kPi = 3.14159265358979323846;

/// SplitMix64-seeded xoshiro256+: fast, small state, good doubles.
class Rng
{
public:
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0);
  std::uint64_t next();
  /// Uniform in [0, 1).
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
  std::uint64_t s_[4];
};

/// Uniform direction on the unit sphere.
Vec3 sampleSphere(Rng& rng);
/// Direction in the hemisphere about unit n, uniform in solid angle (the
/// phase function of a surface-like voxel: uniform radiance over 2 pi).
Vec3 sampleHemisphereUniform(const Vec3& n, Rng& rng);
/// Cosine-weighted direction in the hemisphere about unit n (Lambertian).
Vec3 sampleHemisphereCosine(const Vec3& n, Rng& rng);
/// Uniformly distributed rotation.
Eigen::Matrix3d sampleRotation(Rng& rng);
/// An orthonormal frame whose third column is n.
Eigen::Matrix3d frameAround(const Vec3& n);

/// n points of the spherical Fibonacci lattice: equal-weight quadrature of
/// the sphere with low discrepancy.
std::vector<Vec3> fibonacciSphere(int n);
/// n cosine-weighted directions about +z from a 2-D Fibonacci lattice shifted
/// by (shiftU, shiftPhi) in [0, 1)^2 (Cranley-Patterson): equal weights
/// integrate f cos(theta) over the hemisphere (times pi), and a random shift
/// per point makes the quadrature unbiased while keeping it stratified.
void fibonacciCosineHemisphere(int n, double shiftU, double shiftPhi, std::vector<Vec3>& out);

/// Jittered stratified points in the box [lower, lower + size]: `perAxis`
/// strata along each axis whose size is non-zero.
std::vector<Vec3> stratifiedPoints(const Vec3& lower, const Vec3& size, int perAxis, Rng& rng);

} // namespace volrad
