// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumetricRadiosity.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "volrad/DirectLight.h"
#include "volrad/Error.h"
#include "volrad/Normals.h"
#include "volrad/RenderColors.h"
#include "volrad/SceneDescription.h"
#include "volrad/Solve.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkVolumetricRadiosity);

namespace {

using volrad::Index;

/// Copies a coefficient array (1 or `channels` components, any numeric
/// type) into the scene's layout. A missing array means zero
/// (scene-format.md); when the scene file named it, `missing` gets its name.
void readCoefficient(vtkImageData* input,
                     const volrad::ArrayBinding& binding,
                     int channels,
                     std::vector<float>& out,
                     std::string& missing)
{
  vtkDataArray* a = input->GetPointData()->GetArray(binding.name.c_str());
  if (!a) {
    if (input->GetPointData()->GetAbstractArray(binding.name.c_str())) {
      throw volrad::Error("point-data array '" + binding.name + "' is not numeric");
    }
    if (input->GetCellData()->GetAbstractArray(binding.name.c_str())) {
      throw volrad::Error("'" + binding.name +
                          "' is a cell-data array: VolRad reads point data (one value per voxel "
                          "centre); convert it with vtkCellDataToPointData");
    }
    if (binding.required) {
      missing += (missing.empty() ? "'" : ", '") + binding.name + "'";
    }
    return;
  }
  const int nc = a->GetNumberOfComponents();
  if (nc != 1 && nc != channels) {
    throw volrad::Error("point-data array '" + binding.name + "' has " + std::to_string(nc) +
                        " components; expected 1 or " + std::to_string(channels) + " (channels)");
  }
  const Index n = input->GetNumberOfPoints();
  for (Index v = 0; v < n; ++v) {
    for (int c = 0; c < channels; ++c) {
      out[std::size_t(v) * channels + c] = static_cast<float>(a->GetComponent(v, nc == 1 ? 0 : c));
    }
  }
}

/// The field the material maps and whose gradient gives the default normals:
/// material.scalars, else the active scalars (empty when there are none).
std::vector<double> materialScalars(vtkImageData* input, const volrad::SceneDescription& d)
{
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* s =
    d.material.scalars.empty() ? pd->GetScalars() : pd->GetArray(d.material.scalars.c_str());
  if (!s) {
    if (!d.material.scalars.empty()) {
      throw volrad::Error("the input has no numeric point-data array '" + d.material.scalars +
                          "' (material.scalars)");
    }
    if (d.material.map.active()) {
      throw volrad::Error("the material maps scalars, and the input has no active point scalars: "
                          "name the array in material.scalars");
    }
    return {};
  }
  std::vector<double> values(input->GetNumberOfPoints());
  for (Index v = 0; v < input->GetNumberOfPoints(); ++v) {
    values[v] = s->GetComponent(v, 0);
  }
  return values;
}

void readNormals(vtkImageData* input, const volrad::SceneDescription& d, volrad::Scene& scene)
{
  vtkPointData* pd = input->GetPointData();
  if (vtkDataArray* a = pd->GetArray(d.arrays.normals.name.c_str())) {
    if (a->GetNumberOfComponents() != 3) {
      throw volrad::Error("normals array '" + d.arrays.normals.name + "' must have 3 components");
    }
    scene.normals.resize(input->GetNumberOfPoints());
    for (Index v = 0; v < input->GetNumberOfPoints(); ++v) {
      double n[3];
      a->GetTuple(v, n);
      scene.normals[v] = { float(n[0]), float(n[1]), float(n[2]) };
    }
    return;
  }
  if (d.arrays.normals.required) {
    throw volrad::Error("the input has no point-data array '" + d.arrays.normals.name + "'");
  }
  // Default: the normalised negative gradient of the material scalars.
  const std::vector<double> values = materialScalars(input, d);
  if (!values.empty()) {
    scene.normals = volrad::gradientNormals(scene.grid, values);
  }
}

/// Nodes of a vtkPiecewiseFunction (linear between them: midpoints and
/// sharpness are not used).
volrad::TransferFunction toTransferFunction(vtkPiecewiseFunction* f)
{
  volrad::TransferFunction out;
  for (int i = 0; i < f->GetSize(); ++i) {
    double node[4];
    f->GetNodeValue(i, node);
    out.points.emplace_back(node[0], node[1]);
  }
  return out;
}

void toTransferFunctions(vtkColorTransferFunction* f, volrad::TransferFunction* rgb)
{
  for (int c = 0; c < 3; ++c) {
    rgb[c].points.clear();
  }
  for (int i = 0; i < f->GetSize(); ++i) {
    double node[6];
    f->GetNodeValue(i, node);
    for (int c = 0; c < 3; ++c) {
      rgb[c].points.emplace_back(node[0], node[1 + c]);
    }
  }
}

volrad::Scene makeScene(vtkImageData* input,
                        const volrad::SceneDescription& d,
                        std::string& missing)
{
  volrad::Scene scene;
  int dims[3];
  input->GetDimensions(dims);
  if (input->GetNumberOfPoints() < 1 || dims[0] < 1 || dims[1] < 1 || dims[2] < 1) {
    throw volrad::Error("the input image is empty");
  }
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2) {
    throw volrad::Error("the input image is " + std::to_string(dims[0]) + " x " +
                        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                        " points: volumetric radiosity needs a 3-D volume, at least 2 points "
                        "along every axis");
  }
  double spacing[3], origin[3];
  input->GetSpacing(spacing);
  input->GetOrigin(origin);
  vtkMatrix3x3* dir = input->GetDirectionMatrix();
  if (dir && !dir->IsIdentity()) {
    throw volrad::Error("images with a non-identity direction matrix are not supported yet");
  }
  int extent[6];
  input->GetExtent(extent);
  for (int a = 0; a < 3; ++a) {
    scene.grid.dims[a] = dims[a];
    scene.grid.spacing[a] = spacing[a];
    // Centre of voxel (0,0,0): the first point of the extent.
    scene.grid.origin[a] = origin[a] + extent[2 * a] * spacing[a];
  }
  d.applyTo(scene);
  scene.allocate();
  readNormals(input, d, scene);
  // The material first: arrays the input has win, coefficient by coefficient.
  if (d.material.map.active()) {
    volrad::applyMaterial(d.material.map, materialScalars(input, d), scene);
  }
  readCoefficient(input, d.arrays.absorption, d.channels, scene.kappaA, missing);
  readCoefficient(input, d.arrays.scattering, d.channels, scene.sigmaI, missing);
  readCoefficient(input, d.arrays.surfaceScattering, d.channels, scene.sigmaD, missing);
  readCoefficient(input, d.arrays.emission, d.channels, scene.emissionI, missing);
  readCoefficient(input, d.arrays.surfaceEmission, d.channels, scene.emissionD, missing);
  return scene;
}

