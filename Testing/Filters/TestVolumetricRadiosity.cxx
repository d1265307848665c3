// SPDX-License-Identifier: BSD-3-Clause
// The filter against the core, for every scalar type, extents and origins,
// and its errors.
#include "vtkVolumetricRadiosity.h"

#include "CollectErrors.h"
#include "IncidentRadiation.h"

#include "vtkCallbackCommand.h"
#include "vtkCell.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "volrad/DenseSolver.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

using volrad::test::updateCollectingErrors;

namespace {

/// An 8x7x6 image with integer-valued coefficients (exact in every type).
template<class ArrayT>
vtkSmartPointer<vtkImageData> makeImage(int extentShift = 0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetExtent(extentShift, extentShift + 7, 0, 6, -extentShift, 5 - extentShift);
  image->SetSpacing(0.5, 0.25, 0.4);
  image->SetOrigin(1.0 - extentShift * 0.5, -2.0, 3.0 + extentShift * 0.4);
  auto add = [&](const char* name, auto f) {
    vtkNew<ArrayT> a;
    a->SetName(name);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
      a->SetTuple1(i, f(i));
    }
    image->GetPointData()->AddArray(a);
  };
  add("kappa_a", [](vtkIdType i) { return double(1 + i % 3); });
  add("sigma_i", [](vtkIdType i) { return double((i * 7) % 5); });
  add("E_I", [](vtkIdType i) { return i % 11 == 0 ? 2.0 : 0.0; });
  return image;
}

/// Adds an array of `tuples` x `components` ones to point or cell data.
void addOnes(vtkDataSetAttributes* data, const char* name, vtkIdType tuples, int components = 1)
{
  vtkNew<vtkFloatArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  a->Fill(1.0);
  data->AddArray(a);
}

const char* kScene = R"({"version": 1, "solver": {"method": "dense"},
  "lights": [{"type": "directional", "direction": [0.3, -0.2, -1], "irradiance": 2}],
  "boundary": {"zmin": {"type": "wall", "reflectance": 0.5}}})";

std::vector<float> runFilter(vtkImageData* image, const char* scene, std::string* error = nullptr)
{
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(scene);
  const std::string messages = updateCollectingErrors(f);
  if (error) {
    *error = messages;
  }
  return volrad::test::incidentRadiation(f->GetOutput());
}

} // namespace

TEST(VolumetricRadiosity, OutputEqualsTheCoreSolution)
{
  auto image = makeImage<vtkDoubleArray>();
  const std::vector<float> g = runFilter(image, kScene);
  ASSERT_EQ(g.size(), std::size_t(image->GetNumberOfPoints()));

  volrad::Scene s;
  s.grid.dims = { 8, 7, 6 };
  s.grid.spacing = volrad::Vec3(0.5, 0.25, 0.4);
  s.grid.origin = volrad::Vec3(1.0, -2.0, 3.0);
  s.allocate();
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    s.kappaA[i] = float(1 + i % 3);
    s.sigmaI[i] = float((i * 7) % 5);
    s.emissionI[i] = i % 11 == 0 ? 2.0f : 0.0f;
  }
  s.directionalLights.push_back({ volrad::Vec3(0.3, -0.2, -1), volrad::uniformChannels(2.0) });
  s.boundary[4].type = volrad::BoundaryCondition::Type::Wall;
  s.boundary[4].reflectance = volrad::uniformChannels(0.5);
  const volrad::Solution sol = volrad::solveDense(s);
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_NEAR(g[i], sol.G[i], 1e-5 * sol.G[i] + 1e-12) << i;
  }
}

