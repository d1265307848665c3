// SPDX-License-Identifier: BSD-3-Clause
// Render-ready RGBA: alpha is the voxel's opacity along one spacing, colour
// the tone-mapped view-averaged radiance (Q_I + Q_D / 2) / pi.
#include "volrad/Error.h"
#include "volrad/RenderColors.h"
#include "volrad/Sampling.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace volrad;

namespace {

Scene line(int n, int channels)
{
  Scene s;
  s.grid.dims = { n, 2, 2 };
  s.grid.spacing = Vec3(0.5, 0.5, 0.5);
  s.channels = channels;
  s.allocate();
  return s;
}

Solution solutionFor(const Scene& s)
{
  Solution sol;
  sol.channels = s.channels;
  sol.QI.assign(std::size_t(s.grid.voxelCount()) * s.channels, 0.0);
  sol.QD = sol.QI;
  return sol;
}

} // namespace

TEST(RenderColors, AlphaIsTheOpacityOfOneSpacing)
{
  Scene s = line(5, 1);
  Solution sol = solutionFor(s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    s.kappaA[v] = float(0.4 * (v % 5));
  }
  const auto rgba = renderColors(s, sol);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const double alpha = 1.0 - std::exp(-0.4 * (v % 5) * 0.5);
    EXPECT_NEAR(rgba[4 * v + 3], 255.0 * alpha, 0.5) << v;
    EXPECT_EQ(rgba[4 * v], 0); // dark: no colour
  }
}

TEST(RenderColors, ColourIsToneMappedRadiance)
{
  Scene s = line(200, 3);
  Solution sol = solutionFor(s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    for (int c = 0; c < 3; ++c) {
      sol.QI[3 * v + c] = kPi * 0.01 * double(v % 200) * (c + 1);
      sol.QD[3 * v + c] = kPi * 0.01 * double(v % 200);
    }
  }
  sol.QI[3 * 7] = 1e6; // one hot voxel does not set the white point
  double white = 0.0;
  const auto rgba = renderColors(s, sol, {}, &white);
  EXPECT_LT(white, 10.0);
  EXPECT_GT(white, 3.0);
  for (Index v = 1; v < s.grid.voxelCount(); ++v) {
    if (v % 200 == 7 || v % 200 == 0 || v % 200 == 8) {
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const double L = 0.01 * double(v % 200) * (c + 1) + 0.005 * double(v % 200);
      const double expected = 255.0 * std::pow(std::min(1.0, L / white), 1.0 / 2.2);
      EXPECT_NEAR(rgba[4 * v + c], expected, 0.5) << v << " " << c;
    }
    EXPECT_GE(rgba[4 * v + 2], rgba[4 * v]); // the bluest channel is the brightest here
  }
  EXPECT_EQ(rgba[4 * 7], 255); // clamped
  // A fixed white point.
  RenderColorOptions o;
  o.white = 1.0;
  const auto fixed = renderColors(s, sol, o);
  EXPECT_EQ(fixed[4 * 50], std::lround(255.0 * std::pow(0.75, 1.0 / 2.2)));
}

TEST(RenderColors, GreyIsGreyAndMismatchesAreErrors)
{
  Scene s = line(4, 1);
  Solution sol = solutionFor(s);
  sol.QI[3] = 2.0;
  const auto rgba = renderColors(s, sol);
  EXPECT_EQ(rgba[12], 255);
  EXPECT_EQ(rgba[13], 255);
  EXPECT_EQ(rgba[14], 255);
  sol.QI.pop_back();
  EXPECT_THROW(renderColors(s, sol), Error);
}
