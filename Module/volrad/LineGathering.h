// SPDX-License-Identifier: BSD-3-Clause
/// @file LineGathering.h
/// @brief The ray walks behind every exchange factor (internal to the core):
/// a ray's first collisions, the lines leaving a voxel with its emission
/// integrated exactly along each, a patch's cosine-weighted lines and a
/// voxel's view of its surroundings, each optionally cut at a box.
#pragma once

#include "volrad/ExchangeAreas.h"
#include "volrad/Sampling.h"
#include "volrad/VoxelTraversal.h"

#include <cmath>
#include <limits>
#include <vector>

namespace volrad::detail {

/// Below this transmittance a ray carries nothing measurable any more.
constexpr double kNegligibleTransmittance = 1e-13;

struct ChannelMedium
{
  const Scene& scene;
  std::vector<double> kappaT;

  ChannelMedium(const Scene& s, int c)
    : scene(s)
    , kappaT(s.extinction(c))
  {
  }
  double normalDot(Index v, const Vec3& d) const { return scene.normalDot(v, d); }
};

/// Follows one ray of the given weight and hands each crossed element the
/// probability that the ray's first collision is there (exact for the
/// piecewise-constant medium): sink(element, amount). Stops at tMax;
/// returns the weight still travelling there (0 when the ray left the
/// domain, its remainder then going to the patch it leaves by).
template<class Sink>
double depositRay(const ChannelMedium& m,
                  const ExchangeElements& el,
                  const Vec3& x,
                  const Vec3& d,
                  double weight,
                  double tMax,
                  Sink&& sink)
{
  double T = weight;
  const DomainExit exit =
    traverseVoxels(m.scene.grid, x, d, tMax, [&](Index v, double length, double) {
      const double k = m.kappaT[v];
      if (k <= 0.0) {
        return true;
      }
      const double p = T * -std::expm1(-k * length); // exact also where k * length is tiny
      T *= std::exp(-k * length);
      sink(el.full[v], p);
      // Light travelling along d reaches v's front side from v's front iff
      // the emitter lies in front of v, i.e. n_v . d < 0.
      const Index er = el.front[v];
      if (er >= 0 && m.normalDot(v, d) < 0.0) {
        sink(er, p);
      }
      return T > kNegligibleTransmittance * weight;
    });
  if (exit.exited) {
    sink(el.patchElement(exit.patch), T);
    return 0.0;
  }
  return T > kNegligibleTransmittance * weight ? T : 0.0;
}

/// A box that rays are followed to the edge of (none: to the end).
struct Reach
{
  bool truncate = false;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  double tMax(const Vec3& x, const Vec3& d) const
  {
    return truncate ? distanceToBoxExit(x, d, lo, hi) : std::numeric_limits<double>::infinity();
  }
};

/// The box of voxels within Chebyshev distance r of voxel v. Where it
/// reaches the domain's boundary it is pushed past it, so that lines leave
/// the domain (into a patch) before they reach the box's edge.
inline Reach neighbourhood(const Grid& g, Index v, int r)
{
  Reach reach{ true,
               g.voxelLower(v) - double(r) * g.spacing,
               g.voxelLower(v) + double(r + 1) * g.spacing };
  const auto c = g.ijk(v);
  for (int a = 0; a < 3; ++a) {
    if (c[a] - r <= 0) {
      reach.lo[a] = g.lower()[a] - g.spacing[a];
    }
    if (c[a] + r >= g.dims[a] - 1) {
      reach.hi[a] = g.upper()[a] + g.spacing[a];
    }
  }
  return reach;
}

/// The lines leaving voxel v (kappa_t > 0), parametrised by their exit
/// point on one of v's faces and their direction (d mu = cos(theta) dA dw);
/// the emission of v along each is integrated exactly, 1 - exp(-kappa_t l),
/// and the part collided inside v, kappa_t l - (1 - exp(-kappa_t l)), is
/// v's self term. sink(element, amount, front) receives every deposit;
/// front is true for lines leaving through v's front (n_v . d > 0) when v
/// has a front side. With `truncate`, lines are followed only to the
/// boundary of the box [reachLo, reachHi]; returns the weight they still
/// carry there.
template<class Sink>
double gatherVoxelLinesInto(const ChannelMedium& m,
                            const ExchangeElements& el,
                            Index v,
                            const QuadratureSettings& q,
                            const Reach& reach,
                            Sink&& sink)
{
  const Grid& g = m.scene.grid;
  const double kt = m.kappaT[v];
  const Index self = el.full[v];
  const Index selfFront = el.front[v];
  const Vec3 lo = g.voxelLower(v);
  const auto c = g.ijk(v);
  double leftover = 0.0;
  Rng rng(q.seed, std::uint64_t(v));
  for (int fi = 0; fi < kFaceCount; ++fi) {
    const Face f = static_cast<Face>(fi);
    const int axis = faceAxis(f);
    const Vec3 outward = -faceInwardNormal(f);
    Vec3 faceLo = lo;
    if (faceIsMax(f)) {
      faceLo[axis] += g.spacing[axis];
    }
    Vec3 size = g.spacing;
    size[axis] = 0.0;
    const double area = g.patchArea(f);
    const auto pts = stratifiedPoints(faceLo, size, q.voxelPointsPerAxis, rng);
    const double w = area / double(pts.size() * q.voxelDirections);
    std::vector<Vec3> cosDirs;
    // A face on the domain boundary sends its lines straight into a patch.
    const bool boundary = faceIsMax(f) ? c[axis] == g.dims[axis] - 1 : c[axis] == 0;
    const Index patch =
      boundary
        ? el.patchElement(g.patchIndex(f, c[faceAxesInPlane(f)[0]], c[faceAxesInPlane(f)[1]]))
        : -1;
    const Eigen::Matrix3d frame = frameAround(outward);
    for (const Vec3& x : pts) {
      fibonacciCosineHemisphere(q.voxelDirections, rng.uniform(), rng.uniform(), cosDirs);
      for (const Vec3& d0 : cosDirs) {
        const Vec3 d = frame * d0;
        const double l = distanceToBoxExit(x, -d, lo, lo + g.spacing); // chord back through v
        const double escape = -std::expm1(-kt * l);
        const double selfCollided = kt * l - escape;
        const bool front = selfFront >= 0 && m.normalDot(v, d) > 0.0;
        // Self terms: emitted along this line and collided in v itself.
        sink(self, w * selfCollided, front);
        if (selfFront >= 0 && m.normalDot(v, d) < 0.0) {
          sink(selfFront, w * selfCollided, front);
        }
        if (boundary) {
          sink(patch, w * escape, front);
          continue;
        }
        // The escaping part, carried on to its first collision.
        leftover += depositRay(
          m, el, x, d, w * escape, reach.tMax(x, d), [&](Index e, double p) { sink(e, p, front); });
      }
    }
  }
  return leftover;
}

inline void gatherVoxelLines(const ChannelMedium& m,
                             const ExchangeElements& el,
                             Index v,
                             const QuadratureSettings& q,
                             double* rowFull,
                             double* rowFront)
{
  gatherVoxelLinesInto(m, el, v, q, Reach{}, [&](Index e, double p, bool front) {
    rowFull[e] += p;
    if (front) {
      rowFront[e] += p;
    }
  });
}

/// Gathers the G (front false) and G+ (front true) weights of a voxel that
/// is not an element from stratified interior points, per unit radiosity
/// of each element reached inside `reach`: sink(element, weight, front).
template<class Sink>
void gatherVoxelView(const ChannelMedium& m,
                     const ExchangeElements& el,
                     Index v,
                     const std::vector<Vec3>& dirs,
                     const QuadratureSettings& q,
                     bool wantFront,
                     const Reach& reach,
                     Sink&& sink)
{
  const Grid& g = m.scene.grid;
  Rng rng(q.seed, std::uint64_t(v));
  // Twice the rays of a voxel with kappa_t > 0: these rows are a direct
  // quadrature of G or G+, not smoothed by reciprocity.
  const int perAxis = std::max(2, (2 * q.voxelPointsPerAxis) / 3);
  const auto pts = stratifiedPoints(g.voxelLower(v), g.spacing, perAxis, rng);
  // G weights: 4 pi sr / pi per unit radiosity, shared among the rays.
  const double w = 4.0 / double(pts.size() * dirs.size());
  for (const Vec3& x : pts) {
    const Eigen::Matrix3d R = sampleRotation(rng);
    for (const Vec3& d0 : dirs) {
      const Vec3 d = R * d0;
      const bool front = wantFront && m.normalDot(v, d) > 0.0;
      depositRay(m, el, x, d, w, reach.tMax(x, d), [&](Index e, double p) {
        sink(e, p, false);
        if (front) {
          sink(e, p, true);
        }
      });
    }
  }
}

/// Gathers the row of boundary patch p with cosine-weighted directions,
/// per unit radiosity of p (the row sums to the patch's area).
template<class Sink>
void gatherPatch(const ChannelMedium& m,
                 const ExchangeElements& el,
                 Index p,
                 const QuadratureSettings& q,
                 const Reach& reach,
                 Sink&& sink)
{
  const Grid& g = m.scene.grid;
  const PatchLocation loc = g.patchLocation(p);
  Rng rng(q.seed ^ 0x7061746368ULL, std::uint64_t(p));
  Vec3 size = g.spacing;
  size[faceAxis(loc.face)] = 0.0;
  const auto pts = stratifiedPoints(g.patchLower(p), size, q.patchPointsPerAxis, rng);
  const Eigen::Matrix3d frame = frameAround(faceInwardNormal(loc.face));
  const double w = g.patchArea(loc.face) / double(pts.size() * q.patchDirections);
  std::vector<Vec3> cosDirs;
  for (const Vec3& x : pts) {
    fibonacciCosineHemisphere(q.patchDirections, rng.uniform(), rng.uniform(), cosDirs);
    for (const Vec3& d0 : cosDirs) {
      const Vec3 d = frame * d0;
      depositRay(m, el, x, d, w, reach.tMax(x, d), sink);
    }
  }
}

} // namespace volrad::detail