void addPointArray(vtkImageData* out,
                   const char* name,
                   const std::vector<double>& values,
                   int channels)
{
  vtkNew<vtkFloatArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(channels);
  a->SetNumberOfTuples(vtkIdType(values.size() / channels));
  for (std::size_t i = 0; i < values.size(); ++i) {
    // Beyond float's range the stored field would be silently infinite.
    if (!(std::abs(values[i]) <= std::numeric_limits<float>::max())) {
      std::ostringstream message;
      message << name << " = " << values[i] << " at voxel " << i / channels
              << " does not fit the output's float32: scale the emission, lights and "
                 "environment down (the field scales with them)";
      throw volrad::Error(message.str());
    }
    a->SetValue(vtkIdType(i), static_cast<float>(values[i]));
  }
  out->GetPointData()->AddArray(a);
}

void addField(vtkFieldData* fd, const char* name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(int(values.size()));
  a->SetNumberOfTuples(1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    a->SetComponent(0, int(i), values[i]);
  }
  fd->AddArray(a);
}

template<class F>
std::vector<double> perChannel(const volrad::Solution& s, F f)
{
  std::vector<double> v;
  for (const auto& e : s.energy) {
    v.push_back(f(e));
  }
  return v;
}

void addStatistics(vtkFieldData* fd, const volrad::Solution& s)
{
  using E = volrad::EnergyTerms;
  addField(fd, "EnergyEmitted", perChannel(s, [](const E& e) { return e.emitted(); }));
  addField(fd, "EnergyEmittedVoxels", perChannel(s, [](const E& e) { return e.emittedVoxels; }));
  addField(fd, "EnergyEmittedWalls", perChannel(s, [](const E& e) { return e.emittedWalls; }));
  addField(fd, "EnergyEnteringLights", perChannel(s, [](const E& e) { return e.enteringLights; }));
  addField(fd, "EnergyEnteringEnvironment", perChannel(s, [](const E& e) {
             return e.enteringEnvironment;
           }));
  addField(fd, "EnergyAbsorbed", perChannel(s, [](const E& e) { return e.absorbedVoxels; }));
  addField(fd, "EnergyAbsorbedWalls", perChannel(s, [](const E& e) { return e.absorbedWalls; }));
  addField(fd, "EnergyEscaped", perChannel(s, [](const E& e) { return e.escaped; }));
  addField(
    fd, "EnergyBalanceResidual", perChannel(s, [](const E& e) { return e.relativeResidual(); }));
  addField(fd, "Iterations", { double(s.stats.iterations) });
  addField(fd, "Links", { double(s.stats.links) });
  addField(fd, "SolveSeconds", { s.stats.seconds });
  addField(fd, "FinalUnshot", { s.stats.finalUnshot });
  addField(fd, "QuadratureError", { s.stats.quadratureError });
  addField(fd, "MemoryEstimateBytes", { double(s.stats.estimatedBytes) });
  vtkNew<vtkStringArray> method;
  method->SetName("SolverMethod");
  method->InsertNextValue(s.stats.method);
  fd->AddArray(method);
}

