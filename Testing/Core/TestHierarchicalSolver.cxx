// SPDX-License-Identifier: BSD-3-Clause
// physics.md 5.5: the hierarchical solver against the dense solver (the
// same zonal model with every factor) on 12^3-16^3 scenes with walls,
// surface-like voxels, RGB and a point light inside a scattering medium;
// its error falls with epsilon; white furnace and energy balance.
#include "BenchmarkScenes.h"
#include "DenseReference.h"
#include "TestScenes.h"
#include "volrad/DenseSolver.h"
#include "volrad/Error.h"
#include "volrad/HierarchicalSolver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace volrad;
using namespace volrad::test;

namespace {

Solution reference(const Scene& s)
{
  return solveDense(s, fineDenseOptions());
}

struct Comparison
{
  double rms = 0.0, residual = 0.0;
  long long links = 0;
};

Comparison compare(const Solution& dense, const Scene& s, double linkTolerance)
{
  HierarchicalOptions ho;
  ho.linkTolerance = linkTolerance;
  const Solution h = solveHierarchical(s, ho);
  EXPECT_TRUE(h.stats.converged);
  Comparison c;
  c.rms = rmsRelative(dense.G, h.G);
  for (const auto& e : h.energy) {
    c.residual = std::max(c.residual, e.relativeResidual());
  }
  c.links = h.stats.links;
  return c;
}

/// At the default tolerances: within 1% RMS of the fine dense reference
/// (whose own quadrature noise is about 0.5%), energy balanced within 0.5%.
/// (Error falling with the link tolerance: PointLightErrorFallsWithTolerance.)
void expectClose(const char* name, const Scene& s)
{
  const Solution dense = reference(s);
  const Comparison c = compare(dense, s, 0.0);
  std::printf("[measured] %s %d^3: hierarchical vs dense G rms rel %.4f at the default link "
              "tolerance (%lld links, energy residual %.2g)\n",
              name,
              s.grid.dims[0],
              c.rms,
              c.links,
              c.residual);
  EXPECT_LT(c.rms, 0.01) << name;
  EXPECT_LT(c.residual, 0.005) << name;
}

} // namespace

TEST(HierarchicalSolver, MatchesDenseWithWalls)
{
  expectClose("walls + emission + sky", wallsScene(14));
}

TEST(HierarchicalSolver, MatchesDenseWithSurfaceLikeVoxels)
{
  expectClose("sigma_d shell + sun", shellTestScene(14));
}

TEST(HierarchicalSolver, MatchesDenseInRgb)
{
  expectClose("RGB + sun + emission", rgbTestScene(12));
}

TEST(HierarchicalSolver, MatchesDenseInAGreyMediumUnderColouredLight)
{
  expectClose("grey medium under coloured light (shared links)", greyColouredScene(12));
}

TEST(HierarchicalSolver, MatchesDenseWithAPointLightInsideAScatteringMedium)
{
  expectClose("point light in a scattering medium", pointLightScene(16));
}

TEST(HierarchicalSolver, ErrorFallsAsLinksAreRefined)
{
  const Scene s = pointLightScene(12);
  const Solution dense = reference(s);
  double previous = 1.0;
  for (double tolerance : { 1e-5, 1e-6, 1e-7 }) {
    const Comparison c = compare(dense, s, tolerance);
    std::printf("[measured] point light 12^3, link tolerance %.0e: G rms rel %.4f, %lld links\n",
                tolerance,
                c.rms,
                c.links);
    EXPECT_LT(c.rms, previous);
    previous = c.rms;
  }
}

