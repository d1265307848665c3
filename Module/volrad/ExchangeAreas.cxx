// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/ExchangeAreas.h"

#include "volrad/LineGathering.h"

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

using namespace detail;

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
  // At most two elements a voxel (full and front side) and the patches.
  const Index most = 2 * nv + scene.grid.patchCount();
  if (most > Index(std::numeric_limits<ExchangeElements::Number>::max())) {
    throw Error("too many voxels for 32-bit element numbers (" + std::to_string(nv) +
                " voxels and " + std::to_string(scene.grid.patchCount()) + " wall patches)");
  }
  el.full.assign(nv, -1);
  el.front.assign(nv, -1);
  for (Index v = 0; v < nv; ++v) {
    if (scene.kappaTAt(v, channel) > 0.0) {
      el.full[v] = ExchangeElements::Number(el.fullCount++);
    }
  }
  el.patchCount = scene.grid.patchCount();
  for (Index v = 0; v < nv; ++v) {
    if (el.full[v] >= 0 && needsFrontSide(scene, v)) {
      el.front[v] = ExchangeElements::Number(el.partitionSize() + el.frontCount++);
    }
  }
  el.voxelOf.assign(el.size(), -1);
  for (Index v = 0; v < nv; ++v) {
    if (el.full[v] >= 0) {
      el.voxelOf[el.full[v]] = ExchangeElements::Number(v);
    }
    if (el.front[v] >= 0) {
      el.voxelOf[el.front[v]] = ExchangeElements::Number(v);
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
  if (!q.exchangeCountsValid()) {
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
            gatherVoxelView(medium,
                            el,
                            v,
                            viewDirs,
                            q,
                            rowFront != nullptr,
                            Reach{},
                            [&](Index e, double p, bool front) {
                              double* row = front ? rowFront : rowFull;
                              if (row) {
                                row[e] += p;
                              }
                            });
          }
        } else {
          const Index p = u - nv;
          double* row = out.S.row(el.patchElement(p)).data();
          gatherPatch(medium, el, p, q, Reach{}, [&](Index e, double w) { row[e] += w; });
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

} // namespace volrad
