// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkVolumetricRadiosity
 * @brief Global illumination of a volume: volumetric radiosity.
 *
 * Takes a vtkImageData whose point data hold the optical coefficients of
 * the medium (docs/scene-format.md: absorption kappa_a, isotropic
 * scattering sigma_i, surface-like scattering sigma_d [1/length];
 * emission E_I, E_D [W/m^2]; normals), solves volumetric radiosity once
 * (lights, environment and walls as the scene says), and outputs the input
 * with these point-data arrays added (float, 1 or 3 components):
 * IncidentRadiation (G), IsotropicRadiosity (Q_I), DiffuseRadiosity (Q_D),
 * FrontIncidentRadiation (G+), AbsorbedPower [W/length^3]; the solve's
 * statistics and energy terms go to field data.
 *
 * The scene (array names, channels, boundary, lights, solver) is given as a
 * scene file or as its JSON text. Radiosity is global, so the filter always
 * requests and produces the whole extent.
 */
#ifndef vtkVolumetricRadiosity_h
#define vtkVolumetricRadiosity_h

#include "VolRadFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for the transfer functions

class vtkColorTransferFunction;
class vtkPiecewiseFunction;

class VOLRADFILTERS_EXPORT vtkVolumetricRadiosity : public vtkImageAlgorithm
{
public:
  static vtkVolumetricRadiosity* New();
  vtkTypeMacro(vtkVolumetricRadiosity, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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
   * MaterialPreset: "ct", "ct-bone", "mr", "cloud" (README); empty: none.
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

  /** Includes the transfer functions' modification times. */
  vtkMTimeType GetMTime() override;

protected:
  vtkVolumetricRadiosity();
  ~vtkVolumetricRadiosity() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* SceneFileName = nullptr;
  char* SceneJSON = nullptr;
  int NumberOfThreads = 0;
  char* MaterialPreset = nullptr;
  vtkSmartPointer<vtkPiecewiseFunction> ExtinctionFunction;
  vtkSmartPointer<vtkPiecewiseFunction> AlbedoFunction;
  vtkSmartPointer<vtkColorTransferFunction> ColorFunction;
  vtkSmartPointer<vtkColorTransferFunction> EmissionFunction;
  double SurfaceGradient = -1.0;

private:
  vtkVolumetricRadiosity(const vtkVolumetricRadiosity&) = delete;
  void operator=(const vtkVolumetricRadiosity&) = delete;
};

#endif
