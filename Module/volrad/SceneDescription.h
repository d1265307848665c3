// SPDX-License-Identifier: BSD-3-Clause
/// @file SceneDescription.h
/// @brief The scene file (JSON, version 1) of docs/scene-format.md: which
/// input arrays hold the coefficients, boundary, lights, solver settings.
///
/// Unknown keys, wrong types and out-of-range values are errors whose
/// message names the key (e.g. "solver.epsilon").
#pragma once

#include "volrad/Material.h"
#include "volrad/Scene.h"

#include <array>
#include <string>
#include <vector>

namespace volrad {

/// A point-data array of the input that holds a coefficient directly.
struct ArrayBinding
{
  std::string name;
  bool required = false; ///< named in the scene file: it must exist
};

struct ArrayNames
{
  ArrayBinding absorption{ "kappa_a" };
  ArrayBinding scattering{ "sigma_i" };
  ArrayBinding surfaceScattering{ "sigma_d" };
  ArrayBinding emission{ "E_I" };
  ArrayBinding surfaceEmission{ "E_D" };
  ArrayBinding normals{ "n" };
};

struct MaterialSettings
{
  /// The scalar field the material maps, and whose gradient gives the
  /// default normals ("" = the active scalars).
  std::string scalars;
  std::string preset; ///< the preset it started from, if any
  MaterialMap map;    ///< active() when the material gives coefficients
};

struct SolverSettings
{
  std::string method = "hierarchical"; ///< "hierarchical" or "dense"
  double epsilon = 1e-3;               ///< stopping threshold of the hierarchical solver
  long long maxIterations = 1000000;
  /// Above this estimate of its memory [bytes] a solve refuses before it
  /// allocates; 0: the solver's default (hierarchical: half the physical
  /// memory; dense: 4 GiB). Not a scene-file key: the filter's MemoryBudget,
  /// volrad's --memory-budget.
  double memoryBudgetBytes = 0.0;
  /// Whether the hierarchical solver computes the fields of empty voxels
  /// (kappa_t = 0); false: a sparse solve, empty space costs no links or
  /// views and its fields are 0. Not a scene-file key: the filter's
  /// SkipEmptySpace, volrad's --skip-empty-space.
  bool emptySpaceFields = true;
};

struct SceneDescription
{
  int version = 1;
  int channels = 1;
  ArrayNames arrays;
  MaterialSettings material;
  std::array<BoundaryCondition, kFaceCount> boundary{};
  std::vector<DirectionalLight> directionalLights;
  std::vector<PointLight> pointLights;
  SolverSettings solver;

  /// Copies channels, boundary and lights into a scene.
  void applyTo(Scene& scene) const;
};

/// Parses the JSON text; throws volrad::Error with the offending key.
SceneDescription parseSceneDescription(const std::string& jsonText);
/// Reads and parses a file; throws volrad::Error naming the file.
SceneDescription readSceneDescription(const std::string& path);

} // namespace volrad