// physics.md 5.2 in a 0.99-albedo cube 61 mean free paths across (the
// benchmark's), point light at its centre: every photon scatters about a
// hundred times before it is absorbed, so a residual of epsilon of the
// radiosities alone is tens of epsilons of the absorbed power (the
// benchmark's cube at 128^3: 4.5% at epsilon 1e-3). The stopping test also
// holds the unshot power under epsilon of the light: the energy balances
// to about epsilon (plus the links' own imbalance, about 1e-4 here), and
// closer as epsilon falls.
TEST(HierarchicalSolver, EnergyBalancesToEpsilonInAThickHighAlbedoMedium)
{
  const Scene s = bench::cubeScene61(24);
  double previous = 1.0;
  for (const double epsilon : { 1e-2, 1e-3 }) {
    HierarchicalOptions o;
    o.epsilon = epsilon;
    const Solution h = solveHierarchical(s, o);
    ASSERT_TRUE(h.stats.converged);
    const double r = h.energy[0].relativeResidual();
    std::printf("[measured] cube 24^3, albedo 0.99, 61 mfp, epsilon %.0e: energy residual %.2g "
                "(%lld iterations)\n",
                epsilon,
                r,
                h.stats.iterations);
    EXPECT_LT(r, epsilon + 2e-4);
    EXPECT_LT(r, previous);
    previous = r;
  }
}

// Coarse links: in an optically thin medium (a tenth of the point-light
// scene's coefficients) most of the scattered light travels over cluster
// links, and what a link exchanges varies across its clusters (1/r^2 by 2/r
// per length, the attenuation towards the partner). The far field pulls and
// pushes it to first order and through the clusters' sides; when clusters
// sent and received uniformly, G at link tolerance 1e-4 was 2.8% off, now
// about 1%.
TEST(HierarchicalSolver, ClusterLinksCarryTheVariationAcrossTheirClusters)
{
  Scene s = pointLightScene(12);
  for (auto* a : { &s.kappaA, &s.sigmaI }) {
    for (auto& k : *a) {
      k *= 0.1f;
    }
  }
  const Solution dense = reference(s);
  const Comparison c = compare(dense, s, 1e-4);
  std::printf("[measured] thin medium, point light 12^3, link tolerance 1e-4: G rms rel %.4f, "
              "%lld links\n",
              c.rms,
              c.links);
  EXPECT_LT(c.rms, 0.015);
}

TEST(HierarchicalSolver, SingleThreadedRunsAreBitIdentical)
{
  const Scene s = shellTestScene(8);
  HierarchicalOptions o;
  o.threads = 1;
  const Solution a = solveHierarchical(s, o);
  o.threads = 2;
  const Solution b = solveHierarchical(s, o);
  const Solution c = solveHierarchical(s, o);
  EXPECT_EQ(a.G, b.G); // deterministic whatever the thread count
  EXPECT_EQ(b.G, c.G);
}

// Every phase checks for a stop (issue 8): progress rises to 1 without going
// back, and a stop asked at any of its reports, early, middle or late, ends
// the solve with Aborted.
TEST(HierarchicalSolver, ProgressRisesToOneAndAStopAnywhereEndsTheSolve)
{
  const Scene s = pointLightScene(8);
  HierarchicalOptions o;
  std::vector<double> fractions;
  o.progress = [&](double f) {
    fractions.push_back(f);
    return true;
  };
  solveHierarchical(s, o);
  ASSERT_GT(fractions.size(), 20u);
  for (std::size_t i = 1; i < fractions.size(); ++i) {
    ASSERT_GE(fractions[i], fractions[i - 1]) << "report " << i;
  }
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  const std::size_t reports = fractions.size();
  for (const double at : { 0.05, 0.3, 0.5, 0.7, 0.95 }) {
    const std::size_t stopAt = std::size_t(at * double(reports));
    std::size_t count = 0;
    o.progress = [&](double) { return ++count <= stopAt; };
    EXPECT_THROW(solveHierarchical(s, o), Aborted) << "stop at report " << stopAt;
    EXPECT_EQ(count, stopAt + 1) << "reports after the stop";
  }
}

