// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkVolumetricRadiosity
 * @brief Global illumination of a volume: volumetric radiosity.
 *
 * Takes a vtkImageData whose point data hold the optical coefficients of
 * the medium (docs/scene-format.md: absorption kappa_a, isotropic
 * scattering sigma_i, surface-like scattering sigma_d [1/length];
 * emission E_I, E_D [W/m^2]; normals), or scalars that a material maps to
 * them (a preset or transfer functions, below), solves volumetric radiosity
 * once (lights, environment and walls as the scene says; the hierarchical
 * solver by default) and outputs on port 0 the input with these point-data
 * arrays added (float, 1 or 3 components): IncidentRadiation (G),
 * IsotropicRadiosity (Q_I), DiffuseRadiosity (Q_D), FrontIncidentRadiation
 * (G+), AbsorbedPower [W/length^3], plus RenderRGBA (unsigned char, 4
 * components: tone-mapped radiance and opacity, for volume mappers with
 * IndependentComponents off); the solve's statistics and energy terms go to
 * field data. Port 1 holds the wall patches with their radiosity and
 * irradiance.
 *
 * The scene (array names, material, channels, boundary, lights, solver) is
 * given as a scene file or as its JSON text; the material properties below
 * replace the scene's. Radiosity is global, so the filter always requests
 * and produces the whole extent. Progress events follow the solve, and
 * AbortExecute stops it (the output is then empty).
 */
#ifndef vtkVolumetricRadiosity_h
#define vtkVolumetricRadiosity_h

#include "VolRadFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for the transfer functions

#include <array>  // for the lights
#include <vector> // for the lights

class vtkColorTransferFunction;
class vtkPolyData;
class vtkRenderer;
class vtkPiecewiseFunction;

class VOLRADFILTERS_EXPORT vtkVolumetricRadiosity : public vtkImageAlgorithm
{
public:
  static vtkVolumetricRadiosity* New();
  vtkTypeMacro(vtkVolumetricRadiosity, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Port 1: the wall patches, one quad per voxel face on every wall of the
   * domain, with cell data Radiosity (B) and Irradiance (H) [W/m^2], 1 or
   * `channels` components; empty when the scene has no walls.
   */
  vtkPolyData* GetWallOutput();

  ///@{
  /**
   * Path of a scene file (JSON, docs/scene-format.md). Used when SceneJSON
   * is empty; when both are empty the defaults apply (arrays named
   * kappa_a, sigma_i, sigma_d, E_I, E_D, n where present, open black
   * boundary, no lights).
   */
  vtkSetStringMacro(SceneFileName);
  vtkGetStringMacro(SceneFileName);
  ///@}

  ///@{
  /** The scene as JSON text; takes precedence over SceneFileName. */
  vtkSetStringMacro(SceneJSON);
  vtkGetStringMacro(SceneJSON);
  ///@}

  ///@{
  /**
   * Scene settings as properties; each replaces the scene file's when set.
   * Channels: 1 (grey) or 3 (RGB); 0 (default): the scene's.
   * SolverMethod: "hierarchical" or "dense"; empty (default): the scene's.
   * Epsilon: the hierarchical solver's relative accuracy; <= 0: the scene's.
   * MaterialScalars: the point array the material maps and whose gradient
   * gives the normals; empty: the scene's, else the active scalars.
   */
  vtkSetClampMacro(Channels, int, 0, 3);
  vtkGetMacro(Channels, int);
  vtkSetStringMacro(SolverMethod);
  vtkGetStringMacro(SolverMethod);
  vtkSetMacro(Epsilon, double);
  vtkGetMacro(Epsilon, double);
  vtkSetStringMacro(MaterialScalars);
  vtkGetStringMacro(MaterialScalars);
  ///@}

  ///@{
  /**
   * The faces of the domain (0-5: xmin, xmax, ymin, ymax, zmin, zmax, in
   * index directions), besides the scene file's: an open face with incoming
   * radiance (r, g, b) [W/(m^2 sr)], or a Lambertian wall of reflectance
   * (r, g, b) in [0, 1) and emission (er, eg, eb) [W/m^2].
   * SetEnvironmentRadiance opens every face with one radiance.
   */
  void SetOpenFace(int face, double r, double g, double b);
  void SetWallFace(int face, double r, double g, double b, double er, double eg, double eb);
  void SetEnvironmentRadiance(double r, double g, double b);
  /**
   * The same with the face number as a double: ParaView's repeated
   * properties (OpenFaces, WallFaces) pass doubles only.
   */
  void SetOpenFace(double face, double r, double g, double b);
  void SetWallFace(double face, double r, double g, double b, double er, double eg, double eb);
  /** Back to the scene file's faces: all of them, the open ones, the walls. */
  void RemoveAllFaceSettings();
  void RemoveAllOpenFaces();
  void RemoveAllWallFaces();
  ///@}

  ///@{
  /**
   * Memory budget of the solve [MiB]: above its estimate of what it needs,
   * the solve refuses before allocating, naming both figures. 0 (default):
   * the solver's own (hierarchical: half the physical memory; dense: 4 GiB).
   */
  vtkSetClampMacro(MemoryBudget, double, 0.0, 1e12);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  ///@{
  /**
   * A sparse solve (the hierarchical solver; the dense one computes every
   * voxel, with a warning): the fields of voxels without medium (kappa_t = 0
   * in a channel, empty space) are not computed and are 0 in that channel,
   * like the inactive background of an OpenVDB grid; empty space then costs
   * no links, views or time, and the medium's fields are those of the full
   * solve. Off (default): G of empty space too.
   */
  vtkSetMacro(SkipEmptySpace, vtkTypeBool);
  vtkGetMacro(SkipEmptySpace, vtkTypeBool);
  vtkBooleanMacro(SkipEmptySpace, vtkTypeBool);
  ///@}

  ///@{
  /** Threads of the solve; 0 (default) uses all cores, 1 is deterministic. */
  vtkSetClampMacro(NumberOfThreads, int, 0, 4096);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Material: how the input's scalars (the scene's material.scalars, else the
   * active scalars) become optical coefficients, in the idiom of
   * vtkVolumeProperty. Each of these replaces the same part of the scene
   * file's material; coefficient arrays the input has still win.
   * MaterialPreset: "ct", "ct-bone", "mr", "cloud" (README); empty or
   * "none": none.
   * ExtinctionFunction: kappa_t [1/length] of the scalar.
   * AlbedoFunction: the scattering albedo in [0, 1].
   * ColorFunction: per-channel factor of the albedo (the colour of the
   * scattered light) in [0, 1].
   * EmissionFunction: E_I [W/m^2] per channel.
   * SurfaceGradient: gradient magnitude [scalar / length] at which 63% of the
   * scattering is surface-like (about the gradient normal); 0: isotropic;
   * negative (default): the scene's or preset's.
   */
  vtkSetStringMacro(MaterialPreset);
  vtkGetStringMacro(MaterialPreset);
  void SetExtinctionFunction(vtkPiecewiseFunction* f);
  vtkPiecewiseFunction* GetExtinctionFunction();
  void SetAlbedoFunction(vtkPiecewiseFunction* f);
  vtkPiecewiseFunction* GetAlbedoFunction();
  void SetColorFunction(vtkColorTransferFunction* f);
  vtkColorTransferFunction* GetColorFunction();
  void SetEmissionFunction(vtkColorTransferFunction* f);
  vtkColorTransferFunction* GetEmissionFunction();
  vtkSetMacro(SurfaceGradient, double);
  vtkGetMacro(SurfaceGradient, double);
  ///@}

