// SPDX-License-Identifier: BSD-3-Clause
// The hierarchical solver's benchmark (issue 4): time, peak memory, links,
// shots and energy-balance residual on the three benchmark scenes
// (BenchmarkScenes.h) at 32^3, 64^3, 128^3 and 256^3, or at the sizes and
// scenes given:
//   BenchHierarchicalSolver [--scenes a,b,c] [--epsilon E] [--link-tolerance T]
//                           [--threads N] [--memory-budget GIB] [--mc]
//                           [--skip-empty-space] [N ...]
// Each run is a child process, so its peak resident memory is its own; a
// run that fails (memory refused, solver error) prints its message.
// --skip-empty-space leaves out the fields of empty voxels (the air around
// the phantom, the gaps in the cloud: HierarchicalOptions::emptySpaceFields).
// With --mc, G of the cube along the x axis through the light is compared
// with the track-length Monte Carlo estimator of the same medium.
#include "BenchmarkScenes.h"
#include "ChildProcess.h"

#include "volrad/HierarchicalSolver.h"
#include "volrad/MonteCarlo.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

using namespace volrad;

namespace {

struct Figures
{
  double seconds = 0, nearSeconds = 0, linkSeconds = 0, iterationSeconds = 0;
  double links = 0, shots = 0, iterations = 0, residual = 0, estimatedMiB = 0;
  double krylov = 0, converged = 0;
  char error[256] = {};
};

Figures run(const std::string& name, int n, const HierarchicalOptions& options)
{
  Figures f;
  try {
    const Scene s = bench::benchmarkScene(name, n);
    HierarchicalReport report;
    const Solution sol = solveHierarchical(s, options, &report);
    f.seconds = sol.stats.seconds;
    f.nearSeconds = report.nearSeconds;
    f.linkSeconds = report.linkSeconds;
    f.iterationSeconds = report.iterationSeconds;
    f.links = double(sol.stats.links);
    f.shots = double(report.shots);
    f.iterations = double(sol.stats.iterations);
    f.residual = sol.energy[0].relativeResidual();
    f.estimatedMiB = double(sol.stats.estimatedBytes) / (1 << 20);
    f.krylov = report.usedKrylov ? 1 : 0;
    f.converged = sol.stats.converged ? 1 : 0;
  } catch (const std::exception& e) {
    std::snprintf(f.error, sizeof(f.error), "%s", e.what());
  }
  return f;
}

/// G along the x axis through the cube's centre: solver against Monte Carlo
/// of the transport equation (the exact answer of the piecewise-constant
/// medium) and of the zonal model the solver discretises (scattered light
/// leaving from a uniform point of its voxel), which separates the solver's
/// own error from the zonal model's.
void compareCubeAxis(int n, const HierarchicalOptions& options)
{
  const Scene s = bench::cubeScene61(n);
  const Solution sol = solveHierarchical(s, options);
  MonteCarloOptions mc;
  mc.photons = 2000000;
  const MonteCarloEstimate transport = estimateMonteCarlo(s, mc);
  mc.zonal = true;
  const MonteCarloEstimate zonal = estimateMonteCarlo(s, mc);
  const Grid& g = s.grid;
  const int j = n / 2, k = n / 2;
  std::printf("cube %d^3: G along x through the light (y, z index %d), hierarchical vs Monte Carlo "
              "(%lld photons)\n",
              n,
              j,
              mc.photons);
  std::printf("%6s %12s %12s %9s %12s %9s %10s %10s\n",
              "i",
              "G",
              "transport",
              "sigma",
              "zonal",
              "sigma",
              "vs transp.",
              "vs zonal");
  double sumT = 0.0, sumZ = 0.0;
  for (int i = 0; i < n; ++i) {
    const Index v = g.index(i, j, k);
    const double a = sol.G[v], t = transport.G[v], z = zonal.G[v];
    const double dt = t > 0.0 ? a / t - 1.0 : 0.0, dz = z > 0.0 ? a / z - 1.0 : 0.0;
    if (i % std::max(1, n / 16) == 0 || i == n / 2) {
      std::printf("%6d %12.5g %12.5g %8.2f%% %12.5g %8.2f%% %+9.2f%% %+9.2f%%\n",
                  i,
                  a,
                  t,
                  100.0 * transport.GStdErr[v] / t,
                  z,
                  100.0 * zonal.GStdErr[v] / z,
                  100.0 * dt,
                  100.0 * dz);
    }
    sumT += dt * dt;
    sumZ += dz * dz;
  }
  std::printf("rms relative difference along the axis: %.2f%% from transport, %.2f%% from zonal "
              "Monte Carlo\n",
              100.0 * std::sqrt(sumT / n),
              100.0 * std::sqrt(sumZ / n));
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<int> sizes;
  std::vector<std::string> scenes = { "phantom", "cloud", "cube" };
  bool mc = false;
  HierarchicalOptions options;
  bool bad = false;
  auto number = [&](const char* option, const char* text) {
    char* end = nullptr;
    const double x = std::strtod(text, &end);
    if (end == text || *end || !std::isfinite(x)) {
      std::fprintf(stderr, "BenchHierarchicalSolver: %s needs a number, not '%s'\n", option, text);
      bad = true;
    }
    return x;
  };
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) {
      scenes.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) {
        scenes.push_back(item);
      }
    } else if (std::strcmp(argv[i], "--epsilon") == 0 && i + 1 < argc) {
      options.epsilon = number("--epsilon", argv[++i]);
    } else if (std::strcmp(argv[i], "--link-tolerance") == 0 && i + 1 < argc) {
      options.linkTolerance = number("--link-tolerance", argv[++i]);
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      const double t = number("--threads", argv[++i]);
      if (!bad && (t < 0.0 || t != std::floor(t) || t > 4096)) {
        std::fprintf(stderr, "BenchHierarchicalSolver: --threads needs a count (0: all cores)\n");
        bad = true;
      }
      options.threads = bad ? 0 : int(t);
    } else if (std::strcmp(argv[i], "--memory-budget") == 0 && i + 1 < argc) {
      options.memoryLimitBytes = number("--memory-budget", argv[++i]) * double(1 << 30);
    } else if (std::strcmp(argv[i], "--mc") == 0) {
      mc = true;
    } else if (std::strcmp(argv[i], "--skip-empty-space") == 0) {
      options.emptySpaceFields = false;
    } else if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf("usage: BenchHierarchicalSolver [--scenes phantom,cloud,cube] [--epsilon E]\n"
                  "         [--link-tolerance T] [--threads N] [--memory-budget GiB] [--mc]\n"
                  "         [--skip-empty-space]\n"
                  "         [SIZE ...]   (grid sizes n for n^3 voxels; default 32 64 128 256)\n");
      return 0;
    } else {
      const int n = bench::gridSize("BenchHierarchicalSolver", argv[i]);
      if (n == 0) {
        return 2;
      }
      sizes.push_back(n);
    }
  }
  if (bad) {
    return 2;
  }
  if (sizes.empty()) {
    sizes = { 32, 64, 128, 256 };
  }
  for (const std::string& name : scenes) {
    try {
      bench::benchmarkScene(name, 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "BenchHierarchicalSolver: %s\n", e.what());
      return 2;
    }
  }
  std::printf("%-8s %5s %8s %8s %8s %8s %9s %10s %10s %6s %10s %9s\n",
              "scene",
              "grid",
              "seconds",
              "near s",
              "links s",
              "iter s",
              "peak MiB",
              "links",
              "shots",
              "iters",
              "residual",
              "notes");
  for (const std::string& name : scenes) {
    for (int n : sizes) {
      Figures f;
      const bench::ChildResult child = bench::runInChild([&] { return run(name, n, options); }, f);
      if (!child.finished) {
        std::printf("%-8s %4d^3 crashed (status %d)\n", name.c_str(), n, child.status);
      } else if (f.error[0]) {
        std::printf("%-8s %4d^3 error: %s\n", name.c_str(), n, f.error);
      } else {
        std::printf("%-8s %4d^3 %8.2f %8.2f %8.2f %8.2f %9.1f %10.3g %10.3g %6.0f %10.2g %9s\n",
                    name.c_str(),
                    n,
                    f.seconds,
                    f.nearSeconds,
                    f.linkSeconds,
                    f.iterationSeconds,
                    child.peakMiB,
                    f.links,
                    f.shots,
                    f.iterations,
                    f.residual,
                    f.converged ? (f.krylov ? "krylov" : "") : "UNCONV");
      }
    }
  }
  if (mc) {
    compareCubeAxis(sizes.front(), options);
  }
  return 0;
}
