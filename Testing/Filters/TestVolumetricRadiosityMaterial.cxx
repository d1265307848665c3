// SPDX-License-Identifier: BSD-3-Clause
// The filter's materials: a preset or transfer functions (properties or
// scene file) give the same field as the core solve of the same mapped
// scene; arrays the input has win; bad materials are errors.
#include "vtkVolumetricRadiosity.h"

#include "IncidentRadiation.h"

#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"

#include "volrad/DenseSolver.h"
#include "volrad/Material.h"
#include "volrad/Normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

const char* kDense = R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
  "lights": [{"type": "directional", "direction": [0.2, 0.3, -1], "irradiance": 1}]})";

/// A small CT-like volume in Hounsfield units (short, the active scalars):
/// soft tissue with a bone block, air around, 2 mm voxels.
vtkSmartPointer<vtkImageData> ctVolume()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(9, 8, 7);
  image->SetSpacing(2.0, 2.0, 2.0);
  vtkNew<vtkShortArray> hu;
  hu->SetName("HU");
  hu->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    int ijk[3];
    vtkIdType id = i;
    ijk[0] = int(id % 9);
    ijk[1] = int((id / 9) % 8);
    ijk[2] = int(id / 72);
    const bool inside =
      ijk[0] > 0 && ijk[0] < 8 && ijk[1] > 0 && ijk[1] < 7 && ijk[2] > 0 && ijk[2] < 6;
    const bool bone = inside && ijk[0] >= 4 && ijk[2] >= 3;
    hu->SetValue(i, short(bone ? 1200 : (inside ? 40 : -1000)));
  }
  image->GetPointData()->SetScalars(hu);
  return image;
}

std::vector<float> incident(vtkVolumetricRadiosity* f)
{
  f->Update();
  return volrad::test::incidentRadiation(f->GetOutput());
}

} // namespace

TEST(VolumetricRadiosityMaterial, PresetEqualsTheCoreSolveOfTheMappedScene)
{
  auto image = ctVolume();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kDense);
  f->SetMaterialPreset("ct");
  const std::vector<float> g = incident(f);
  ASSERT_EQ(g.size(), std::size_t(3 * image->GetNumberOfPoints()));

  volrad::Scene s;
  s.grid.dims = { 9, 8, 7 };
  s.grid.spacing = volrad::Vec3::Constant(2.0);
  s.grid.origin = volrad::Vec3::Zero();
  s.channels = 3;
  s.allocate();
  std::vector<double> hu(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    hu[i] = image->GetPointData()->GetScalars()->GetComponent(i, 0);
  }
  s.normals = volrad::gradientNormals(s.grid, hu);
  volrad::applyMaterial(volrad::materialPreset("ct"), hu, s);
  s.directionalLights.push_back({ volrad::Vec3(0.2, 0.3, -1), volrad::uniformChannels(1.0) });
  const volrad::Solution sol = volrad::solveDense(s);
  double lit = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_NEAR(g[i], sol.G[i], 1e-5 * sol.G[i] + 1e-12) << i;
    lit = std::max(lit, double(g[i]));
  }
  EXPECT_GT(lit, 0.0);

  // The same preset from the scene file gives the same field.
  vtkNew<vtkVolumetricRadiosity> byFile;
  byFile->SetInputData(image);
  byFile->SetSceneJSON(R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
    "material": {"preset": "ct"},
    "lights": [{"type": "directional", "direction": [0.2, 0.3, -1], "irradiance": 1}]})");
  EXPECT_EQ(incident(byFile), g);
}

TEST(VolumetricRadiosityMaterial, TransferFunctionPropertiesMatchTheSceneFile)
{
  auto image = ctVolume();
  vtkNew<vtkPiecewiseFunction> extinction, albedo;
  extinction->AddPoint(-1000, 0.0);
  extinction->AddPoint(0, 0.1);
  extinction->AddPoint(1000, 0.8);
  albedo->AddPoint(-1000, 0.9);
  albedo->AddPoint(1000, 0.5);
  vtkNew<vtkColorTransferFunction> color, emission;
  color->AddRGBPoint(0, 1.0, 0.6, 0.5);
  color->AddRGBPoint(1000, 1.0, 1.0, 0.9);
  emission->AddRGBPoint(0, 0.0, 0.0, 0.0);
  emission->AddRGBPoint(1000, 0.5, 0.2, 0.1);
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kDense);
  f->SetExtinctionFunction(extinction);
  f->SetAlbedoFunction(albedo);
  f->SetColorFunction(color);
  f->SetEmissionFunction(emission);
  f->SetSurfaceGradient(200.0);
  const std::vector<float> g = incident(f);
  ASSERT_FALSE(g.empty());

  vtkNew<vtkVolumetricRadiosity> byFile;
  byFile->SetInputData(image);
  byFile->SetSceneJSON(R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
    "material": {"extinction": [[-1000, 0], [0, 0.1], [1000, 0.8]],
                 "albedo": [[-1000, 0.9], [1000, 0.5]],
                 "color": [[0, 1, 0.6, 0.5], [1000, 1, 1, 0.9]],
                 "emission": [[0, 0, 0, 0], [1000, 0.5, 0.2, 0.1]],
                 "surface_gradient": 200},
    "lights": [{"type": "directional", "direction": [0.2, 0.3, -1], "irradiance": 1}]})");
  EXPECT_EQ(incident(byFile), g);

  // Changing a function re-executes the filter (its MTime counts).
  extinction->AddPoint(1000, 2.0);
  EXPECT_NE(incident(f), g);
}

