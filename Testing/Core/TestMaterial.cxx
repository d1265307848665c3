// SPDX-License-Identifier: BSD-3-Clause
// Materials: transfer functions, the mapping rule of Material.h, presets
// that give valid scenes, and the scene file's material keys.
#include "volrad/Error.h"
#include "volrad/Material.h"
#include "volrad/Normals.h"
#include "volrad/SceneDescription.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace volrad;

namespace {

Scene grid(int n, int channels, double h = 1.0)
{
  Scene s;
  s.grid.dims = { n, n, n };
  s.grid.spacing = Vec3::Constant(h);
  s.grid.origin = Vec3::Zero();
  s.channels = channels;
  s.allocate();
  return s;
}

/// A CT-like head in Hounsfield units: air, soft tissue, a bone shell.
std::vector<double> ctHead(const Grid& g)
{
  std::vector<double> hu(g.voxelCount());
  const Vec3 c = 0.5 * (g.lower() + g.upper());
  const double R = 0.45 * (g.upper() - g.lower()).minCoeff();
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const double r = (g.voxelCentre(v) - c).norm() / R;
    hu[v] = r < 0.8 ? 40.0 : (r < 1.0 ? 1200.0 : -1000.0);
  }
  return hu;
}

/// The error a scene file gives ("no error" if none).
std::string message(const char* text)
{
  try {
    parseSceneDescription(text);
  } catch (const Error& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

} // namespace

TEST(Material, TransferFunctionsInterpolateAndClamp)
{
  const TransferFunction f{ { { 0.0, 1.0 }, { 10.0, 3.0 }, { 20.0, 3.0 } } };
  EXPECT_DOUBLE_EQ(f(-5.0), 1.0);
  EXPECT_DOUBLE_EQ(f(0.0), 1.0);
  EXPECT_DOUBLE_EQ(f(2.5), 1.5);
  EXPECT_DOUBLE_EQ(f(10.0), 3.0);
  EXPECT_DOUBLE_EQ(f(15.0), 3.0);
  EXPECT_DOUBLE_EQ(f(1e9), 3.0);
  EXPECT_DOUBLE_EQ(TransferFunction{}(4.0), 0.0);
}

TEST(Material, MappingConservesExtinctionAndSplitsScatteringByGradient)
{
  Scene s = grid(8, 3, 0.5);
  std::vector<double> scalars(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    scalars[v] = s.grid.voxelCentre(v)[0] < 2.0 ? 0.0 : 100.0; // one sharp step
  }
  s.normals = gradientNormals(s.grid, scalars);
  MaterialMap m;
  m.extinction = TransferFunction{ { { 0.0, 1.0 }, { 100.0, 5.0 } } };
  m.albedo = TransferFunction{ { { 0.0, 0.9 } } };
  m.color[1] = TransferFunction{ { { 0.0, 0.5 } } };
  m.emission[2] = TransferFunction{ { { 0.0, 0.0 }, { 100.0, 2.0 } } };
  m.surfaceGradient = 20.0;
  applyMaterial(m, scalars, s);
  bool sawSurface = false;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const double kt = m.extinction(scalars[v]);
    for (int c = 0; c < 3; ++c) {
      // kappa_t is the extinction in every channel; the albedo is coloured.
      EXPECT_NEAR(s.kappaTAt(v, c), kt, 1e-5 * kt);
      const double a = 0.9 * (c == 1 ? 0.5 : 1.0);
      EXPECT_NEAR(s.sigmaIAt(v, c) + s.sigmaDAt(v, c), a * kt, 1e-5 * kt);
      EXPECT_NEAR(s.emissionIAt(v, c), c == 2 ? scalars[v] / 50.0 : 0.0, 1e-6);
    }
    // Surface-like only across the step (gradient 100 / 1.0 = 100 per unit).
    const double share = s.sigmaDAt(v, 0) / (s.sigmaIAt(v, 0) + s.sigmaDAt(v, 0));
    if (s.hasNormal(v)) {
      EXPECT_NEAR(share, 1.0 - std::exp(-100.0 / 20.0), 1e-5);
      sawSurface = true;
    } else {
      EXPECT_EQ(share, 0.0);
    }
  }
  EXPECT_TRUE(sawSurface);
  s.validate();
}

