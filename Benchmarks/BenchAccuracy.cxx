// SPDX-License-Identifier: BSD-3-Clause
// The hierarchical solver's accuracy against the dense solver, link tolerance
// by link tolerance: G rms and max relative difference (over voxels with G
// above 1% of the largest), links, time and energy residual on the accuracy
// scenes of its tests (TestScenes.h) and the phantom and cloud of its
// benchmark (BenchmarkScenes.h), at 12^3-16^3:
//   BenchAccuracy [--scenes a,b,...] [--epsilon E] [--cache DIR] [TOLERANCE ...]
//   BenchAccuracy --size N --reference-tolerance T [--reference-epsilon E] [...]
//                 [TOLERANCE ...]
// Scenes: walls, shell, rgb, grey, point, thin, phantom, cloud, cube.
// TOLERANCE 0 is the default (3e-4 epsilon). The dense references (minutes
// in all) are kept in DIR (default ./accuracy-references), named by a hash
// of the scene: delete it when the dense solver changes. --size solves the
// scenes at N^3 instead of the tests' sizes; --reference-tolerance compares
// with the hierarchical solver at that finer link tolerance (and iterated
// to E) instead of the dense solver (which stops at about 20^3): how far
// the default is from converged on larger grids, in its links and in its
// iterations.
#include "BenchmarkScenes.h"
#include "DenseReference.h"
#include "TestScenes.h"

#include "volrad/HierarchicalSolver.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace volrad;

namespace {

struct AccuracyScene
{
  std::string name;
  int n; ///< the tests' size
  std::function<Scene(int)> make;
};

const std::vector<AccuracyScene>& allScenes()
{
  static const std::vector<AccuracyScene> scenes = {
    { "walls", 14, test::wallsScene },
    { "shell", 14, test::shellTestScene },
    { "rgb", 12, test::rgbTestScene },
    { "grey", 12, test::greyColouredScene },
    { "point", 16, test::pointLightScene },
    { "thin",
      12,
      [](int n) {
        Scene s = test::pointLightScene(n);
        for (auto* a : { &s.kappaA, &s.sigmaI }) {
          for (auto& k : *a) {
            k *= 0.1f;
          }
        }
        return s;
      } },
    { "phantom", 16, bench::phantomScene },
    { "cloud", 16, bench::cloudScene },
    { "cube", 16, bench::cubeScene61 },
  };
  return scenes;
}

/// FNV-1a over the scene's coefficients, lights and boundary: the cache key.
std::uint64_t fingerprint(const Scene& s)
{
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&h](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h = (h ^ b[i]) * 1099511628211ull;
    }
  };
  add(s.grid.dims.data(), sizeof(s.grid.dims));
  for (const auto* a : { &s.kappaA, &s.sigmaI, &s.sigmaD, &s.emissionI, &s.emissionD }) {
    add(a->data(), a->size() * sizeof(float));
  }
  for (const auto& n : s.normals) {
    add(n.data(), sizeof(n));
  }
  for (const auto& l : s.directionalLights) {
    add(l.direction.data(), 3 * sizeof(double));
    add(l.irradiance.data(), l.irradiance.size() * sizeof(double));
  }
  for (const auto& l : s.pointLights) {
    add(l.position.data(), 3 * sizeof(double));
    add(l.intensity.data(), l.intensity.size() * sizeof(double));
  }
  for (const auto& b : s.boundary) {
    const int type = static_cast<int>(b.type);
    add(&type, sizeof(type));
    add(b.reflectance.data(), b.reflectance.size() * sizeof(double));
    add(b.emission.data(), b.emission.size() * sizeof(double));
    add(b.radiance.data(), b.radiance.size() * sizeof(double));
  }
  return h;
}