TEST(VolumetricRadiosity, DefaultsToTheHierarchicalSolver)
{
  // The same scene without "method": the hierarchical solver, within a few
  // percent of the dense one (its own accuracy is tested in the core).
  const char* scene = R"({"version": 1,
    "lights": [{"type": "directional", "direction": [0.3, -0.2, -1], "irradiance": 2}],
    "boundary": {"zmin": {"type": "wall", "reflectance": 0.5}}})";
  auto image = makeImage<vtkDoubleArray>();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(scene);
  f->Update();
  auto* method =
    vtkStringArray::SafeDownCast(f->GetOutput()->GetFieldData()->GetAbstractArray("SolverMethod"));
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(method->GetValue(0), "hierarchical");
  const std::vector<float> dense = runFilter(image, kScene);
  auto* g =
    vtkFloatArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("IncidentRadiation"));
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(std::size_t(g->GetNumberOfValues()), dense.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const double r = g->GetValue(vtkIdType(i)) / dense[i] - 1.0;
    sum += r * r;
  }
  const double rms = std::sqrt(sum / double(dense.size()));
  std::printf("[measured] filter default (hierarchical) vs dense, 8x7x6: G rms rel %.4f\n", rms);
  EXPECT_LT(rms, 0.03);
}

TEST(VolumetricRadiosity, EveryScalarTypeGivesTheSameField)
{
  const std::vector<float> reference = runFilter(makeImage<vtkDoubleArray>(), kScene);
  EXPECT_EQ(runFilter(makeImage<vtkFloatArray>(), kScene), reference);
  EXPECT_EQ(runFilter(makeImage<vtkIntArray>(), kScene), reference);
  EXPECT_EQ(runFilter(makeImage<vtkShortArray>(), kScene), reference);
  EXPECT_EQ(runFilter(makeImage<vtkUnsignedCharArray>(), kScene), reference);
}

TEST(VolumetricRadiosity, NonZeroExtentsGiveTheSameField)
{
  // Same world-space voxels, described with a shifted extent and origin.
  EXPECT_EQ(runFilter(makeImage<vtkDoubleArray>(3), kScene),
            runFilter(makeImage<vtkDoubleArray>(0), kScene));
}

TEST(VolumetricRadiosity, OutputArraysAndStatistics)
{
  auto image = makeImage<vtkFloatArray>();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kScene);
  f->Update();
  vtkImageData* out = f->GetOutput();
  for (const char* name : { "IncidentRadiation",
                            "IsotropicRadiosity",
                            "DiffuseRadiosity",
                            "FrontIncidentRadiation",
                            "AbsorbedPower",
                            "kappa_a" }) {
    EXPECT_NE(out->GetPointData()->GetArray(name), nullptr) << name;
  }
  for (const char* name : { "EnergyEmitted",
                            "EnergyAbsorbed",
                            "EnergyEscaped",
                            "EnergyAbsorbedWalls",
                            "Iterations",
                            "Links",
                            "SolveSeconds",
                            "FinalUnshot" }) {
    EXPECT_NE(out->GetFieldData()->GetArray(name), nullptr) << name;
  }
  const double emitted = out->GetFieldData()->GetArray("EnergyEmitted")->GetComponent(0, 0);
  const double removed = out->GetFieldData()->GetArray("EnergyAbsorbed")->GetComponent(0, 0) +
                         out->GetFieldData()->GetArray("EnergyAbsorbedWalls")->GetComponent(0, 0) +
                         out->GetFieldData()->GetArray("EnergyEscaped")->GetComponent(0, 0);
  EXPECT_NEAR(removed / emitted, 1.0, 1e-6);
}

TEST(VolumetricRadiosity, ANamedArrayThatIsMissingIsZeroWithAWarning)
{
  // scene-format.md: a missing array means zero. The filter says which.
  auto image = makeImage<vtkFloatArray>();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(
    R"({"version": 1, "arrays": {"absorption": "kappa_a", "surface_emission": "glow"}})");
  volrad::test::MessageCollector warnings;
  warnings.observe(f, vtkCommand::WarningEvent);
  f->Update();
  EXPECT_NE(warnings.text.find("'glow'"), std::string::npos) << warnings.text;
  EXPECT_EQ(
    runFilter(image, R"({"version": 1})"),
    std::vector<float>(
      vtkFloatArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("IncidentRadiation"))
        ->GetPointer(0),
      vtkFloatArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("IncidentRadiation"))
          ->GetPointer(0) +
        image->GetNumberOfPoints()));
}