TEST(HierarchicalSolver, RefusesOverItsMemoryBudget)
{
  const Scene s = pointLightScene(12);
  HierarchicalOptions o;
  // Below what the voxels alone need: refused before the near field.
  o.memoryLimitBytes = 1e5;
  try {
    solveHierarchical(s, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("memory budget"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("before any link"), std::string::npos) << e.what();
  }
  // Enough for the voxels and the fewest links (1728 voxels x 20), not for
  // those the default tolerance needs here (about 1e6): refused during the
  // refinement.
  o.memoryLimitBytes = 2e6 + 64.0 * 2e5;
  try {
    solveHierarchical(s, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("links, over its memory budget"), std::string::npos)
      << e.what();
  }
}

// The views of empty space have their own error budget where the direct
// light shines on them (a fraction of it): the air around a lumpy
// scattering ball in sunlight, some of it in the ball's shadow, against the
// dense solver, over the empty voxels and over the medium apart.
TEST(HierarchicalSolver, LitEmptySpaceMatchesDense)
{
  Scene s = cubeScene(12);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    if ((x - Vec3(0.5, 0.5, 0.5)).norm() > 0.35) {
      continue; // air
    }
    const double kappa = lumpy(x, 2.0, 12.0, 0.7);
    s.kappaA[v] = float(0.1 * kappa);
    s.sigmaI[v] = float(0.9 * kappa);
  }
  s.directionalLights.push_back({ Vec3(0.3, -0.2, -1.0), uniformChannels(1.0) });
  const Solution dense = reference(s);
  const Solution h = solveHierarchical(s, HierarchicalOptions{});
  EXPECT_TRUE(h.stats.converged);
  std::vector<double> refEmpty, gEmpty, refMedium, gMedium;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    auto& r = s.kappaTAt(v, 0) > 0.0 ? refMedium : refEmpty;
    auto& g = s.kappaTAt(v, 0) > 0.0 ? gMedium : gEmpty;
    r.push_back(dense.G[v]);
    g.push_back(h.G[v]);
  }
  const double empty = rmsRelative(refEmpty, gEmpty), medium = rmsRelative(refMedium, gMedium);
  std::printf("[measured] lit empty space 12^3: G rms rel %.4f over %zu empty voxels, %.4f over "
              "%zu medium voxels (%lld links)\n",
              empty,
              refEmpty.size(),
              medium,
              refMedium.size(),
              h.stats.links);
  EXPECT_LT(empty, 0.01);
  EXPECT_LT(medium, 0.01);
}

