// SPDX-License-Identifier: BSD-3-Clause
/// @file VoxelTraversal.h
/// @brief Exact traversal of the voxels a ray crosses (Amanatides & Woo 1987).
///
/// The medium is piecewise constant per voxel, so the optical depth along a
/// segment is the exact sum of kappa_t * length over the voxels it crosses;
/// this walk gives those lengths without sampling.
#pragma once

#include "volrad/Grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace volrad {

/// Where a ray leaves the domain.
struct DomainExit
{
  bool exited = false; ///< false: stopped inside (tMax reached or visitor stopped)
  Face face = Face::XMin;
  Index patch = -1;
  double t = 0.0; ///< ray parameter at the exit point
};

/// Clips the ray o + t d against the domain box. On overlap returns true with
/// [t0, t1] and the face through which the ray enters (meaningful when t0 > 0
/// or the origin lies on the boundary).
bool clipToDomain(const Grid& g,
                  const Vec3& o,
                  const Vec3& d,
                  double& t0,
                  double& t1,
                  Face* entry = nullptr);

/// Distance along d from x (inside or on the box [lo, hi]) to the box's boundary.
inline double distanceToBoxExit(const Vec3& x, const Vec3& d, const Vec3& lo, const Vec3& hi)
{
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0) {
      t = std::min(t, (hi[a] - x[a]) / d[a]);
    } else if (d[a] < 0.0) {
      t = std::min(t, (lo[a] - x[a]) / d[a]);
    }
  }
  return std::max(0.0, t);
}

/// Walks the voxels along o + t d for t in [max(0, entry), tMax], calling
/// visit(voxel, length, tStart) for each crossed voxel (zero-length pieces are
/// skipped). The visitor returns false to stop the walk. d must be unit
/// length; o may lie outside the domain.
template<class Visitor>
DomainExit traverseVoxels(const Grid& g, const Vec3& o, const Vec3& d, double tMax, Visitor&& visit)
{
  DomainExit out;
  if (!o.allFinite() || !d.allFinite() || d.squaredNorm() == 0.0) {
    return out;
  }
  const Vec3 lo = g.lower();
  // Most walks (the hierarchy's marches between points of the domain)
  // start and end inside it: no clipping needed.
  double t0 = 0.0, t1 = tMax;
  const Vec3 hi = g.upper(), end = o + d * tMax;
  const bool inside = (o.array() >= lo.array()).all() && (o.array() <= hi.array()).all() &&
                      (end.array() >= lo.array()).all() && (end.array() <= hi.array()).all();
  if (!inside && !clipToDomain(g, o, d, t0, t1)) {
    return out;
  }
  double t = std::max(t0, 0.0);
  if (t1 <= t) {
    return out;
  }
  // Start voxel: the point a little way along the first piece, so a start on
  // a voxel boundary picks the voxel the ray goes into.
  const Vec3 probe = o + d * (t + std::min(1e-7 * g.spacing.minCoeff(), 0.5 * (t1 - t)));
  int idx[3];
  int step[3];
  double tNext[3];
  double tDelta[3];
  for (int a = 0; a < 3; ++a) {
    int i = static_cast<int>(std::floor((probe[a] - lo[a]) / g.spacing[a]));
    i = std::min(std::max(i, 0), g.dims[a] - 1);
    idx[a] = i;
    if (d[a] > 0.0) {
      step[a] = 1;
      tNext[a] = (lo[a] + (i + 1) * g.spacing[a] - o[a]) / d[a];
      tDelta[a] = g.spacing[a] / d[a];
    } else if (d[a] < 0.0) {
      step[a] = -1;
      tNext[a] = (lo[a] + i * g.spacing[a] - o[a]) / d[a];
      tDelta[a] = -g.spacing[a] / d[a];
    } else {
      step[a] = 0;
      tNext[a] = std::numeric_limits<double>::infinity();
      tDelta[a] = std::numeric_limits<double>::infinity();
    }
  }
  const Index sx = 1, sy = g.dims[0], sz = Index(g.dims[0]) * g.dims[1];
  const Index strides[3] = { sx, sy, sz };
  Index voxel = idx[0] + sy * idx[1] + sz * idx[2];
  for (;;) {
    const int axis =
      tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
    const double tEnd = std::min(tNext[axis], tMax);
    if (tEnd > t && !visit(voxel, tEnd - t, t)) {
      return out;
    }
    if (tNext[axis] >= tMax) {
      return out; // stopped inside the domain
    }
    t = tNext[axis];
    idx[axis] += step[axis];
    if (idx[axis] < 0 || idx[axis] >= g.dims[axis]) {
      out.exited = true;
      out.face = makeFace(axis, step[axis] > 0);
      const auto ax = faceAxesInPlane(out.face);
      out.patch = g.patchIndex(out.face, idx[ax[0]], idx[ax[1]]);
      out.t = t;
      return out;
    }
    voxel += step[axis] * strides[axis];
    tNext[axis] += tDelta[axis];
  }
}

} // namespace volrad
