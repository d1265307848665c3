// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/RenderColors.h"

#include "volrad/Error.h"
#include "volrad/Sampling.h"

#include <algorithm>
#include <cmath>

namespace volrad {

std::vector<std::uint8_t> renderColors(const Scene& scene,
                                       const Solution& sol,
                                       const RenderColorOptions& opt,
                                       double* whiteOut)
{
  const Index nv = scene.grid.voxelCount();
  const int C = sol.channels;
  if (sol.QI.size() != std::size_t(nv) * C || sol.QD.size() != std::size_t(nv) * C) {
    throw Error("render colours: the solution does not match the scene");
  }
  if (!(opt.gamma > 0.0) || !(opt.white >= 0.0)) {
    throw Error("render colours: gamma must be > 0 and white >= 0");
  }
  auto radiance = [&](Index v, int c) {
    const std::size_t o = std::size_t(v) * C + c;
    return (sol.QI[o] + 0.5 * sol.QD[o]) / kPi;
  };
  double white = opt.white;
  if (white == 0.0) {
    std::vector<double> peak;
    peak.reserve(nv);
    for (Index v = 0; v < nv; ++v) {
      double m = 0.0;
      for (int c = 0; c < C; ++c) {
        m = std::max(m, radiance(v, c));
      }
      if (m > 0.0) {
        peak.push_back(m);
      }
    }
    if (!peak.empty()) {
      const std::size_t k = std::min(peak.size() - 1, std::size_t(0.995 * double(peak.size())));
      std::nth_element(peak.begin(), peak.begin() + k, peak.end());
      white = peak[k];
    }
  }
  if (whiteOut) {
    *whiteOut = white;
  }
  const double h = scene.grid.spacing.mean();
  std::vector<std::uint8_t> rgba(std::size_t(nv) * 4, 0);
  auto byte = [](double x) { return std::uint8_t(std::lround(255.0 * std::clamp(x, 0.0, 1.0))); };
  for (Index v = 0; v < nv; ++v) {
    double kt = 0.0;
    for (int c = 0; c < scene.channels; ++c) {
      kt += scene.kappaTAt(v, c);
    }
    kt /= scene.channels;
    for (int k = 0; k < 3; ++k) {
      const double L = radiance(v, C == 1 ? 0 : k);
      rgba[4 * std::size_t(v) + k] =
        white > 0.0 ? byte(std::pow(std::min(1.0, L / white), 1.0 / opt.gamma)) : 0;
    }
    rgba[4 * std::size_t(v) + 3] = byte(-std::expm1(-kt * h));
  }
  return rgba;
}

} // namespace volrad
