// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/ExchangeAreas.h"
#include "volrad/NearField.h"

#include "volrad/Error.h"
#include "volrad/Sampling.h"
#include "volrad/VoxelTraversal.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace volrad {

namespace {

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

/// Adds to rowA and, when given, rowB (either may be null).
struct RowSink
{
  double* rowA;
  double* rowB;
  void operator()(Index e, double p) const
  {
    if (rowA) {
      rowA[e] += p;
    }
    if (rowB) {
      rowB[e] += p;
    }
  }
};

void depositRayWeighted(const ChannelMedium& m,
                        const ExchangeElements& el,
                        const Vec3& x,
                        const Vec3& d,
                        double weight,
                        double* rowA,
                        double* rowB)
{
  depositRay(m, el, x, d, weight, std::numeric_limits<double>::infinity(), RowSink{ rowA, rowB });
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
                            bool truncate,
                            const Vec3& reachLo,
                            const Vec3& reachHi,
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
        const double tMax = truncate ? distanceToBoxExit(x, d, reachLo, reachHi)
                                     : std::numeric_limits<double>::infinity();
        leftover +=
          depositRay(m, el, x, d, w * escape, tMax, [&](Index e, double p) { sink(e, p, front); });
      }
    }
  }
  return leftover;
}

void gatherVoxelLines(const ChannelMedium& m,
                      const ExchangeElements& el,
                      Index v,
                      const QuadratureSettings& q,
                      double* rowFull,
                      double* rowFront)
{
  gatherVoxelLinesInto(
    m, el, v, q, false, Vec3::Zero(), Vec3::Zero(), [&](Index e, double p, bool front) {
      rowFull[e] += p;
      if (front) {
        rowFront[e] += p;
      }
    });
}

/// Gathers the G (rowFull) and G+ (rowFront) weights of a voxel that is not
/// an element from stratified interior points; either row may be null.
double gatherVoxelView(const ChannelMedium& m,
                       const ExchangeElements& el,
                       Index v,
                       const std::vector<Vec3>& dirs,
                       const QuadratureSettings& q,
                       double* rowFull,
                       double* rowFront)
{
  const Grid& g = m.scene.grid;
  Rng rng(q.seed, std::uint64_t(v));
  // Twice the rays of a voxel with kappa_t > 0: these rows are a direct
  // quadrature of G or G+, not smoothed by reciprocity.
  const int perAxis = std::max(2, (2 * q.voxelPointsPerAxis) / 3);
  const auto pts = stratifiedPoints(g.voxelLower(v), g.spacing, perAxis, rng);
  for (const Vec3& x : pts) {
    const Eigen::Matrix3d R = sampleRotation(rng);
    for (const Vec3& d0 : dirs) {
      const Vec3 d = R * d0;
      double* front = (rowFront && m.normalDot(v, d) > 0.0) ? rowFront : nullptr;
      if (rowFull || front) {
        depositRayWeighted(m, el, x, d, 1.0, rowFull, front);
      }
    }
  }
  return double(pts.size() * dirs.size());
}

/// Gathers the row of boundary patch p with cosine-weighted directions.
double gatherPatch(const ChannelMedium& m,
                   const ExchangeElements& el,
                   Index p,
                   const QuadratureSettings& q,
                   double* row)
{
  const Grid& g = m.scene.grid;
  const PatchLocation loc = g.patchLocation(p);
  Rng rng(q.seed ^ 0x7061746368ULL, std::uint64_t(p));
  Vec3 size = g.spacing;
  size[faceAxis(loc.face)] = 0.0;
  const auto pts = stratifiedPoints(g.patchLower(p), size, q.patchPointsPerAxis, rng);
  const Eigen::Matrix3d frame = frameAround(faceInwardNormal(loc.face));
  std::vector<Vec3> cosDirs;
  for (const Vec3& x : pts) {
    fibonacciCosineHemisphere(q.patchDirections, rng.uniform(), rng.uniform(), cosDirs);
    for (const Vec3& d0 : cosDirs) {
      depositRayWeighted(m, el, x, frame * d0, 1.0, row, nullptr);
    }
  }
  return double(pts.size() * cosDirs.size());
}