// Issue 6's sparse solve: with emptySpaceFields off, empty voxels (a
// smoke's background) cost no links or views, and the medium's fields, the
// walls' and the energy terms are those of the solve over the whole box
// (empty voxels neither emit nor scatter: the links they drop carried only
// their own G). RGB (one extinction, albedos per channel), surface-like
// voxels, walls, an emitting wall, sky, sun and a point light in the empty
// space.
TEST(HierarchicalSolver, SparseSolveGivesTheBoxSolveInTheMedium)
{
  Scene s = cubeScene(10, 3);
  radialNormals(s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v);
    const double ball = (x - Vec3(0.3, 0.45, 0.5)).norm();
    const bool slab = x[0] > 0.7 && x[1] > 0.2 && x[2] < 0.6;
    if (ball > 0.25 && !slab) {
      continue; // empty space
    }
    for (int c = 0; c < 3; ++c) {
      const std::size_t o = std::size_t(v) * 3 + c;
      // Short binary fractions: kappa_a + sigma_i is the same in every
      // channel to the last bit, so the channels share one geometry.
      const double kappa = std::round(8.0 * lumpy(x, 1.0, 6.0, 1.1)) / 8.0;
      s.kappaA[o] = float(kappa * (1 + c) / 16.0);
      s.sigmaI[o] = float(kappa - kappa * (1 + c) / 16.0);
      s.sigmaD[o] = ball > 0.15 && ball <= 0.25 ? 4.0f : 0.0f;
      s.emissionI[o] = slab && x[2] < 0.2 ? 0.5f : 0.0f;
    }
  }
  addMixedBoundary(s);
  s.directionalLights.push_back({ Vec3(0.4, -0.3, -1.0), { 1.0, 0.8, 0.6 } });
  s.pointLights.push_back({ Vec3(0.55, 0.8, 0.75), uniformChannels(0.05) });

  HierarchicalOptions o;
  const Solution box = solveHierarchical(s, o);
  o.emptySpaceFields = false;
  const Solution sparse = solveHierarchical(s, o);

  auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-12); };
  double worst = 0.0, emptyBoxG = 0.0;
  Index empty = 0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t o3 = std::size_t(v) * 3 + c;
      if (s.kappaTAt(v, c) > 0.0) {
        for (const auto field : { &Solution::G,
                                  &Solution::Gplus,
                                  &Solution::QI,
                                  &Solution::QD,
                                  &Solution::absorbed }) {
          worst = std::max(worst, relative((sparse.*field)[o3], (box.*field)[o3]));
        }
      } else {
        ++empty;
        EXPECT_EQ(sparse.G[o3], 0.0) << "voxel " << v;
        EXPECT_EQ(sparse.Gplus[o3], 0.0) << "voxel " << v;
        emptyBoxG = std::max(emptyBoxG, box.G[o3]);
      }
    }
  }
  for (std::size_t p = 0; p < box.B.size(); ++p) {
    worst = std::max(worst, relative(sparse.B[p], box.B[p]));
    worst = std::max(worst, relative(sparse.H[p], box.H[p]));
  }
  for (int c = 0; c < 3; ++c) {
    worst = std::max(worst, relative(sparse.energy[c].escaped, box.energy[c].escaped));
    worst =
      std::max(worst, relative(sparse.energy[c].absorbedVoxels, box.energy[c].absorbedVoxels));
    worst = std::max(worst, relative(sparse.energy[c].absorbedWalls, box.energy[c].absorbedWalls));
  }
  std::printf("[measured] %lld of %lld voxel-channels empty; largest relative difference of a "
              "field, sparse vs box: %.3g; links %lld (box %lld)\n",
              (long long)empty,
              (long long)s.grid.voxelCount() * 3,
              worst,
              sparse.stats.links,
              box.stats.links);
  ASSERT_GT(empty, s.grid.voxelCount());
  EXPECT_GT(emptyBoxG, 0.0); // the box solve lights its empty space
  // The same links and sums: equal to round-off (issue 6 asks for 1e-3).
  EXPECT_LE(worst, 1e-12);
  EXPECT_LT(double(sparse.stats.links), 0.9 * double(box.stats.links));
}

// Bone as a CT scan shrunk to centimetre voxels gives it: a skull-like shell
// 30 optical depths per voxel (albedo 0.7, mostly surface-like) around soft
// tissue of 0.2 per voxel, in air, under a sun. Off-centre lines of such
// voxels once counted their light as tens of optical depths less attenuated
// than their gain assumed: the near field's rows summed above 1 and the
// shooting diverged (energy terms of 1e10 on the CT head).
TEST(HierarchicalSolver, ThickBoneBalancesAndMatchesDense)
{
  const int n = 10;
  Scene s = cubeScene(n);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const double r = (s.grid.voxelCentre(v) - Vec3::Constant(0.5)).norm();
    if (r < 0.3) {
      s.kappaA[v] = 0.1f * n;
      s.sigmaI[v] = 1.9f * n;
    } else if (r < 0.45) {
      s.kappaA[v] = 9.0f * n;
      s.sigmaI[v] = 6.0f * n;
      s.sigmaD[v] = 15.0f * n;
    }
  }
  radialNormals(s);
  s.directionalLights.push_back({ Vec3(0.85, -0.45, 0.25), uniformChannels(1.0) });
  const Solution dense = reference(s);
  const Comparison c = compare(dense, s, 0.0);
  std::printf("[measured] thick bone %d^3: hierarchical vs dense G rms rel %.4f (%lld links, "
              "energy residual %.2g)\n",
              n,
              c.rms,
              c.links,
              c.residual);
  EXPECT_LT(c.residual, 0.005);
  EXPECT_LT(c.rms, 0.05);
}