std::vector<double> denseReference(const std::string& name, const Scene& s, const std::string& dir)
{
  std::ostringstream file;
  file << dir << "/" << name << "-" << std::hex << fingerprint(s) << ".bin";
  std::vector<double> G(std::size_t(s.grid.voxelCount()) * s.channels);
  if (std::ifstream in{ file.str(), std::ios::binary }) {
    if (in.read(reinterpret_cast<char*>(G.data()), std::streamsize(G.size() * sizeof(double)))) {
      return G;
    }
  }
  std::fprintf(stderr, "%s: dense reference (kept in %s)...\n", name.c_str(), file.str().c_str());
  G = solveDense(s, test::fineDenseOptions()).G;
  std::filesystem::create_directories(dir);
  std::ofstream out(file.str(), std::ios::binary);
  out.write(reinterpret_cast<const char*>(G.data()), std::streamsize(G.size() * sizeof(double)));
  return G;
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> names;
  std::vector<double> tolerances;
  std::string cache = "accuracy-references";
  int size = 0;
  double referenceTolerance = 0.0, referenceEpsilon = 0.0;
  HierarchicalOptions options;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) {
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) {
        names.push_back(item);
      }
    } else if (std::strcmp(argv[i], "--epsilon") == 0 && i + 1 < argc) {
      options.epsilon = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--cache") == 0 && i + 1 < argc) {
      cache = argv[++i];
    } else if (std::strcmp(argv[i], "--size") == 0 && i + 1 < argc) {
      size = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--reference-tolerance") == 0 && i + 1 < argc) {
      referenceTolerance = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--reference-epsilon") == 0 && i + 1 < argc) {
      referenceEpsilon = std::atof(argv[++i]);
    } else {
      char* end = nullptr;
      tolerances.push_back(std::strtod(argv[i], &end));
      if (end == argv[i] || *end) {
        std::fprintf(stderr, "BenchAccuracy: not a tolerance: %s\n", argv[i]);
        return 2;
      }
    }
  }
  if (tolerances.empty()) {
    tolerances = { 0.0 };
  }
  std::vector<const AccuracyScene*> scenes;
  for (const auto& s : allScenes()) {
    if (names.empty() || std::find(names.begin(), names.end(), s.name) != names.end()) {
      scenes.push_back(&s);
    }
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "BenchAccuracy: no such scene\n");
    return 2;
  }
  std::printf("%-8s %5s %10s %8s %8s %10s %8s %8s %10s\n",
              "scene",
              "grid",
              "tolerance",
              "G rms",
              "G max",
              "links",
              "seconds",
              "links s",
              "residual");
  for (const AccuracyScene* a : scenes) {
    const Scene s = a->make(size > 0 ? size : a->n);
    std::vector<double> ref;
    if (referenceTolerance > 0.0) {
      HierarchicalOptions o = options;
      o.linkTolerance = referenceTolerance;
      if (referenceEpsilon > 0.0) {
        o.epsilon = referenceEpsilon;
      }
      const Solution h = solveHierarchical(s, o);
      std::printf("%-8s %4d^3 %10.2g %8s %8s %10lld %8.2f %8s (reference)\n",
                  a->name.c_str(),
                  s.grid.dims[0],
                  referenceTolerance,
                  "",
                  "",
                  h.stats.links,
                  h.stats.seconds,
                  "");
      ref = h.G;
    } else {
      ref = denseReference(a->name, s, cache);
    }
    for (double t : tolerances) {
      HierarchicalOptions o = options;
      o.linkTolerance = t;
      HierarchicalReport report;
      const Solution h = solveHierarchical(s, o, &report);
      double residual = 0.0;
      for (const auto& e : h.energy) {
        residual = std::max(residual, e.relativeResidual());
      }
      std::printf("%-8s %4d^3 %10.2g %7.2f%% %7.1f%% %10lld %8.2f %8.2f %10.2g%s\n",
                  a->name.c_str(),
                  s.grid.dims[0],
                  t > 0.0 ? t : 3e-4 * o.epsilon,
                  100.0 * test::rmsRelative(ref, h.G),
                  100.0 * test::maxRelative(ref, h.G),
                  h.stats.links,
                  h.stats.seconds,
                  report.linkSeconds,
                  residual,
                  h.stats.converged ? "" : " UNCONVERGED");
      // Where the scene has empty voxels (the air around the phantom, the
      // gaps in the cloud), the same figure over the medium and over empty
      // space apart: the empty voxels' G only shows, it feeds nothing back.
      auto empty = [&](std::size_t i) {
        return !(s.kappaTAt(Index(i) / s.channels, int(i) % s.channels) > 0.0);
      };
      bool hasEmpty = false;
      for (std::size_t i = 0; i < ref.size() && !hasEmpty; ++i) {
        hasEmpty = empty(i);
      }
      if (hasEmpty) {
        std::printf("%-8s %4d^3 %10s medium %.2f%%, empty space %.2f%%\n",
                    a->name.c_str(),
                    s.grid.dims[0],
                    "",
                    100.0 * test::rmsRelative(ref, h.G, [&](std::size_t i) { return !empty(i); }),
                    100.0 * test::rmsRelative(ref, h.G, empty));
      }
      std::fflush(stdout);
    }
  }
  return 0;
}