/// Conjugate gradients with a Jacobi preconditioner on the SPD smoothing
/// system M mu = r, M = S_PP + diag(rowSum - diag(S_PP)).
Eigen::VectorXd solveSmoothing(const RowMatrix& S,
                               Index nP,
                               const Eigen::VectorXd& rowSum,
                               const Eigen::VectorXd& r)
{
  const auto SPP = S.topLeftCorner(nP, nP);
  const Eigen::VectorXd diagExtra = rowSum - SPP.diagonal();
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    return SPP * v + diagExtra.cwiseProduct(v);
  };
  Eigen::VectorXd invDiag(nP);
  for (Index i = 0; i < nP; ++i) {
    invDiag[i] = rowSum[i] > 0.0 ? 1.0 / rowSum[i] : 0.0;
  }
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(nP);
  Eigen::VectorXd res = r;
  Eigen::VectorXd z = invDiag.cwiseProduct(res);
  Eigen::VectorXd p = z;
  double rz = res.dot(z);
  const double r0 = r.norm();
  for (int it = 0; it < 1000 && res.norm() > 1e-15 * r0 + 1e-300; ++it) {
    const Eigen::VectorXd Ap = apply(p);
    const double pAp = p.dot(Ap);
    if (!(pAp > 0.0)) {
      break;
    }
    const double alpha = rz / pAp;
    mu += alpha * p;
    res -= alpha * Ap;
    z = invDiag.cwiseProduct(res);
    const double rzNew = res.dot(z);
    p = z + (rzNew / rz) * p;
    rz = rzNew;
  }
  return mu;
}

} // namespace

ExchangeElements makeExchangeElements(const Scene& scene, int channel)
{
  ExchangeElements el;
  const Index nv = scene.grid.voxelCount();
  el.full.assign(nv, -1);
  el.front.assign(nv, -1);
  for (Index v = 0; v < nv; ++v) {
    if (scene.kappaTAt(v, channel) > 0.0) {
      el.full[v] = el.fullCount++;
    }
  }
  el.patchCount = scene.grid.patchCount();
  for (Index v = 0; v < nv; ++v) {
    if (el.full[v] >= 0 && needsFrontSide(scene, v)) {
      el.front[v] = el.partitionSize() + el.frontCount++;
    }
  }
  el.voxelOf.assign(el.size(), -1);
  for (Index v = 0; v < nv; ++v) {
    if (el.full[v] >= 0) {
      el.voxelOf[el.full[v]] = v;
    }
    if (el.front[v] >= 0) {
      el.voxelOf[el.front[v]] = v;
    }
  }
  return el;
}

double exchangeRowTarget(const Scene& scene, int channel, const ExchangeElements& el, Index e)
{
  if (el.isPatch(e)) {
    return scene.grid.patchArea(scene.grid.patchLocation(e - el.fullCount).face);
  }
  const double kv = scene.kappaTAt(el.voxelOf[e], channel) * scene.grid.voxelVolume();
  return el.isFront(e) ? 2.0 * kv : 4.0 * kv;
}

bool needsFrontSide(const Scene& scene, Index v)
{
  for (int c = 0; c < scene.channels; ++c) {
    if (scene.sigmaDAt(v, c) > 0.0 || scene.emissionDAt(v, c) > 0.0) {
      return true;
    }
  }
  return false;
}

