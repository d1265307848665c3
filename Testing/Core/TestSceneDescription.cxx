// SPDX-License-Identifier: BSD-3-Clause
// The scene file of docs/scene-format.md.
#include "volrad/Error.h"
#include "volrad/SceneDescription.h"

#include <gtest/gtest.h>

using namespace volrad;

namespace {

std::string errorOf(const std::string& text)
{
  try {
    parseSceneDescription(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(SceneDescription, TheDocumentedExampleParses)
{
  // docs/scene-format.md's example, word for word.
  const SceneDescription d = parseSceneDescription(R"({
    "version": 1,
    "channels": 3,
    "arrays": { "absorption": "kappa_a", "scattering": "sigma_i", "surface_scattering": "sigma_d",
                "emission": "E_I", "surface_emission": "E_D", "normals": "n" },
    "material": {
      "scalars": "ImageScalars",
      "preset": "ct-bone"
    },
    "boundary": {
      "default": { "type": "open", "radiance": 0.0 },
      "zmin":    { "type": "wall", "reflectance": 0.5, "emission": 0.0 }
    },
    "lights": [
      { "type": "directional", "direction": [0, 0, -1], "irradiance": 1.0 },
      { "type": "point", "position": [0.5, 0.5, 0.5], "intensity": [1, 0.9, 0.8] }
    ],
    "solver": { "method": "hierarchical", "epsilon": 1e-3, "max_iterations": 1000000 }
  })");
  EXPECT_EQ(d.channels, 3);
  EXPECT_EQ(d.arrays.surfaceScattering.name, "sigma_d");
  EXPECT_TRUE(d.arrays.normals.required);
  EXPECT_EQ(d.material.scalars, "ImageScalars");
  EXPECT_EQ(d.material.preset, "ct-bone");
  EXPECT_TRUE(d.material.map.active());
  EXPECT_EQ(d.boundary[static_cast<int>(Face::ZMin)].type, BoundaryCondition::Type::Wall);
  EXPECT_DOUBLE_EQ(d.boundary[static_cast<int>(Face::ZMin)].reflectance[2], 0.5);
  EXPECT_EQ(d.boundary[static_cast<int>(Face::XMax)].type, BoundaryCondition::Type::Open);
  ASSERT_EQ(d.directionalLights.size(), 1u);
  EXPECT_DOUBLE_EQ(d.directionalLights[0].irradiance[1], 1.0); // scalar -> every channel
  ASSERT_EQ(d.pointLights.size(), 1u);
  EXPECT_DOUBLE_EQ(d.pointLights[0].intensity[2], 0.8);
  EXPECT_EQ(d.solver.method, "hierarchical");
  EXPECT_EQ(d.solver.maxIterations, 1000000);
}

TEST(SceneDescription, DefaultsWhenOnlyTheVersionIsGiven)
{
  const SceneDescription d = parseSceneDescription(R"({"version": 1})");
  EXPECT_EQ(d.channels, 1);
  EXPECT_EQ(d.arrays.absorption.name, "kappa_a");
  EXPECT_FALSE(d.arrays.absorption.required);
  EXPECT_EQ(d.solver.method, "hierarchical");
  EXPECT_TRUE(d.directionalLights.empty());
}

TEST(SceneDescription, ErrorsNameTheKey)
{
  EXPECT_NE(errorOf(R"({"version": 1, "colour": 2})").find("'colour'"), std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "solver": {"epsilom": 1}})").find("'solver.epsilom'"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "solver": {"epsilon": 0}})").find("solver.epsilon"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "solver": {"epsilon": "small"}})").find("must be a number"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "solver": {"method": "fast"}})").find("solver.method"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 2})").find("version"), std::string::npos);
  EXPECT_NE(errorOf(R"({"channels": 1})").find("version"), std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "channels": 2})").find("channels"), std::string::npos);
  EXPECT_NE(
    errorOf(R"({"version": 1, "channels": 3, "lights": [{"type": "point", "position": [0,0,0],
    "intensity": [1, 2]}]})")
      .find("lights[0].intensity"),
    std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "lights": [{"type": "spot"}]})").find("lights[0].type"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "lights": [{"type": "directional", "direction": [0,0,0]}]})")
              .find("lights[0].direction"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "boundary": {"top": {}}})").find("'boundary.top'"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "boundary": {"xmin": {"type": "open", "reflectance": 0.5}}})")
              .find("boundary.xmin"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, "arrays": {"absorbtion": "k"}})").find("'arrays.absorbtion'"),
            std::string::npos);
  EXPECT_NE(
    errorOf(R"({"version": 1, "material": {"preset": "ct-marble"}})").find("material.preset"),
    std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 1, )").find("malformed JSON"), std::string::npos);
  // A number past double's range (nlohmann's out_of_range, found by the fuzzer).
  EXPECT_NE(errorOf(R"({"version": 1, "solver": {"epsilon": -10999E99999900}})")
              .find("number overflow"),
            std::string::npos);
  EXPECT_NE(errorOf(R"([1, 2])").find("must be an object"), std::string::npos);
}

TEST(SceneDescription, UnreadableFileIsNamed)
{
  try {
    readSceneDescription("/nonexistent/scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
  }
}