TEST(VolumetricRadiosity, BadInputGivesAClearErrorAndNoField)
{
  std::string error;

  EXPECT_TRUE(
    runFilter(makeImage<vtkFloatArray>(), R"({"version": 1, "bogus": 1})", &error).empty());
  EXPECT_NE(error.find("'bogus'"), std::string::npos) << error;

  auto nan = makeImage<vtkFloatArray>();
  nan->GetPointData()->GetArray("kappa_a")->SetTuple1(5, std::nan(""));
  EXPECT_TRUE(runFilter(nan, kScene, &error).empty());
  EXPECT_NE(error.find("kappa_a = nan"), std::string::npos) << error;

  auto negative = makeImage<vtkFloatArray>();
  negative->GetPointData()->GetArray("sigma_i")->SetTuple1(7, -2.0);
  EXPECT_TRUE(runFilter(negative, kScene, &error).empty());
  EXPECT_NE(error.find("sigma_i = -2"), std::string::npos) << error;

  auto rgb = makeImage<vtkFloatArray>();
  addOnes(rgb->GetPointData(), "kappa_a", rgb->GetNumberOfPoints(), 2);
  EXPECT_TRUE(runFilter(rgb, R"({"version": 1, "channels": 3})", &error).empty());
  EXPECT_NE(error.find("2 components"), std::string::npos) << error;

  vtkNew<vtkImageData> empty;
  EXPECT_TRUE(runFilter(empty, kScene, &error).empty());
  EXPECT_FALSE(error.empty());
}

TEST(VolumetricRadiosity, OneVoxelAndFlatImagesAreRefused)
{
  for (const auto& dims : { std::array<int, 3>{ 1, 1, 1 },
                            std::array<int, 3>{ 5, 3, 1 },
                            std::array<int, 3>{ 1, 4, 4 } }) {
    vtkNew<vtkImageData> image;
    image->SetDimensions(dims.data());
    addOnes(image->GetPointData(), "kappa_a", image->GetNumberOfPoints());
    std::string error;
    EXPECT_TRUE(runFilter(image, R"({"version": 1})", &error).empty());
    EXPECT_NE(error.find("needs a 3-D volume"), std::string::npos) << error;
  }
}

TEST(VolumetricRadiosity, SmallestVolumeIsAWhiteFurnace)
{
  // 2 x 2 x 2 voxels emitting E in a sky of radiance E/pi: G = 4E.
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 2);
  for (const char* name : { "kappa_a", "E_I" }) {
    addOnes(image->GetPointData(), name, image->GetNumberOfPoints());
  }
  const auto g = runFilter(
    image,
    R"({"version": 1, "boundary": {"default": {"type": "open", "radiance": 0.3183098861837907}}})");
  ASSERT_EQ(g.size(), 8u);
  for (float x : g) {
    EXPECT_NEAR(x, 4.0, 1e-4);
  }
}

TEST(VolumetricRadiosity, CellDataCoefficientsAreNamedInTheError)
{
  auto image = makeImage<vtkFloatArray>();
  image->GetPointData()->RemoveArray("kappa_a");
  addOnes(image->GetCellData(), "kappa_a", image->GetNumberOfCells());
  std::string error;
  EXPECT_TRUE(runFilter(image, kScene, &error).empty());
  EXPECT_NE(error.find("'kappa_a' is a cell-data array"), std::string::npos) << error;
}