ExchangeAreas computeExchangeAreas(const Scene& scene,
                                   int channel,
                                   const QuadratureSettings& q,
                                   const ExchangeOptions& options,
                                   const ProgressRange& progress)
{
  if (q.voxelPointsPerAxis < 1 || q.voxelDirections < 1 || q.patchPointsPerAxis < 1 ||
      q.patchDirections < 1) {
    throw Error("quadrature settings must all be >= 1");
  }
  const Grid& g = scene.grid;
  const ChannelMedium medium(scene, channel);
  ExchangeAreas out;
  ExchangeElements& el = out.elements;
  el = makeExchangeElements(scene, channel);
  const Index n = el.size();
  const Index nv = g.voxelCount();

  Index gatherCount = 0;
  out.gatherFullRow.assign(nv, -1);
  out.gatherFrontRow.assign(nv, -1);
  for (Index v = 0; v < nv; ++v) {
    if (el.full[v] < 0) {
      out.gatherFullRow[v] = gatherCount++;
    }
    if (el.front[v] < 0 && scene.hasNormal(v)) {
      out.gatherFrontRow[v] = gatherCount++;
    }
  }
  out.S.setZero(n, n);
  out.gatherRows.setZero(gatherCount, n);

  const auto viewDirs = fibonacciSphere(8 * q.voxelDirections);

  // One unit of work per voxel, then per patch; blocks keep progress and
  // abort responsive and on the calling thread.
  const Index units = nv + el.patchCount;
  const Index block = std::max<Index>(64, units / 100);
  const ProgressRange gatherProgress = progress.sub(0.0, 0.9);
  for (Index b0 = 0; b0 < units; b0 += block) {
    const Index b1 = std::min(units, b0 + block);
    tbb::parallel_for(tbb::blocked_range<Index>(b0, b1), [&](const tbb::blocked_range<Index>& r) {
      for (Index u = r.begin(); u != r.end(); ++u) {
        if (u < nv) {
          const Index v = u;
          if (el.full[v] >= 0) {
            double* rowFront = el.front[v] >= 0 ? out.S.row(el.front[v]).data() : nullptr;
            gatherVoxelLines(medium, el, v, q, out.S.row(el.full[v]).data(), rowFront);
          }
          double* rowFull =
            out.gatherFullRow[v] >= 0 ? out.gatherRows.row(out.gatherFullRow[v]).data() : nullptr;
          double* rowFront =
            out.gatherFrontRow[v] >= 0 ? out.gatherRows.row(out.gatherFrontRow[v]).data() : nullptr;
          if (rowFull || rowFront) {
            const double scale =
              4.0 / gatherVoxelView(medium, el, v, viewDirs, q, rowFull, rowFront);
            for (Index e = 0; e < n; ++e) {
              // G weights: 4 pi sr / pi per unit radiosity.
              if (rowFull) {
                rowFull[e] *= scale;
              }
              if (rowFront) {
                rowFront[e] *= scale;
              }
            }
          }
        } else {
          const Index p = u - nv;
          double* row = out.S.row(el.patchElement(p)).data();
          const double rays = gatherPatch(medium, el, p, q, row);
          const double area = g.patchArea(g.patchLocation(p).face);
          for (Index e = 0; e < n; ++e) {
            row[e] *= area / rays;
          }
        }
      }
    });
    gatherProgress.report(double(b1) / double(units));
  }

  if (options.symmetrize) {
    // Each row is a ray estimate whose relative variance for a pair (a, b)
    // falls as the number of a's rays that reach b, which is proportional to
    // a's rays per unit of its emitting surface. Weighting the two
    // estimates by their inverse variances gives one weight per element.
    const Vec3& h = g.spacing;
    const double voxelSurface = 2.0 * (h[0] * h[1] + h[1] * h[2] + h[0] * h[2]);
    const double voxelRays = 6.0 * q.voxelPointsPerAxis * q.voxelPointsPerAxis * q.voxelDirections;
    const double patchRays =
      double(q.patchPointsPerAxis) * q.patchPointsPerAxis * q.patchDirections;
    Eigen::VectorXd u(n);
    for (Index e = 0; e < n; ++e) {
      u[e] = el.isPatch(e) ? patchRays / exchangeRowTarget(scene, channel, el, e)
                           : voxelRays / voxelSurface;
    }
    // Row i owns the pairs (i, j > i): no two tasks touch the same entry.
    tbb::parallel_for(Index(0), n, [&](Index i) {
      for (Index j = i + 1; j < n; ++j) {
        const double s = (u[i] * out.S(i, j) + u[j] * out.S(j, i)) / (u[i] + u[j]);
        out.S(i, j) = s;
        out.S(j, i) = s;
      }
    });
  }
  if (options.symmetrize && options.smooth && n > 0) {
    const Index nP = el.partitionSize();
    Eigen::VectorXd rowSum = out.S.topLeftCorner(nP, nP).rowwise().sum();
    Eigen::VectorXd residual(nP);
    for (Index e = 0; e < nP; ++e) {
      residual[e] = exchangeRowTarget(scene, channel, el, e) - rowSum[e];
    }
    const Eigen::VectorXd mu = solveSmoothing(out.S, nP, rowSum, residual);
    double maxChange = 0.0;
    for (Index i = 0; i < nP; ++i) {
      for (Index j = 0; j < nP; ++j) {
        const double rel = (i == j) ? mu[i] : mu[i] + mu[j];
        if (out.S(i, j) != 0.0) {
          maxChange = std::max(maxChange, std::abs(rel));
        }
        out.S(i, j) *= 1.0 + rel;
      }
    }
    // Front sides: their partition row sum is 2 kappa_t V; a uniform scale
    // of the row (and of its mirror column) restores it.
    for (Index f = nP; f < n; ++f) {
      const double sum = out.S.row(f).head(nP).sum();
      const double target = exchangeRowTarget(scene, channel, el, f);
      const double scale = sum > 0.0 ? target / sum : 1.0;
      maxChange = std::max(maxChange, std::abs(scale - 1.0));
      out.S.row(f).head(nP) *= scale;
      out.S.col(f).head(nP) *= scale;
    }
    out.quadratureError = maxChange;
  }
  progress.report(1.0);
  return out;
}