  ///@{
  /**
   * The material reads slope x scalar + intercept (DICOM's RescaleSlope and
   * RescaleIntercept: stored CT values to Hounsfield units, e.g. intercept
   * -1024). Unset (NaN, the default): the scene file's, else 1 and 0.
   */
  vtkSetMacro(RescaleSlope, double);
  vtkGetMacro(RescaleSlope, double);
  vtkSetMacro(RescaleIntercept, double);
  vtkGetMacro(RescaleIntercept, double);
  ///@}

  ///@{
  /**
   * Lights besides the scene file's. A directional light travels along
   * (dx, dy, dz) with irradiance (r, g, b) [W/m^2] on a plane normal to it;
   * a point light at (x, y, z) has intensity (r, g, b) [W/sr]. Grey scenes
   * take the mean of r, g, b.
   */
  void AddDirectionalLight(double dx, double dy, double dz, double r, double g, double b);
  void AddPointLight(double x, double y, double z, double r, double g, double b);
  void RemoveAllLights();
  /** Removes one kind only (ParaView's light lists clear them one by one). */
  void RemoveAllDirectionalLights();
  void RemoveAllPointLights();
  int GetNumberOfLights();
  /**
   * Adds the switched-on lights of a renderer, so that the lighting matches
   * what it renders: positional lights as point lights of intensity
   * `scale` x Intensity x DiffuseColor, the others (scene, camera and head
   * lights, placed by the renderer's active camera) as directional lights
   * from their position towards their focal point with that irradiance.
   */
  void AddLightsFromRenderer(vtkRenderer* renderer, double scale = 1.0);
  ///@}

  /** Includes the transfer functions' modification times. */
  vtkMTimeType GetMTime() override;

protected:
  vtkVolumetricRadiosity();
  ~vtkVolumetricRadiosity() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* SceneFileName = nullptr;
  char* SceneJSON = nullptr;
  int NumberOfThreads = 0;
  double MemoryBudget = 0.0;
  vtkTypeBool SkipEmptySpace = 0;
  char* MaterialPreset = nullptr;
  vtkSmartPointer<vtkPiecewiseFunction> ExtinctionFunction;
  vtkSmartPointer<vtkPiecewiseFunction> AlbedoFunction;
  vtkSmartPointer<vtkColorTransferFunction> ColorFunction;
  vtkSmartPointer<vtkColorTransferFunction> EmissionFunction;
  double SurfaceGradient = -1.0;
  double RescaleSlope;
  double RescaleIntercept;
  int Channels = 0;
  char* SolverMethod = nullptr;
  double Epsilon = 0.0;
  char* MaterialScalars = nullptr;
  /// Per face set here: 0 none, 1 open, 2 wall; then (r, g, b, er, eg, eb).
  std::array<std::array<double, 7>, 6> Faces{};
  /// Per light: 0 directional / 1 point, then direction or position, then r, g, b.
  std::vector<std::array<double, 7>> Lights;

private:
  vtkVolumetricRadiosity(const vtkVolumetricRadiosity&) = delete;
  void operator=(const vtkVolumetricRadiosity&) = delete;
};

#endif
