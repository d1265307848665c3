// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkOpenVDBGridWriter
 * @brief Writes point arrays of a vtkImageData as grids of an OpenVDB (.vdb) file.
 *
 * Each array becomes a grid of its name: a float grid (1 component) or a
 * vec3s grid (3 components), voxel size the image's spacing, placed so that
 * voxel centres are the image's points. Values equal to Background stay
 * inactive, so empty space costs nothing in the file; vtkOpenVDBGridReader
 * gives back the box of the active voxels (the same image when its borders
 * hold something else; an array of background only, a grid without active
 * voxels, is written with a warning, and the reader refuses it). Rotated
 * images (a direction matrix other than the identity) are refused. Houdini, Blender and every
 * OpenVDB tool read the result: vtkVolumetricRadiosity's lighting (its IncidentRadiation,
 * IsotropicRadiosity, ... arrays) can be rendered there.
 *
 * ArrayNames chooses the arrays (default: every point array with 1 or 3
 * components). The file is written next to FileName and renamed, so a
 * failed write leaves no partial file. Errors (no input, an absent or
 * unsuitable array, an unwritable path) are reported with vtkErrorMacro
 * and GetErrorCode.
 */
#ifndef vtkOpenVDBGridWriter_h
#define vtkOpenVDBGridWriter_h

#include "VolRadFiltersModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for the array names
#include <vector> // for the array names

class vtkImageData;

class VOLRADFILTERS_EXPORT vtkOpenVDBGridWriter : public vtkWriter
{
public:
  static vtkOpenVDBGridWriter* New();
  vtkTypeMacro(vtkOpenVDBGridWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vdb file (replaced if it exists).
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// The point arrays written (none added: every point array with 1 or 3
  /// components).
  void AddArrayName(const char* name);
  void ClearArrayNames();
  ///@}

  ///@{
  /// The grids' background: voxels with this value (every component) stay
  /// inactive. Default 0.
  vtkSetMacro(Background, float);
  vtkGetMacro(Background, float);
  ///@}

  vtkImageData* GetInput();

protected:
  vtkOpenVDBGridWriter();
  ~vtkOpenVDBGridWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkOpenVDBGridWriter(const vtkOpenVDBGridWriter&) = delete;
  void operator=(const vtkOpenVDBGridWriter&) = delete;

  char* FileName = nullptr;
  std::vector<std::string> ArrayNames;
  float Background = 0.f;
};

#endif
