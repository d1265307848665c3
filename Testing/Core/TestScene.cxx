// SPDX-License-Identifier: BSD-3-Clause
// Scene validation: every invalid value is refused with a message naming it.
#include "TestScenes.h"
#include "volrad/Error.h"
#include "volrad/Normals.h"

#include <gtest/gtest.h>

#include <limits>

using namespace volrad;
using namespace volrad::test;

namespace {

std::string errorOf(const Scene& s)
{
  try {
    s.validate();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(Scene, ValidSceneIsAccepted)
{
  EXPECT_EQ(errorOf(cubeScene(4)), "");
}

TEST(Scene, BadValuesAreNamed)
{
  Scene s = cubeScene(4);
  s.kappaA[s.grid.index(1, 2, 3)] = -1.0f;
  EXPECT_NE(errorOf(s).find("kappa_a = -1 at voxel 57 (i=1, j=2, k=3)"), std::string::npos)
    << errorOf(s);

  s = cubeScene(4);
  s.sigmaI[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(errorOf(s).find("sigma_i = nan"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.emissionI[0] = std::numeric_limits<float>::infinity();
  EXPECT_NE(errorOf(s).find("E_I = inf"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.grid.spacing[1] = 0.0;
  EXPECT_NE(errorOf(s).find("spacing[1] = 0"), std::string::npos) << errorOf(s);

  // Spacing in [1e-9, 1e9] and at most 1e4 between axes (a spacing of 6e29,
  // accepted before, gave NaN fields: found by Testing/Fuzz/FuzzSolver).
  for (const Vec3& h : { Vec3(1, 6e29, 1), Vec3(1e-12, 1e-12, 1e-12), Vec3(1, 1, 2e4) }) {
    s = cubeScene(4);
    s.grid.spacing = h;
    EXPECT_NE(errorOf(s).find("must lie in [1e-9, 1e9], its largest at most 1e4 times"),
              std::string::npos)
      << errorOf(s);
  }

  s = cubeScene(4);
  s.grid.dims[2] = 0;
  EXPECT_NE(errorOf(s).find("empty"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.sigmaD[s.grid.index(0, 0, 1)] = 1.0f;
  EXPECT_NE(errorOf(s).find("no normal"), std::string::npos) << errorOf(s);
  EXPECT_NE(errorOf(s).find("i=0, j=0, k=1"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.boundary[2].type = BoundaryCondition::Type::Wall;
  s.boundary[2].reflectance = uniformChannels(1.0);
  EXPECT_NE(errorOf(s).find("boundary ymin reflectance"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.directionalLights.push_back({ Vec3::Zero(), uniformChannels(1.0) });
  EXPECT_NE(errorOf(s).find("directional light 0"), std::string::npos) << errorOf(s);

  s = cubeScene(4);
  s.channels = 2;
  EXPECT_NE(errorOf(s).find("channels"), std::string::npos) << errorOf(s);
}

TEST(Scene, GradientNormalsPointFromDenseToLessDense)
{
  Scene s = cubeScene(6);
  std::vector<double> density(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    density[v] = 10.0 - s.grid.voxelCentre(v)[2] * 3.0; // denser at the bottom
  }
  const auto n = gradientNormals(s.grid, density);
  for (const auto& x : n) {
    EXPECT_NEAR(x[2], 1.0, 1e-6);
  }
  // A constant field has no gradient: no normals.
  std::fill(density.begin(), density.end(), 1.0);
  for (const auto& x : gradientNormals(s.grid, density)) {
    EXPECT_EQ(x[0] * x[0] + x[1] * x[1] + x[2] * x[2], 0.0f);
  }
}
