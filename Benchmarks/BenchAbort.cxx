// SPDX-License-Identifier: BSD-3-Clause
// How soon a solve stops when asked to (issue 8: within a second). A watcher
// thread asks for the stop after a delay, as a GUI's abort button would,
// while the solve runs on the main thread; the figure is the time from the
// request to the solve's return (volrad::Aborted), printed with the
// progress the solve had reported, for several delays so that the request
// falls into every phase (near field, link refinement, far field, shooting):
//   BenchAbort [--scene phantom|cloud|cube] [--method hierarchical|dense]
//              [--threads N] [--gaps] [N [DELAY_S ...]]
// Default: the phantom at 32^3, hierarchical, delays 0.5 1 2 4 8 16 32 64 s.
// --gaps instead runs one whole solve and prints the longest times between
// two progress reports (where a stop is heard), with the fractions they lay
// between: the bound on the time to stop anywhere in the solve, not only at
// the sampled delays.
#include "BenchmarkScenes.h"

#include "volrad/Solve.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

using namespace volrad;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv)
{
  std::string sceneName = "phantom";
  SolverSettings settings;
  int threads = 0;
  int n = 32;
  std::vector<double> delays;
  bool haveN = false, gaps = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) {
      sceneName = argv[++i];
    } else if (!std::strcmp(argv[i], "--method") && i + 1 < argc) {
      settings.method = argv[++i];
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--gaps")) {
      gaps = true;
    } else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf("usage: BenchAbort [--scene phantom|cloud|cube] [--method M] [--threads N]\n"
                  "         [--gaps] [SIZE [DELAY_SECONDS ...]]\n");
      return 0;
    } else if (!haveN) {
      n = bench::gridSize("BenchAbort", argv[i]);
      if (n == 0) {
        return 2;
      }
      haveN = true;
    } else {
      char* end = nullptr;
      const double x = std::strtod(argv[i], &end);
      if (end == argv[i] || *end || !(x > 0.0) || !std::isfinite(x)) {
        std::fprintf(stderr,
                     "BenchAbort: not an option or a delay in seconds (> 0): %s (--help lists "
                     "the options)\n",
                     argv[i]);
        return 2;
      }
      delays.push_back(x);
    }
  }
  if (delays.empty()) {
    delays = { 0.5, 1, 2, 4, 8, 16, 32, 64 };
  }
  Scene scene;
  try {
    scene = bench::benchmarkScene(sceneName, n);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "BenchAbort: %s\n", e.what());
    return 2;
  }
  if (gaps) {
    struct Gap
    {
      double seconds, from, to;
    };
    std::vector<Gap> all;
    Clock::time_point last = Clock::now();
    double lastFraction = 0.0;
    auto gap = [&](double f) {
      const Clock::time_point now = Clock::now();
      all.push_back({ std::chrono::duration<double>(now - last).count(), lastFraction, f });
      last = now;
      lastFraction = f;
    };
    const Clock::time_point start = Clock::now();
    try {
      solve(scene, settings, threads, [&](double f) {
        gap(f);
        return true;
      });
    } catch (const Error& e) {
      std::fprintf(stderr, "BenchAbort: %s\n", e.what());
      return 1;
    }
    gap(1.0); // from the last report to the return
    std::sort(
      all.begin(), all.end(), [](const Gap& a, const Gap& b) { return a.seconds > b.seconds; });
    std::printf("%s %d^3, %s solver: %zu progress reports in %.1f s; longest gaps between them:\n",
                sceneName.c_str(),
                n,
                settings.method.c_str(),
                all.size() - 1,
                std::chrono::duration<double>(last - start).count());
    for (std::size_t i = 0; i < std::min<std::size_t>(8, all.size()); ++i) {
      std::printf("  %.3f s  between %7.3f%% and %7.3f%%\n",
                  all[i].seconds,
                  100.0 * all[i].from,
                  100.0 * all[i].to);
    }
    return 0;
  }
  std::printf("%s %d^3, %s solver: delay [s] | progress at the request | stopped after [s]\n",
              sceneName.c_str(),
              n,
              settings.method.c_str());
  double worst = 0.0;
  for (double delay : delays) {
    std::atomic<bool> stop{ false };
    std::atomic<double> lastProgress{ 0.0 };
    Clock::time_point requested;
    std::atomic<bool> done{ false };
    const Clock::time_point start = Clock::now();
    std::thread watcher([&] {
      while (!done && Clock::now() - start < std::chrono::duration<double>(delay)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      requested = Clock::now();
      stop = true;
    });
    bool aborted = false;
    double progressAtRequest = -1.0;
    try {
      solve(scene, settings, threads, [&](double f) {
        if (!stop) {
          lastProgress = f;
        } else if (progressAtRequest < 0.0) {
          progressAtRequest = lastProgress;
        }
        return !stop;
      });
    } catch (const Aborted&) {
      aborted = true;
    } catch (const Error& e) {
      done = true;
      watcher.join();
      std::fprintf(stderr, "BenchAbort: %s\n", e.what());
      return 1;
    }
    const Clock::time_point end = Clock::now();
    done = true;
    watcher.join();
    if (!aborted) {
      std::printf("%8.1f | finished before the request (%.1f s)\n",
                  delay,
                  std::chrono::duration<double>(end - start).count());
      break;
    }
    const double latency = std::chrono::duration<double>(end - requested).count();
    worst = std::max(worst, latency);
    std::printf("%8.1f | %5.1f%% | %.3f\n", delay, 100.0 * progressAtRequest, latency);
    std::fflush(stdout);
  }
  std::printf("longest time to stop: %.3f s\n", worst);
  return 0;
}