TEST(Material, RelativeAndPerVoxelFunctions)
{
  Scene s = grid(4, 1, 0.25);
  std::vector<double> scalars(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    scalars[v] = 1000.0 + 10.0 * double(v % 5); // range [1000, 1040]
  }
  MaterialMap m = materialPreset("cloud"); // relative, 0.5 per voxel at the top
  applyMaterial(m, scalars, s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const double rel = (scalars[v] - 1000.0) / 40.0;
    EXPECT_NEAR(s.kappaTAt(v, 0), 0.5 * rel / 0.25, 1e-5);
    EXPECT_NEAR(s.kappaAAt(v, 0), 0.01 * 0.5 * rel / 0.25, 1e-6);
  }
}

TEST(Material, RescaleMapsStoredValuesFirst)
{
  // CT stored without its offset: value = HU + 1024.
  Scene a = grid(6, 3, 1.0), b = grid(6, 3, 1.0);
  const std::vector<double> hu = ctHead(a.grid);
  std::vector<double> stored(hu.size());
  for (std::size_t i = 0; i < hu.size(); ++i) {
    stored[i] = hu[i] + 1024.0;
  }
  a.normals = b.normals = gradientNormals(a.grid, hu);
  applyMaterial(materialPreset("ct"), hu, a);
  MaterialMap m = materialPreset("ct");
  m.rescaleIntercept = -1024.0;
  applyMaterial(m, stored, b);
  EXPECT_EQ(a.kappaA, b.kappaA);
  EXPECT_EQ(a.sigmaI, b.sigmaI);
  EXPECT_EQ(a.sigmaD, b.sigmaD);
  m.rescaleSlope = 0.0;
  EXPECT_THROW(validateMaterial(m), Error);
  const SceneDescription d = parseSceneDescription(
    R"({"version": 1, "material": {"preset": "ct", "rescale_slope": 2, "rescale_intercept": -1024}})");
  EXPECT_EQ(d.material.map.rescaleSlope, 2.0);
  EXPECT_EQ(d.material.map.rescaleIntercept, -1024.0);
}

TEST(Material, LabelTablesGiveEachLabelItsMaterial)
{
  // A segmentation: labels 0 (background), 3 and 7, and 9 (not listed).
  const SceneDescription d = parseSceneDescription(R"({"version": 1, "channels": 3,
    "material": {"labels": {
      "3": {"extinction": 0.5, "albedo": 0.8, "color": [1, 0.5, 0.25]},
      "7": {"extinction": 2, "albedo": 0.5, "emission": [0, 0, 4]}}}})");
  ASSERT_TRUE(d.material.map.active());
  Scene s = grid(4, 3, 0.5);
  std::vector<double> labels(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const int pick[4] = { 0, 3, 7, 9 };
    labels[v] = pick[v % 4] + (v % 3 == 0 ? 0.2 : -0.2); // rounded to the label
  }
  applyMaterial(d.material.map, labels, s);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const int label = int(std::lround(labels[v]));
    for (int c = 0; c < 3; ++c) {
      const double kt = label == 3 ? 0.5 : (label == 7 ? 2.0 : 0.0);
      const double a = label == 3 ? 0.8 * (c == 0 ? 1.0 : (c == 1 ? 0.5 : 0.25)) : 0.5;
      EXPECT_NEAR(s.kappaTAt(v, c), kt, 1e-6);
      EXPECT_NEAR(s.sigmaIAt(v, c), a * kt, 1e-6);
      EXPECT_EQ(s.sigmaDAt(v, c), 0.0);
      EXPECT_NEAR(s.emissionIAt(v, c), label == 7 && c == 2 ? 4.0 : 0.0, 1e-6);
    }
  }
  s.validate();

  EXPECT_NE(message(R"({"version": 1, "material": {"labels": {"bone": {"extinction": 1}}}})")
              .find("'bone'"),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"labels": {"2": {"albedo": 0.5}}}})")
              .find("material.labels.2"),
            std::string::npos);
  EXPECT_NE(
    message(R"({"version": 1, "material": {"labels": {"2": {"extinction": 1, "albedo": 3}}}})")
      .find("material.labels.2.albedo"),
    std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"extinction": [[0, 1]],
                      "labels": {"2": {"extinction": 1}}}})")
              .find("not both"),
            std::string::npos);
}