TEST(VolumetricRadiosity, WallPatchesOnTheSecondPortAndRenderColours)
{
  auto image = makeImage<vtkFloatArray>(); // 8x7x6, spacing 0.5 0.25 0.4
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kScene); // a zmin wall of reflectance 0.5
  f->Update();
  vtkPolyData* walls = f->GetWallOutput();
  ASSERT_NE(walls, nullptr);
  ASSERT_EQ(walls->GetNumberOfCells(), 8 * 7);
  auto* B = walls->GetCellData()->GetArray("Radiosity");
  auto* H = walls->GetCellData()->GetArray("Irradiance");
  ASSERT_NE(B, nullptr);
  ASSERT_NE(H, nullptr);
  // Every quad lies on the zmin face (z = 3.0 - 0.2) and is 0.5 x 0.25;
  // absorbed by the wall: (1 - rho) H A, summed = EnergyAbsorbedWalls.
  double absorbed = 0.0;
  for (vtkIdType c = 0; c < walls->GetNumberOfCells(); ++c) {
    double bounds[6];
    walls->GetCell(c)->GetBounds(bounds);
    EXPECT_NEAR(bounds[4], 2.8, 1e-6);
    EXPECT_NEAR(bounds[5], 2.8, 1e-6);
    EXPECT_NEAR((bounds[1] - bounds[0]) * (bounds[3] - bounds[2]), 0.125, 1e-6);
    EXPECT_NEAR(B->GetComponent(c, 0), 0.5 * H->GetComponent(c, 0), 1e-5 * H->GetComponent(c, 0));
    absorbed += 0.5 * H->GetComponent(c, 0) * 0.125;
  }
  const double expected =
    f->GetOutput()->GetFieldData()->GetArray("EnergyAbsorbedWalls")->GetComponent(0, 0);
  EXPECT_NEAR(absorbed, expected, 1e-5 * expected);
  EXPECT_GT(absorbed, 0.0);

  auto* rgba =
    vtkUnsignedCharArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("RenderRGBA"));
  ASSERT_NE(rgba, nullptr);
  EXPECT_EQ(rgba->GetNumberOfComponents(), 4);
  EXPECT_EQ(rgba->GetNumberOfTuples(), image->GetNumberOfPoints());

  // No walls: an empty second output.
  f->SetSceneJSON(R"({"version": 1, "solver": {"method": "dense"}})");
  f->Update();
  EXPECT_EQ(f->GetWallOutput()->GetNumberOfCells(), 0);
}

TEST(VolumetricRadiosity, LightPropertiesAndARenderersLights)
{
  auto image = makeImage<vtkFloatArray>();
  const char* dark = R"({"version": 1, "channels": 3, "solver": {"method": "dense"}})";
  const char* lit = R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
    "lights": [{"type": "directional", "direction": [0, 0, -10], "irradiance": [2, 1, 0.5]},
               {"type": "point", "position": [2.5, -1.2, 4.0], "intensity": [0.3, 0.2, 0.1]}]})";
  const std::vector<float> reference = runFilter(image, lit);
  ASSERT_FALSE(reference.empty());

  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(dark);
  f->AddDirectionalLight(0, 0, -10, 2, 1, 0.5);
  f->AddPointLight(2.5, -1.2, 4.0, 0.3, 0.2, 0.1);
  EXPECT_EQ(f->GetNumberOfLights(), 2);
  f->Update();
  EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()), reference);

  // The same from a renderer: a scene light shining down, a positional one.
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkLight> sun, lamp;
  sun->SetLightTypeToSceneLight();
  sun->SetPosition(1, 2, 13);
  sun->SetFocalPoint(1, 2, 3);
  sun->SetIntensity(2.0);
  sun->SetDiffuseColor(1.0, 0.5, 0.25);
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetPosition(2.5, -1.2, 4.0);
  lamp->SetIntensity(0.3);
  lamp->SetDiffuseColor(1.0, 2.0 / 3.0, 1.0 / 3.0);
  vtkNew<vtkLight> off;
  off->SwitchOff();
  renderer->AddLight(sun);
  renderer->AddLight(lamp);
  renderer->AddLight(off);
  f->RemoveAllLights();
  f->AddLightsFromRenderer(renderer);
  EXPECT_EQ(f->GetNumberOfLights(), 2);
  f->Update();
  const std::vector<float> fromRenderer = volrad::test::incidentRadiation(f->GetOutput());
  ASSERT_EQ(fromRenderer.size(), reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    EXPECT_NEAR(fromRenderer[i], reference[i], 1e-5 * reference[i] + 1e-9) << i;
  }
}