/// One quad per wall patch, with B and H as cell data.
vtkSmartPointer<vtkPolyData> makeWalls(const volrad::Scene& scene, const volrad::Solution& sol)
{
  const volrad::Grid& g = scene.grid;
  const int C = sol.channels;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkFloatArray> radiosity, irradiance;
  radiosity->SetName("Radiosity");
  irradiance->SetName("Irradiance");
  radiosity->SetNumberOfComponents(C);
  irradiance->SetNumberOfComponents(C);
  for (Index p = 0; p < g.patchCount(); ++p) {
    const volrad::Face f = g.patchLocation(p).face;
    if (scene.boundary[static_cast<int>(f)].type != volrad::BoundaryCondition::Type::Wall) {
      continue;
    }
    const auto ax = volrad::faceAxesInPlane(f);
    const volrad::Vec3 lo = g.patchLower(p);
    vtkIdType ids[4];
    for (int k = 0; k < 4; ++k) {
      volrad::Vec3 x = lo;
      x[ax[0]] += ((k == 1 || k == 2) ? 1.0 : 0.0) * g.spacing[ax[0]];
      x[ax[1]] += (k >= 2 ? 1.0 : 0.0) * g.spacing[ax[1]];
      ids[k] = points->InsertNextPoint(x[0], x[1], x[2]);
    }
    quads->InsertNextCell(4, ids);
    for (int c = 0; c < C; ++c) {
      radiosity->InsertNextValue(float(sol.B[std::size_t(p) * C + c]));
      irradiance->InsertNextValue(float(sol.H[std::size_t(p) * C + c]));
    }
  }
  auto walls = vtkSmartPointer<vtkPolyData>::New();
  walls->SetPoints(points);
  walls->SetPolys(quads);
  walls->GetCellData()->AddArray(radiosity);
  walls->GetCellData()->AddArray(irradiance);
  return walls;
}

/// (r, g, b) for a scene of C channels: grey scenes take their mean.
volrad::ChannelValues channelValues(int C, double r, double g, double b)
{
  return C == 1 ? volrad::uniformChannels((r + g + b) / 3.0) : volrad::ChannelValues{ r, g, b };
}

