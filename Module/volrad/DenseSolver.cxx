// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/DenseSolver.h"

#include "volrad/DirectLight.h"
#include "volrad/EnergyBalance.h"
#include "volrad/ExchangeAreas.h"
#include "volrad/Sampling.h"
#include "volrad/ZonalSystem.h"

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <tbb/task_arena.h>

#include <chrono>
#include <memory>
#include <sstream>

namespace volrad {

namespace {

struct LinearSolveResult
{
  Eigen::VectorXd x;
  long long iterations = 0;
  double residual = 0.0; ///< max |x - (e + c (S x + D))|
};

LinearSolveResult solveSystem(const RowMatrix& S,
                              const ZonalSystem& sys,
                              const DenseSolverOptions& opt)
{
  const Index n = S.rows();
  LinearSolveResult out;
  out.x = sys.e;
  std::vector<Index> unknown;
  for (Index i = 0; i < n; ++i) {
    if (sys.c[i] > 0.0) {
      unknown.push_back(i);
    }
  }
  const Index m = Index(unknown.size());
  if (m > 0) {
    // Right-hand side with the fixed radiosities moved over.
    Eigen::VectorXd fixed = sys.e;
    for (Index i : unknown) {
      fixed[i] = 0.0;
    }
    const Eigen::VectorXd Sfixed = S * fixed;
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd b(m);
    for (Index r = 0; r < m; ++r) {
      const Index i = unknown[r];
      for (Index col = 0; col < m; ++col) {
        A(r, col) = -sys.c[i] * S(i, unknown[col]);
      }
      A(r, r) += 1.0;
      b[r] = sys.e[i] + sys.c[i] * (sys.D[i] + Sfixed[i]);
      // Jacobi scaling: dividing by 1 - c S_ii solves the self term implicitly.
      const double diag = A(r, r);
      if (!(diag > 1e-12)) {
        throw Error(
          "the dense solve is singular: an element scatters back all it emits (self term " +
          std::to_string(1.0 - diag) + ")");
      }
      A.row(r) /= diag;
      b[r] /= diag;
    }
    Eigen::BiCGSTAB<Eigen::MatrixXd, Eigen::IdentityPreconditioner> solver;
    solver.setTolerance(opt.tolerance);
    solver.setMaxIterations(opt.maxIterations);
    solver.compute(A);
    Eigen::VectorXd y = solver.solve(b);
    out.iterations = solver.iterations();
    if (solver.info() != Eigen::Success || !y.allFinite() ||
        (A * y - b).norm() > 10 * opt.tolerance * b.norm()) {
      y = A.partialPivLu().solve(b); // robust fallback
    }
    if (!y.allFinite()) {
      throw Error(
        "the dense linear solve failed (non-finite radiosity): the scene is numerically singular");
    }
    for (Index r = 0; r < m; ++r) {
      out.x[unknown[r]] = y[r];
    }
  }
  const Eigen::VectorXd update = sys.e + sys.c.cwiseProduct(S * out.x + sys.D);
  out.residual = n > 0 ? (update - out.x).cwiseAbs().maxCoeff() : 0.0;
  return out;
}

struct ChannelSizes
{
  Index elements = 0, gatherRows = 0, unknowns = 0;
};

ChannelSizes channelSizes(const Scene& scene, int ch)
{
  ChannelSizes s;
  const Grid& g = scene.grid;
  s.elements = g.patchCount();
  for (int f = 0; f < kFaceCount; ++f) {
    if (scene.boundary[f].type == BoundaryCondition::Type::Wall &&
        scene.boundary[f].reflectance[ch] > 0.0) {
      s.unknowns += g.facePatchCount(Face(f));
    }
  }
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const bool front = needsFrontSide(scene, v);
    if (scene.kappaTAt(v, ch) > 0.0) {
      s.elements += front ? 2 : 1;
      s.unknowns += (scene.sigmaIAt(v, ch) > 0.0) + (front && scene.sigmaDAt(v, ch) > 0.0);
    } else {
      s.gatherRows += 1;
    }
    s.gatherRows += (!front && scene.hasNormal(v)) ? 1 : 0;
  }
  return s;
}

bool sameExtinction(const Scene& s, int a, int b)
{
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    if (s.kappaTAt(v, a) != s.kappaTAt(v, b)) {
      return false;
    }
  }
  return true;
}

} // namespace