TEST(VolumetricRadiosity, AbortStopsTheSolveAndTheNextRunSucceeds)
{
  auto image = makeImage<vtkFloatArray>();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(
    R"({"version": 1, "lights": [{"type": "directional", "direction": [0, 0, -1]}]})");
  struct Progress
  {
    vtkVolumetricRadiosity* filter;
    double abortAt = 0.3, requested = -1.0, last = 0.0;
    int eventsAfter = 0;
  } p{ f };
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&p);
  cb->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
    auto* s = static_cast<Progress*>(self);
    s->last = *static_cast<double*>(data);
    if (s->requested >= 0.0) {
      ++s->eventsAfter;
    } else if (s->last >= s->abortAt) {
      s->requested = s->last;
      s->filter->AbortExecuteOn();
    }
  });
  f->AddObserver(vtkCommand::ProgressEvent, cb);
  f->Update();
  // Stopped at the first progress check after the request: no field.
  ASSERT_GE(p.requested, 0.0);
  EXPECT_LT(p.last, 0.5);
  EXPECT_LE(p.eventsAfter, 1);
  EXPECT_TRUE(volrad::test::incidentRadiation(f->GetOutput()).empty());

  // The same filter then solves normally.
  p.abortAt = 2.0;
  p.requested = -1.0;
  f->AbortExecuteOff();
  f->Modified();
  f->Update();
  EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()).size(),
            std::size_t(image->GetNumberOfPoints()));
}

TEST(VolumetricRadiosity, SceneSettingsAsPropertiesMatchTheSceneFile)
{
  auto image = makeImage<vtkFloatArray>();
  const std::vector<float> reference = runFilter(image, R"({"version": 1, "channels": 3,
    "solver": {"method": "dense"},
    "boundary": {"zmin": {"type": "wall", "reflectance": [0.5, 0.4, 0.3], "emission": [0, 0, 1]},
                 "zmax": {"type": "open", "radiance": [0.1, 0.2, 0.3]}},
    "lights": [{"type": "directional", "direction": [0.3, -0.2, -1], "irradiance": 2}]})");
  ASSERT_FALSE(reference.empty());
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetChannels(3);
  f->SetSolverMethod("dense");
  f->SetWallFace(4, 0.5, 0.4, 0.3, 0, 0, 1);
  f->SetOpenFace(5, 0.1, 0.2, 0.3);
  f->AddDirectionalLight(0.3, -0.2, -1, 2, 2, 2);
  f->Update();
  EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()), reference);
  auto* method =
    vtkStringArray::SafeDownCast(f->GetOutput()->GetFieldData()->GetAbstractArray("SolverMethod"));
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(method->GetValue(0), "dense");

  // Removing one kind of face or light leaves the other kind (ParaView clears
  // its lists one property at a time, then sets them again).
  f->RemoveAllOpenFaces();
  f->RemoveAllPointLights();
  f->SetOpenFace(5, 0.1, 0.2, 0.3);
  EXPECT_EQ(f->GetNumberOfLights(), 1);
  f->Update();
  EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()), reference);
  f->RemoveAllWallFaces();
  f->RemoveAllDirectionalLights();
  EXPECT_EQ(f->GetNumberOfLights(), 0);
  f->SetWallFace(4, 0.5, 0.4, 0.3, 0, 0, 1);
  f->AddDirectionalLight(0.3, -0.2, -1, 2, 2, 2);
  f->Update();
  EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()), reference);

  // Back to the scene's faces: a different field.
  f->RemoveAllFaceSettings();
  f->Update();
  EXPECT_NE(volrad::test::incidentRadiation(f->GetOutput()), reference);
}