/// The filter's material properties over the scene description's.
void applyMaterialProperties(vtkVolumetricRadiosity* self, volrad::SceneDescription& d)
{
  volrad::MaterialMap& m = d.material.map;
  const char* preset = self->GetMaterialPreset();
  if (preset && *preset && std::string(preset) != "none") {
    d.material.preset = self->GetMaterialPreset();
    // The preset replaces the scene's curves, not how its scalars are stored.
    const double slope = m.rescaleSlope, intercept = m.rescaleIntercept;
    m = volrad::materialPreset(self->GetMaterialPreset());
    m.rescaleSlope = slope;
    m.rescaleIntercept = intercept;
  }
  if (self->GetExtinctionFunction()) {
    m.extinction = toTransferFunction(self->GetExtinctionFunction());
  }
  if (self->GetAlbedoFunction()) {
    m.albedo = toTransferFunction(self->GetAlbedoFunction());
  }
  if (self->GetColorFunction()) {
    toTransferFunctions(self->GetColorFunction(), m.color.data());
  }
  if (self->GetEmissionFunction()) {
    toTransferFunctions(self->GetEmissionFunction(), m.emission.data());
  }
  if (self->GetSurfaceGradient() >= 0.0) {
    m.surfaceGradient = self->GetSurfaceGradient();
  }
  if (!std::isnan(self->GetRescaleSlope())) {
    m.rescaleSlope = self->GetRescaleSlope();
  }
  if (!std::isnan(self->GetRescaleIntercept())) {
    m.rescaleIntercept = self->GetRescaleIntercept();
  }
  if (!m.active() &&
      (self->GetAlbedoFunction() || self->GetColorFunction() || self->GetEmissionFunction())) {
    throw volrad::Error("the material needs an ExtinctionFunction (or a MaterialPreset) for its "
                        "other functions to apply");
  }
  volrad::validateMaterial(m, "the filter's material");
}

} // namespace

vtkVolumetricRadiosity::vtkVolumetricRadiosity()
  : RescaleSlope(std::numeric_limits<double>::quiet_NaN())
  , RescaleIntercept(std::numeric_limits<double>::quiet_NaN())
{
  this->SetNumberOfOutputPorts(2);
}

vtkPolyData* vtkVolumetricRadiosity::GetWallOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkVolumetricRadiosity::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1) {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

int vtkVolumetricRadiosity::RequestInformation(vtkInformation* request,
                                               vtkInformationVector** inputVector,
                                               vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector)) {
    return 0;
  }
  // The image algorithm copies the input's extent to every output: the wall
  // polydata has none.
  vtkInformation* walls = outputVector->GetInformationObject(1);
  walls->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  walls->Remove(vtkDataObject::SPACING());
  walls->Remove(vtkDataObject::ORIGIN());
  return 1;
}

vtkVolumetricRadiosity::~vtkVolumetricRadiosity()
{
  this->SetMaterialPreset(nullptr);
  this->SetSolverMethod(nullptr);
  this->SetMaterialScalars(nullptr);
  this->SetSceneFileName(nullptr);
  this->SetSceneJSON(nullptr);
}

