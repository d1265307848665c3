// SPDX-License-Identifier: BSD-3-Clause
/// @file VdbVolume.h
/// @brief OpenVDB files in and out (issue 6's reader and writer): a named
/// grid of a `.vdb` file as a dense volume over its active bounding box, and
/// solution fields written back as float grids that Houdini, Blender and
/// every OpenVDB tool read. Available when VolRad is built with OpenVDB
/// (vdbSupported()); otherwise these throw volrad::Error saying so.
#pragma once

#include "volrad/Grid.h"

#include <cstddef>
#include <string>
#include <vector>

namespace volrad {

/// A dense box of voxels: values per voxel (x fastest), `components` each.
struct DenseVolume
{
  std::string name;                 ///< the grid's name
  std::array<int, 3> dims{ 0, 0, 0 }; ///< voxels along i, j, k
  std::array<int, 3> indexLower{ 0, 0, 0 }; ///< the box's first voxel in the grid's index space
  Vec3 spacing{ 1, 1, 1 };          ///< voxel size
  Vec3 origin{ 0, 0, 0 };           ///< centre of the box's first voxel, world coordinates
  int components = 1;               ///< 1 (float, double grids) or 3 (vec3 grids)
  std::vector<float> values;        ///< background outside the active voxels
};

bool vdbSupported();

/// The grid names of a .vdb file with their value types.
std::vector<std::pair<std::string, std::string>> listVdbGrids(const std::string& path);

/// Reads grid `name` (the first grid when empty) of a .vdb file over its
/// active voxels' bounding box. float, double and vec3 (float, double)
/// grids; the transform must be a linear scale and translation (voxel
/// centres at index * voxel size + translation). Throws volrad::Error naming
/// the problem: unreadable file, absent grid (with the names there are),
/// unsupported type or transform, no active voxels, more than maxVoxels.
DenseVolume readVdbGrid(const std::string& path,
                        const std::string& name = "",
                        std::size_t maxVoxels = std::size_t(512) * 512 * 512);

/// Writes each volume as a float (1 component) or vec3s grid of the same
/// geometry, values equal to `background` left inactive; replaces the file
/// (written next to it and renamed: a failed write leaves no file).
void writeVdbGrids(const std::string& path,
                   const std::vector<DenseVolume>& volumes,
                   float background = 0.f);

} // namespace volrad