TEST(VolumetricRadiosity, OneThreadIsBitIdenticalAndManyThreadsAgreeWithIt)
{
  // Both solvers; the hierarchical one on a heterogeneous 8x7x6 medium with
  // a wall, so that link refinement, far field and shooting all run.
  auto image = makeImage<vtkFloatArray>();
  for (const char* method : { "hierarchical", "dense" }) {
    auto run = [&](int threads) {
      vtkNew<vtkVolumetricRadiosity> f;
      f->SetInputData(image);
      f->SetSceneJSON(kScene);
      f->SetSolverMethod(method);
      f->SetNumberOfThreads(threads);
      f->Update();
      std::vector<std::vector<float>> fields;
      for (const char* name :
           { "IncidentRadiation", "IsotropicRadiosity", "DiffuseRadiosity", "AbsorbedPower" }) {
        auto* a = vtkFloatArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray(name));
        EXPECT_NE(a, nullptr) << name;
        fields.emplace_back(
          a ? std::vector<float>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues())
            : std::vector<float>());
      }
      return fields;
    };
    const auto one = run(1);
    ASSERT_FALSE(one[0].empty()) << method;
    EXPECT_EQ(run(1), one) << method << ": two single-threaded runs differ";
    // More threads than cores: the work is cut differently.
    for (int threads : { 0, 4 }) {
      const auto many = run(threads);
      ASSERT_EQ(many.size(), one.size());
      for (std::size_t k = 0; k < one.size(); ++k) {
        ASSERT_EQ(many[k].size(), one[k].size());
        for (std::size_t i = 0; i < one[k].size(); ++i) {
          EXPECT_NEAR(many[k][i], one[k][i], 1e-6 * std::abs(one[k][i]) + 1e-30)
            << method << ", " << threads << " threads, field " << k << ", value " << i;
        }
      }
    }
  }
}

TEST(VolumetricRadiosity, MemoryBudgetRefusesBeforeSolvingWithBothFigures)
{
  auto image = makeImage<vtkFloatArray>();
  for (const char* method : { "hierarchical", "dense" }) {
    vtkNew<vtkVolumetricRadiosity> f;
    f->SetInputData(image);
    f->SetSceneJSON(kScene);
    f->SetSolverMethod(method);
    f->SetMemoryBudget(0.01); // MiB: less than the voxels alone need
    const std::string messages = updateCollectingErrors(f);
    EXPECT_TRUE(volrad::test::incidentRadiation(f->GetOutput()).empty()) << method;
    EXPECT_NE(messages.find("over its memory budget of 0.01 MiB"), std::string::npos)
      << method << ": " << messages;
    EXPECT_NE(messages.find(" MiB"), messages.rfind(" MiB")) << "both figures: " << messages;
    // The default budget (0) solves it.
    f->SetMemoryBudget(0.0);
    f->Update();
    EXPECT_EQ(volrad::test::incidentRadiation(f->GetOutput()).size(),
              std::size_t(image->GetNumberOfPoints()))
      << method;
  }
}

// SkipEmptySpace is the hierarchical solver's: with the dense solver the
// filter says that it computes every voxel anyway, and does.
TEST(VolumetricRadiosity, SkipEmptySpaceWithTheDenseSolverIsAWarning)
{
  auto image = makeImage<vtkFloatArray>();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kScene);
  f->SkipEmptySpaceOn();
  volrad::test::MessageCollector warnings;
  warnings.observe(f, vtkCommand::WarningEvent);
  f->Update();
  EXPECT_NE(warnings.text.find("dense solver computes the fields of every voxel"),
            std::string::npos)
    << warnings.text;
  auto* G =
    vtkFloatArray::SafeDownCast(f->GetOutput()->GetPointData()->GetArray("IncidentRadiation"));
  ASSERT_NE(G, nullptr);
  EXPECT_EQ(runFilter(image, kScene),
            std::vector<float>(G->GetPointer(0), G->GetPointer(0) + image->GetNumberOfPoints()));
}