#define volradTransferFunctionProperty(Name, Type)                                                 \
  void vtkVolumetricRadiosity::Set##Name(Type* f)                                                  \
  {                                                                                                \
    if (this->Name != f) {                                                                         \
      this->Name = f;                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  Type* vtkVolumetricRadiosity::Get##Name()                                                        \
  {                                                                                                \
    return this->Name;                                                                             \
  }
volradTransferFunctionProperty(ExtinctionFunction, vtkPiecewiseFunction);
volradTransferFunctionProperty(AlbedoFunction, vtkPiecewiseFunction);
volradTransferFunctionProperty(ColorFunction, vtkColorTransferFunction);
volradTransferFunctionProperty(EmissionFunction, vtkColorTransferFunction);
#undef volradTransferFunctionProperty

void vtkVolumetricRadiosity::SetOpenFace(int face, double r, double g, double b)
{
  if (face < 0 || face > 5) {
    vtkErrorMacro("SetOpenFace: the face is not 0-5 (xmin, xmax, ymin, ymax, zmin, zmax)");
    return;
  }
  this->Faces[face] = { 1.0, r, g, b, 0.0, 0.0, 0.0 };
  this->Modified();
}

void vtkVolumetricRadiosity::SetWallFace(int face,
                                         double r,
                                         double g,
                                         double b,
                                         double er,
                                         double eg,
                                         double eb)
{
  if (face < 0 || face > 5) {
    vtkErrorMacro("SetWallFace: the face is not 0-5 (xmin, xmax, ymin, ymax, zmin, zmax)");
    return;
  }
  this->Faces[face] = { 2.0, r, g, b, er, eg, eb };
  this->Modified();
}

namespace {
/// A face number given as a double: itself when it is a whole 0-5, else 6
/// (which the int setters refuse, naming it).
int faceNumber(double face)
{
  return face >= 0.0 && face <= 5.0 && face == std::floor(face) ? static_cast<int>(face) : 6;
}
} // namespace

void vtkVolumetricRadiosity::SetOpenFace(double face, double r, double g, double b)
{
  this->SetOpenFace(faceNumber(face), r, g, b);
}

void vtkVolumetricRadiosity::SetWallFace(double face,
                                         double r,
                                         double g,
                                         double b,
                                         double er,
                                         double eg,
                                         double eb)
{
  this->SetWallFace(faceNumber(face), r, g, b, er, eg, eb);
}

void vtkVolumetricRadiosity::SetEnvironmentRadiance(double r, double g, double b)
{
  for (int f = 0; f < 6; ++f) {
    this->Faces[f] = { 1.0, r, g, b, 0.0, 0.0, 0.0 };
  }
  this->Modified();
}

void vtkVolumetricRadiosity::RemoveAllFaceSettings()
{
  this->Faces = {};
  this->Modified();
}

namespace {
/// Clears the faces set as `type` (1 open, 2 wall); true when one was.
bool clearFaces(std::array<std::array<double, 7>, 6>& faces, double type)
{
  bool changed = false;
  for (auto& face : faces) {
    if (face[0] == type) {
      face = {};
      changed = true;
    }
  }
  return changed;
}

/// Removes the lights of `type` (0 directional, 1 point); true when one was.
bool removeLights(std::vector<std::array<double, 7>>& lights, double type)
{
  const auto end =
    std::remove_if(lights.begin(), lights.end(), [type](const auto& l) { return l[0] == type; });
  const bool changed = end != lights.end();
  lights.erase(end, lights.end());
  return changed;
}
} // namespace

void vtkVolumetricRadiosity::RemoveAllOpenFaces()
{
  if (clearFaces(this->Faces, 1.0)) {
    this->Modified();
  }
}

void vtkVolumetricRadiosity::RemoveAllWallFaces()
{
  if (clearFaces(this->Faces, 2.0)) {
    this->Modified();
  }
}

void vtkVolumetricRadiosity::RemoveAllDirectionalLights()
{
  if (removeLights(this->Lights, 0.0)) {
    this->Modified();
  }
}

void vtkVolumetricRadiosity::RemoveAllPointLights()
{
  if (removeLights(this->Lights, 1.0)) {
    this->Modified();
  }
}

void vtkVolumetricRadiosity::AddDirectionalLight(double dx,
                                                 double dy,
                                                 double dz,
                                                 double r,
                                                 double g,
                                                 double b)
{
  this->Lights.push_back({ 0.0, dx, dy, dz, r, g, b });
  this->Modified();
}

void vtkVolumetricRadiosity::AddPointLight(double x,
                                           double y,
                                           double z,
                                           double r,
                                           double g,
                                           double b)
{
  this->Lights.push_back({ 1.0, x, y, z, r, g, b });
  this->Modified();
}

void vtkVolumetricRadiosity::RemoveAllLights()
{
  if (!this->Lights.empty()) {
    this->Lights.clear();
    this->Modified();
  }
}

int vtkVolumetricRadiosity::GetNumberOfLights()
{
  return static_cast<int>(this->Lights.size());
}

void vtkVolumetricRadiosity::AddLightsFromRenderer(vtkRenderer* renderer, double scale)
{
  if (!renderer) {
    return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it)) {
    if (!light->GetSwitch()) {
      continue;
    }
    double c[3];
    light->GetDiffuseColor(c);
    const double k = scale * light->GetIntensity();
    double position[3], focal[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    if (light->LightTypeIsHeadlight() && camera) {
      camera->GetPosition(position);
      camera->GetFocalPoint(focal);
    }
    if (light->GetPositional()) {
      this->AddPointLight(position[0], position[1], position[2], k * c[0], k * c[1], k * c[2]);
    } else {
      this->AddDirectionalLight(focal[0] - position[0],
                                focal[1] - position[1],
                                focal[2] - position[2],
                                k * c[0],
                                k * c[1],
                                k * c[2]);
    }
  }
}

vtkMTimeType vtkVolumetricRadiosity::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (vtkObject* f : std::initializer_list<vtkObject*>{ this->ExtinctionFunction,
                                                         this->AlbedoFunction,
                                                         this->ColorFunction,
                                                         this->EmissionFunction }) {
    if (f) {
      t = std::max(t, f->GetMTime());
    }
  }
  return t;
}

int vtkVolumetricRadiosity::RequestUpdateExtent(vtkInformation*,
                                                vtkInformationVector** inputVector,
                                                vtkInformationVector*)
{
  // The solve is global: it always needs the whole volume.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
              inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()),
              6);
  return 1;
}

