// SPDX-License-Identifier: BSD-3-Clause
// The sparse solve's benchmark (issue 6): OpenVDB's smoke sample solved by
// the hierarchical solver over its whole active box ("box": G of the empty
// space too) and sparsely ("sparse": HierarchicalOptions::emptySpaceFields
// off), each in a child process so that its peak resident memory is its own:
//   BenchSparseSolve [--vdb FILE] [--scene FILE] [--threads N] [--dense] [SHRINK ...]
// SHRINK (default 8 4): the file's voxels averaged SHRINK^3 (whole blocks,
// like volrad --shrink). The scene (default Data/smoke.scene.json: cloud
// material, sun and sky) maps the density grid. Prints time, peak memory,
// links and energy residual of both, and the largest relative difference
// of G from the box solve's over the voxels holding smoke. --dense adds the
// dense solver over the box (all factors; the small grids only).
#include "ChildProcess.h"
#include "volrad/DenseSolver.h"
#include "volrad/HierarchicalSolver.h"
#include "volrad/Material.h"
#include "volrad/SceneDescription.h"
#include "volrad/VdbVolume.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace volrad;

namespace {

/// The density grid averaged over whole blocks of shrink^3 voxels, mapped
/// by the scene file.
Scene smokeScene(const std::string& vdb, const std::string& sceneFile, int shrink)
{
  const DenseVolume d = readVdbGrid(vdb, "density");
  const SceneDescription desc = readSceneDescription(sceneFile);
  Scene s;
  for (int a = 0; a < 3; ++a) {
    s.grid.dims[a] = d.dims[a] / shrink;
    s.grid.spacing[a] = d.spacing[a] * shrink;
    s.grid.origin[a] = d.origin[a] + 0.5 * (shrink - 1) * d.spacing[a];
  }
  desc.applyTo(s);
  s.allocate();
  std::vector<double> density(s.grid.voxelCount(), 0.0);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const auto c = s.grid.ijk(v);
    double sum = 0.0;
    for (int k = 0; k < shrink; ++k) {
      for (int j = 0; j < shrink; ++j) {
        for (int i = 0; i < shrink; ++i) {
          const std::size_t x = std::size_t(c[0] * shrink + i), y = std::size_t(c[1] * shrink + j),
                            z = std::size_t(c[2] * shrink + k);
          sum += d.values[x + std::size_t(d.dims[0]) * (y + std::size_t(d.dims[1]) * z)];
        }
      }
    }
    density[v] = sum / (shrink * shrink * shrink);
  }
  applyMaterial(desc.material.map, density, s);
  return s;
}

struct Figures
{
  double seconds = 0, linkSeconds = 0, links = 0, residual = 0, estimatedMiB = 0;
  double converged = 0;
  int dims[3] = { 0, 0, 0 };
  long long medium = 0;
  char error[256] = {};
};

enum class Mode
{
  Box,    ///< the hierarchical solver over the whole box
  Sparse, ///< the same without the fields of empty space
  Dense   ///< the dense solver (every factor) over the whole box
};
const char* const kModeNames[] = { "box", "sparse", "dense" };

/// One solve in this (child) process, the scene made here too (its peak
/// memory is all the child's); G of the medium's voxels to `gFile`.
Figures run(const std::string& vdb,
            const std::string& sceneFile,
            int shrink,
            HierarchicalOptions options,
            Mode mode,
            const std::string& gFile)
{
  Figures f;
  try {
    const Scene s = smokeScene(vdb, sceneFile, shrink);
    for (int a = 0; a < 3; ++a) {
      f.dims[a] = s.grid.dims[a];
    }
    for (Index v = 0; v < s.grid.voxelCount(); ++v) {
      f.medium += s.kappaTAt(v, 0) > 0.0 ? 1 : 0;
    }
    options.emptySpaceFields = mode != Mode::Sparse;
    HierarchicalReport report;
    DenseSolverOptions dense;
    dense.threads = options.threads;
    dense.memoryLimitBytes = 16.0 * (1 << 30);
    const Solution sol =
      mode == Mode::Dense ? solveDense(s, dense) : solveHierarchical(s, options, &report);
    f.seconds = sol.stats.seconds;
    f.linkSeconds = report.linkSeconds;
    f.links = double(sol.stats.links);
    double worst = 0.0;
    for (const EnergyTerms& e : sol.energy) {
      worst = std::max(worst, e.relativeResidual());
    }
    f.residual = worst;
    f.estimatedMiB = double(sol.stats.estimatedBytes) / (1 << 20);
    f.converged = sol.stats.converged ? 1 : 0;
    std::vector<double> G;
    for (Index v = 0; v < s.grid.voxelCount(); ++v) {
      if (s.kappaTAt(v, 0) > 0.0) {
        for (int c = 0; c < s.channels; ++c) {
          G.push_back(sol.G[std::size_t(v) * s.channels + c]);
        }
      }
    }
    FILE* out = std::fopen(gFile.c_str(), "wb");
    if (!out || std::fwrite(G.data(), sizeof(double), G.size(), out) != G.size()) {
      std::snprintf(f.error, sizeof(f.error), "cannot write %s", gFile.c_str());
    }
    if (out) {
      std::fclose(out);
    }
  } catch (const std::exception& e) {
    std::snprintf(f.error, sizeof(f.error), "%s", e.what());
  }
  return f;
}