TEST(VolumetricRadiosityMaterial, RescalePropertiesMatchTheSceneFile)
{
  // Stored CT values (HU + 1024), mapped with the scene file's rescale and
  // with the filter's properties: one field; the properties win over the file.
  auto image = ctVolume();
  vtkDataArray* hu = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < hu->GetNumberOfTuples(); ++i) {
    hu->SetTuple1(i, 0.5 * (hu->GetTuple1(i) + 1024.0));
  }
  const char* rescaled = R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
    "material": {"preset": "ct", "rescale_slope": 2, "rescale_intercept": -1024},
    "lights": [{"type": "directional", "direction": [0.2, 0.3, -1], "irradiance": 1}]})";
  vtkNew<vtkVolumetricRadiosity> byFile;
  byFile->SetInputData(image);
  byFile->SetSceneJSON(rescaled);
  const std::vector<float> g = incident(byFile);
  ASSERT_FALSE(g.empty());

  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(R"({"version": 1, "channels": 3, "solver": {"method": "dense"},
    "material": {"preset": "ct", "rescale_slope": 7, "rescale_intercept": 3},
    "lights": [{"type": "directional", "direction": [0.2, 0.3, -1], "irradiance": 1}]})");
  EXPECT_NE(incident(f), g);
  f->SetRescaleSlope(2.0);
  f->SetRescaleIntercept(-1024.0);
  EXPECT_EQ(incident(f), g);
}

TEST(VolumetricRadiosityMaterial, ArraysWinOverTheMaterial)
{
  auto image = ctVolume();
  vtkNew<vtkFloatArray> kappa;
  kappa->SetName("kappa_a");
  kappa->SetNumberOfTuples(image->GetNumberOfPoints());
  kappa->Fill(0.25);
  image->GetPointData()->AddArray(kappa);
  vtkNew<vtkPiecewiseFunction> extinction;
  extinction->AddPoint(0, 0.5);
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(R"({"version": 1, "solver": {"method": "dense"},
    "boundary": {"default": {"type": "open", "radiance": 1}}})");
  f->SetExtinctionFunction(extinction); // albedo 0: kappa_a 0.5, replaced by the array's 0.25
  f->Update();
  // Absorbing only (the array's kappa_a, no scattering), lit by uniform
  // radiance: absorbed power = 0.25 G per unit volume everywhere.
  auto* g = f->GetOutput()->GetPointData()->GetArray("IncidentRadiation");
  auto* absorbed = f->GetOutput()->GetPointData()->GetArray("AbsorbedPower");
  ASSERT_NE(g, nullptr);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    EXPECT_NEAR(absorbed->GetComponent(i, 0), 0.25 * g->GetComponent(i, 0), 1e-5);
  }
}

TEST(VolumetricRadiosityMaterial, BadMaterialsAreErrors)
{
  auto image = ctVolume();
  vtkNew<vtkVolumetricRadiosity> f;
  f->SetInputData(image);
  f->SetSceneJSON(kDense);
  vtkNew<vtkPiecewiseFunction> albedo;
  albedo->AddPoint(0, 0.5);
  f->SetAlbedoFunction(albedo); // without an extinction
  EXPECT_TRUE(incident(f).empty());
  f->SetAlbedoFunction(nullptr);
  f->SetMaterialPreset("granite");
  EXPECT_TRUE(incident(f).empty());
  f->SetMaterialPreset("ct");
  image->GetPointData()->SetScalars(nullptr);
  image->Modified();
  EXPECT_TRUE(incident(f).empty()); // no scalars to map
}