int vtkVolumetricRadiosity::RequestData(vtkInformation*,
                                        vtkInformationVector** inputVector,
                                        vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkPolyData* walls = vtkPolyData::GetData(outputVector, 1);
  if (!input || !output || !walls) {
    vtkErrorMacro("vtkVolumetricRadiosity needs a vtkImageData input");
    return 0;
  }
  try {
    volrad::SceneDescription description;
    if (this->SceneJSON && *this->SceneJSON) {
      description = volrad::parseSceneDescription(this->SceneJSON);
    } else if (this->SceneFileName && *this->SceneFileName) {
      description = volrad::readSceneDescription(this->SceneFileName);
    }
    // Properties over the scene file.
    if (this->Channels > 0) {
      if (this->Channels == 2) {
        throw volrad::Error("Channels must be 1 or 3");
      }
      description.channels = this->Channels;
    }
    if (this->SolverMethod && *this->SolverMethod) {
      description.solver.method = this->SolverMethod;
    }
    if (this->Epsilon > 0.0) {
      description.solver.epsilon = this->Epsilon;
    }
    description.solver.memoryBudgetBytes = this->MemoryBudget * 1024.0 * 1024.0;
    description.solver.emptySpaceFields = !this->SkipEmptySpace;
    if (this->MaterialScalars && *this->MaterialScalars) {
      description.material.scalars = this->MaterialScalars;
    }
    for (int f = 0; f < 6; ++f) {
      const auto& face = this->Faces[f];
      if (face[0] == 0.0) {
        continue;
      }
      const int C = description.channels;
      auto rgb = [C](double r, double g, double b) { return channelValues(C, r, g, b); };
      volrad::BoundaryCondition bc;
      if (face[0] == 1.0) {
        bc.radiance = rgb(face[1], face[2], face[3]);
      } else {
        bc.type = volrad::BoundaryCondition::Type::Wall;
        bc.reflectance = rgb(face[1], face[2], face[3]);
        bc.emission = rgb(face[4], face[5], face[6]);
      }
      description.boundary[f] = bc;
    }
    applyMaterialProperties(this, description);
    for (const auto& l : this->Lights) {
      const int C = description.channels;
      const volrad::ChannelValues rgb = channelValues(C, l[4], l[5], l[6]);
      if (l[0] == 0.0) {
        description.directionalLights.push_back({ volrad::Vec3(l[1], l[2], l[3]), rgb });
      } else {
        description.pointLights.push_back({ volrad::Vec3(l[1], l[2], l[3]), rgb });
      }
    }
    std::string missing;
    const volrad::Scene scene = makeScene(input, description, missing);
    if (!missing.empty()) {
      vtkWarningMacro("the input has no point-data array " << missing << ": taken as zero");
    }
    for (const std::string& message : volrad::lightsWallsKeepOut(scene)) {
      vtkWarningMacro(<< message);
    }
    if (this->SkipEmptySpace && description.solver.method == "dense") {
      vtkWarningMacro("SkipEmptySpace is for the hierarchical solver: the dense solver computes "
                      "the fields of every voxel");
    }
    const volrad::Solution solution =
      volrad::solve(scene, description.solver, this->NumberOfThreads, [this](double f) {
        this->UpdateProgress(f);
        return !this->GetAbortExecute();
      });

    output->ShallowCopy(input);
    const int C = solution.channels;
    addPointArray(output, "IncidentRadiation", solution.G, C);
    addPointArray(output, "IsotropicRadiosity", solution.QI, C);
    addPointArray(output, "DiffuseRadiosity", solution.QD, C);
    addPointArray(output, "FrontIncidentRadiation", solution.Gplus, C);
    addPointArray(output, "AbsorbedPower", solution.absorbed, C);
    double white = 0.0;
    const std::vector<std::uint8_t> rgba = volrad::renderColors(scene, solution, {}, &white);
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("RenderRGBA");
    colors->SetNumberOfComponents(4);
    colors->SetNumberOfTuples(input->GetNumberOfPoints());
    std::copy(rgba.begin(), rgba.end(), colors->GetPointer(0));
    output->GetPointData()->AddArray(colors);
    addStatistics(output->GetFieldData(), solution);
    addField(output->GetFieldData(), "RenderWhiteRadiance", { white });
    walls->ShallowCopy(makeWalls(scene, solution));
  } catch (const volrad::Aborted&) {
    vtkWarningMacro("the solve was aborted");
    output->Initialize();
    walls->Initialize();
    return 1;
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    output->Initialize();
    walls->Initialize();
    return 0;
  }
  return 1;
}