std::vector<double> readAll(const std::string& path)
{
  std::vector<double> v;
  if (FILE* in = std::fopen(path.c_str(), "rb")) {
    double x;
    while (std::fread(&x, sizeof(x), 1, in) == 1) {
      v.push_back(x);
    }
    std::fclose(in);
  }
  return v;
}

} // namespace

int main(int argc, char* argv[])
{
  std::string vdb = VOLRAD_DATA_DIR "/smoke/smoke.vdb", scene = VOLRAD_DATA_DIR "/smoke.scene.json";
  std::vector<int> shrinks;
  HierarchicalOptions options;
  bool withDense = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--vdb") == 0 && i + 1 < argc) {
      vdb = argv[++i];
    } else if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
      scene = argv[++i];
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      options.threads = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--dense") == 0) {
      withDense = true;
    } else if (std::atoi(argv[i]) >= 1) {
      shrinks.push_back(std::atoi(argv[i]));
    } else {
      std::fprintf(stderr,
                   "usage: BenchSparseSolve [--vdb FILE] [--scene FILE] [--threads N] [--dense] "
                   "[SHRINK ...]\n");
      return 2;
    }
  }
  if (shrinks.empty()) {
    shrinks = { 8, 4 };
  }
  std::printf("%s, scene %s\n", vdb.c_str(), scene.c_str());
  std::printf("%-7s %-14s %9s %8s %8s %9s %10s %10s %20s\n",
              "shrink",
              "grid (smoke)",
              "solve",
              "seconds",
              "links s",
              "peak MiB",
              "links",
              "residual",
              "G vs box: max / rms");
  for (const int shrink : shrinks) {
    std::vector<double> G[3];
    std::vector<Mode> modes = { Mode::Box, Mode::Sparse };
    if (withDense) {
      modes.push_back(Mode::Dense);
    }
    for (const Mode mode : modes) {
      const int m = int(mode);
      const std::string gFile =
        "/tmp/BenchSparseSolve-" + std::to_string(getpid()) + "-" + kModeNames[m];
      Figures f;
      const bench::ChildResult child =
        bench::runInChild([&] { return run(vdb, scene, shrink, options, mode, gFile); }, f);
      G[m] = readAll(gFile);
      std::remove(gFile.c_str());
      char grid[64] = "";
      if (child.finished) {
        std::snprintf(grid,
                      sizeof(grid),
                      "%dx%dx%d (%.0f%%)",
                      f.dims[0],
                      f.dims[1],
                      f.dims[2],
                      100.0 * double(f.medium) / (double(f.dims[0]) * f.dims[1] * f.dims[2]));
      } else {
        std::printf(
          "%-7d %-14s %9s crashed (status %d)\n", shrink, grid, kModeNames[m], child.status);
        continue;
      }
      if (f.error[0]) {
        std::printf("%-7d %-14s %9s error: %s\n", shrink, grid, kModeNames[m], f.error);
        continue;
      }
      // Against the box solve, when both handed back the same voxels' G.
      char diffText[32] = "";
      if (mode != Mode::Box && !G[0].empty() && G[0].size() == G[m].size()) {
        double diff = 0.0, sum = 0.0;
        for (std::size_t k = 0; k < G[0].size(); ++k) {
          const double d = std::abs(G[m][k] - G[0][k]) / std::max(1e-300, std::abs(G[0][k]));
          diff = std::max(diff, d);
          sum += d * d;
        }
        std::snprintf(
          diffText, sizeof(diffText), "%.2g / %.2g", diff, std::sqrt(sum / double(G[0].size())));
      } else if (mode != Mode::Box) {
        std::snprintf(diffText, sizeof(diffText), "n/a");
      }
      std::printf("%-7d %-14s %9s %8.2f %8.2f %9.1f %10.3g %10.2g %20s%s\n",
                  shrink,
                  grid,
                  kModeNames[m],
                  f.seconds,
                  f.linkSeconds,
                  child.peakMiB,
                  f.links,
                  f.residual,
                  diffText,
                  f.converged ? "" : " UNCONVERGED");
    }
  }
  return 0;
}
