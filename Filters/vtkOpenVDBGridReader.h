// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkOpenVDBGridReader
 * @brief Reads one grid of an OpenVDB (.vdb) file as vtkImageData.
 *
 * The grid (GridName, or the file's first grid when empty) is read over
 * the bounding box of its active voxels: one point per voxel, spacing the
 * voxel size, origin the centre of the box's first voxel (the grid's
 * translation and scale; other transforms are refused). The values become
 * the active point scalars, a float array named after the grid with 1
 * component (float and double grids) or 3 (vec3 grids); voxels outside the
 * active set hold the grid's background. Smoke, fire and clouds from
 * simulations and film pipelines come in this format; vtkVolumetricRadiosity
 * lights them like any other volume.
 *
 * An unreadable or corrupt file, an absent grid (the message lists the
 * grids there are), an unsupported type or transform, a grid without
 * active voxels or with more than MaximumVoxels give an error and an empty
 * output. Needs VolRad built with OpenVDB (Debian's libopenvdb-dev).
 *
 * The grid's active box is known only once its tree is read, so
 * RequestInformation reads the grid and RequestData hands it over (two
 * copies of the values for a moment; a later update without a change reads
 * the file again).
 */
#ifndef vtkOpenVDBGridReader_h
#define vtkOpenVDBGridReader_h

#include "VolRadFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for the grid read in RequestInformation

namespace volrad {
struct DenseVolume;
}

class VOLRADFILTERS_EXPORT vtkOpenVDBGridReader : public vtkImageAlgorithm
{
public:
  static vtkOpenVDBGridReader* New();
  vtkTypeMacro(vtkOpenVDBGridReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vdb file.
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  ///@{
  /// The grid to read (empty, the default: the file's first grid).
  vtkSetStringMacro(GridName);
  vtkGetStringMacro(GridName);
  ///@}

  ///@{
  /// Largest active bounding box read, in voxels (default 512^3).
  vtkSetClampMacro(MaximumVoxels, vtkTypeInt64, 1, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MaximumVoxels, vtkTypeInt64);
  ///@}

  /// Whether the file is a .vdb file this reader can open.
  static int CanReadFile(const char* fileName);

protected:
  vtkOpenVDBGridReader();
  ~vtkOpenVDBGridReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkOpenVDBGridReader(const vtkOpenVDBGridReader&) = delete;
  void operator=(const vtkOpenVDBGridReader&) = delete;

  /// Reads the grid into Volume unless it holds this file's and grid's.
  bool ReadGrid();

  char* FileName = nullptr;
  char* GridName = nullptr;
  vtkTypeInt64 MaximumVoxels = vtkTypeInt64(512) * 512 * 512;
  // The grid read for RequestInformation, kept for RequestData (a .vdb
  // file's active box is only known once its grid is read).
  std::unique_ptr<volrad::DenseVolume> Volume;
  vtkTimeStamp ReadTime;
};

#endif