void vtkVolumetricRadiosity::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneFileName: " << (this->SceneFileName ? this->SceneFileName : "(none)")
     << "\n";
  os << indent << "SceneJSON: " << (this->SceneJSON ? this->SceneJSON : "(none)") << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " MiB\n";
  os << indent << "SkipEmptySpace: " << (this->SkipEmptySpace ? "On" : "Off") << "\n";
  os << indent << "MaterialPreset: " << (this->MaterialPreset ? this->MaterialPreset : "(none)")
     << "\n";
  os << indent << "ExtinctionFunction: " << this->ExtinctionFunction.Get() << "\n";
  os << indent << "AlbedoFunction: " << this->AlbedoFunction.Get() << "\n";
  os << indent << "ColorFunction: " << this->ColorFunction.Get() << "\n";
  os << indent << "EmissionFunction: " << this->EmissionFunction.Get() << "\n";
  os << indent << "RescaleSlope: " << this->RescaleSlope << "\n";
  os << indent << "RescaleIntercept: " << this->RescaleIntercept << "\n";
  os << indent << "SurfaceGradient: " << this->SurfaceGradient << "\n";
  os << indent << "Lights: " << this->Lights.size() << "\n";
  os << indent << "Channels: " << this->Channels << "\n";
  os << indent << "SolverMethod: " << (this->SolverMethod ? this->SolverMethod : "(scene's)")
     << "\n";
  os << indent << "Epsilon: " << this->Epsilon << "\n";
  os << indent
     << "MaterialScalars: " << (this->MaterialScalars ? this->MaterialScalars : "(scene's)")
     << "\n";
}