double estimateDenseSolverBytes(const Scene& scene)
{
  double peak = 0.0;
  for (int ch = 0; ch < scene.channels; ++ch) {
    const ChannelSizes s = channelSizes(scene, ch);
    const double n = double(s.elements);
    // S, the gather rows, and the system matrix twice (the LU fallback copies it).
    const double m = double(s.unknowns);
    const double bytes = 8.0 * (n * n + double(s.gatherRows) * n + 2.0 * m * m);
    peak = std::max(peak, bytes);
  }
  return peak;
}

Solution solveDense(const Scene& scene, const DenseSolverOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  scene.validate();
  const double bytes = estimateDenseSolverBytes(scene);
  if (bytes > options.memoryLimitBytes) {
    std::ostringstream m;
    m << "the dense solver would need about " << bytes / (1024.0 * 1024.0) << " MiB for "
      << scene.grid.voxelCount() << " voxels and " << scene.grid.patchCount()
      << " boundary patches, over its memory budget of "
      << options.memoryLimitBytes / (1024.0 * 1024.0)
      << " MiB: use the hierarchical solver (solver.method), or raise the budget";
    throw Error(m.str());
  }
  const Grid& g = scene.grid;
  const int C = scene.channels;

  Solution sol = emptySolution(scene, "dense");
  sol.stats.estimatedBytes = std::size_t(bytes);

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const ProgressRange progress(options.progress, 0.0, 1.0);
  std::unique_ptr<ExchangeAreas> ex;
  int exChannel = -1;
  const double V = g.voxelVolume();
  for (int ch = 0; ch < C; ++ch) {
    const ProgressRange chProgress = progress.sub(double(ch) / C, double(ch + 1) / C);
    if (!ex || !sameExtinction(scene, exChannel, ch)) {
      ex.reset();
      arena.execute([&] {
        ex = std::make_unique<ExchangeAreas>(
          computeExchangeAreas(scene, ch, options.quadrature, {}, chProgress.sub(0.0, 0.8)));
      });
      exChannel = ch;
      const double n = double(ex->elements.size());
      sol.stats.links += static_cast<long long>(n * (n + 1) / 2);
      sol.stats.quadratureError = std::max(sol.stats.quadratureError, ex->quadratureError);
    }
    DirectLighting dl;
    arena.execute(
      [&] { dl = computeDirectLight(scene, ch, options.quadrature, chProgress.sub(0.8, 0.85)); });
    const ExchangeElements& el = ex->elements;
    const ZonalSystem sys = buildZonalSystem(scene, ch, el, dl);
    LinearSolveResult lin;
    arena.execute([&] { lin = solveSystem(ex->S, sys, options); });
    chProgress.report(0.95);
    sol.stats.iterations += lin.iterations;
    sol.stats.finalUnshot = std::max(sol.stats.finalUnshot, lin.residual);
    const Eigen::VectorXd x = lin.x;
    const Eigen::VectorXd collided = ex->S * x + sys.D;

    storeChannelFields(
      scene,
      ch,
      el,
      x,
      collided,
      [&](Index v) { return ex->gatherRows.row(ex->gatherFullRow[v]).dot(x) + dl.track[v] / V; },
      [&](Index v) {
        return ex->gatherRows.row(ex->gatherFrontRow[v]).dot(x) + dl.trackFront[v] / V;
      },
      sol);
    sol.energy[ch] = computeEnergyTerms(scene, ch, sol, dl.entering);
  }
  progress.report(1.0);
  sol.stats.seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sol;
}

} // namespace volrad