TEST(Material, PresetsGiveValidScenes)
{
  for (const std::string& name : materialPresetNames()) {
    Scene s = grid(12, name == "cloud" ? 1 : 3, 1.0);
    const std::vector<double> hu = ctHead(s.grid);
    s.normals = gradientNormals(s.grid, hu);
    applyMaterial(materialPreset(name), hu, s);
    EXPECT_NO_THROW(s.validate()) << name;
    EXPECT_FALSE(materialPresetDescription(name).empty());
  }
  // CT: air is empty, bone much denser than soft tissue and partly surface-like.
  Scene s = grid(12, 3, 1.0);
  const std::vector<double> hu = ctHead(s.grid);
  s.normals = gradientNormals(s.grid, hu);
  applyMaterial(materialPreset("ct"), hu, s);
  double bone = 0.0, tissue = 0.0, boneSurface = 0.0;
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    if (hu[v] < -500) {
      EXPECT_EQ(s.kappaTAt(v, 0), 0.0);
    } else if (hu[v] > 1000) {
      bone = std::max(bone, s.kappaTAt(v, 0));
      boneSurface = std::max(boneSurface, s.sigmaDAt(v, 0));
    } else {
      tissue = std::max(tissue, s.kappaTAt(v, 0));
    }
  }
  EXPECT_GT(bone, 10.0 * tissue);
  EXPECT_GT(boneSurface, 0.0);
}

TEST(Material, BadFunctionsAndPresetsAreNamed)
{
  try {
    materialPreset("marble");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("known: ct, ct-bone, mr, cloud"), std::string::npos)
      << e.what();
  }
  MaterialMap m;
  m.extinction = TransferFunction{ { { 0.0, 1.0 }, { -1.0, 2.0 } } };
  EXPECT_THROW(validateMaterial(m), Error);
  m.extinction = TransferFunction{ { { 0.0, -1.0 } } };
  EXPECT_THROW(validateMaterial(m), Error);
  m.extinction = TransferFunction{ { { 0.0, 1.0 } } };
  m.albedo = TransferFunction{ { { 0.0, 1.5 } } };
  EXPECT_THROW(validateMaterial(m), Error);
  m.albedo = TransferFunction{};
  Scene s = grid(3, 1);
  std::vector<double> scalars(27, 0.0);
  scalars[4] = std::nan("");
  EXPECT_THROW(applyMaterial(m, scalars, s), Error);
  EXPECT_THROW(applyMaterial(m, std::vector<double>(5), s), Error);
}

TEST(Material, SceneFileKeys)
{
  const SceneDescription d = parseSceneDescription(R"({"version": 1, "channels": 3,
    "material": {"scalars": "density", "preset": "ct", "albedo": [[0, 0.5], [100, 0.6]],
                 "emission": [[0, 1], [10, 0, 0, 2]], "surface_gradient": 0}})");
  EXPECT_EQ(d.material.scalars, "density");
  EXPECT_EQ(d.material.preset, "ct");
  EXPECT_TRUE(d.material.map.active());
  EXPECT_DOUBLE_EQ(d.material.map.extinction(40.0), 0.05); // from the preset
  EXPECT_DOUBLE_EQ(d.material.map.albedo(50.0), 0.55);     // replaced
  EXPECT_DOUBLE_EQ(d.material.map.emission[0](0.0), 1.0);  // grey point
  EXPECT_DOUBLE_EQ(d.material.map.emission[2](10.0), 2.0); // RGB point
  EXPECT_EQ(d.material.map.surfaceGradient, 0.0);

  EXPECT_NE(message(R"({"version": 1, "material": {"preset": "wood"}})").find("known: ct"),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"albedo": [[0, 0.5]]}})").find("extinction"),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"extinction": [[0, 1, 2]]}})")
              .find("material.extinction[0]"),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"extinction": [[0, 1]], "albedo": [[0, 2]]}})")
              .find("material.albedo"),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "material": {"density": 1}})").find("material.density"),
            std::string::npos);
}