NearField computeNearField(const Scene& scene, int channel, const QuadratureSettings& q, int radius)
{
  if (radius < 0) {
    throw Error("the near-field radius must be >= 0");
  }
  const Grid& g = scene.grid;
  const ChannelMedium medium(scene, channel);
  NearField out;
  out.radius = radius;
  out.elements = makeExchangeElements(scene, channel);
  if (out.elements.frontCount > 0) {
    throw Error("the near field does not handle front sides (sigma_d, E_D) yet");
  }
  const ExchangeElements& el = out.elements;
  const Index nv = g.voxelCount();
  const int width = out.stencilSize();
  out.stencil.assign(std::size_t(nv) * width, 0.0);
  out.patches.assign(nv, {});
  out.far.assign(nv, 0.0);
  tbb::parallel_for(Index(0), nv, [&](Index v) {
    if (el.full[v] < 0) {
      return;
    }
    const auto c = g.ijk(v);
    const Vec3 boxLo = g.voxelLower(v) - double(radius) * g.spacing;
    const Vec3 boxHi = g.voxelLower(v) + double(radius + 1) * g.spacing;
    double* row = out.stencil.data() + std::size_t(v) * width;
    auto& patches = out.patches[v];
    double sliver = 0.0;
    const double leftover =
      gatherVoxelLinesInto(medium, el, v, q, true, boxLo, boxHi, [&](Index e, double p, bool) {
        if (el.isPatch(e)) {
          const Index patch = e - el.fullCount;
          auto it = std::find_if(
            patches.begin(), patches.end(), [&](const auto& x) { return x.first == patch; });
          if (it == patches.end()) {
            patches.emplace_back(patch, p);
          } else {
            it->second += p;
          }
          return;
        }
        const auto u = g.ijk(el.voxelOf[e]);
        const int dx = u[0] - c[0], dy = u[1] - c[1], dz = u[2] - c[2];
        if (std::abs(dx) <= radius && std::abs(dy) <= radius && std::abs(dz) <= radius) {
          row[out.offsetIndex(dx, dy, dz)] += p;
        } else {
          sliver += p; // a sliver past the box edge from round-off
        }
      });
    out.far[v] = leftover + sliver;
  });
  return out;
}

} // namespace volrad
