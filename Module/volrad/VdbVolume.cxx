// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/VdbVolume.h"

#include "volrad/Error.h"

#ifdef VOLRAD_HAVE_OPENVDB
#include <openvdb/openvdb.h>
#endif

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace volrad {

#ifndef VOLRAD_HAVE_OPENVDB

bool vdbSupported()
{
  return false;
}

namespace {
[[noreturn]] void unsupported()
{
  throw Error("this VolRad was built without OpenVDB: .vdb files are not available");
}
} // namespace

std::vector<std::pair<std::string, std::string>> listVdbGrids(const std::string&)
{
  unsupported();
}
DenseVolume readVdbGrid(const std::string&, const std::string&, std::size_t)
{
  unsupported();
}
void writeVdbGrids(const std::string&, const std::vector<DenseVolume>&, float)
{
  unsupported();
}

#else

bool vdbSupported()
{
  return true;
}

namespace {

/// OpenVDB's message in one short line: from a corrupt file it quotes what
/// it read as a name, which can be a gigabyte of blanks.
std::string shortMessage(const char* what)
{
  constexpr std::size_t kMost = 200;
  std::string out;
  bool cut = false;
  for (const char* p = what; *p; ++p) {
    const unsigned char c = static_cast<unsigned char>(*p);
    if (!std::isgraph(c) && c != ' ') {
      continue; // control characters and bytes past ASCII
    }
    if (c == ' ' && (out.empty() || out.back() == ' ')) {
      continue; // runs of blanks as one
    }
    if (out.size() == kMost) {
      cut = true;
      break;
    }
    out += char(c);
  }
  return cut ? out + "..." : out;
}

/// Runs f; OpenVDB's own errors (and std ones from lengths read from
/// garbage: bad_alloc, length_error) become VolRad's, naming the file.
template<class F>
auto withVdbErrors(const std::string& path, const char* problem, F f) -> decltype(f())
{
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("'" + path + "' " + problem + ": " + shortMessage(e.what()));
  }
}

/// Opens a .vdb file for reading, with VolRad's messages.
std::unique_ptr<openvdb::io::File> openFile(const std::string& path)
{
  openvdb::initialize();
  if (!std::ifstream(path)) {
    throw Error("cannot read the file '" + path + "'");
  }
  auto file = std::make_unique<openvdb::io::File>(path);
  withVdbErrors(path, "is not a readable OpenVDB file", [&] { file->open(); });
  return file;
}

/// Runs a read from an open file (a truncated or corrupt file passes open()
/// and fails here).
template<class Read>
auto readFrom(const std::string& path, Read read) -> decltype(read())
{
  return withVdbErrors(path, "is corrupt or truncated", read);
}

template<class GridT, int Components>
void copyValues(const GridT& grid, const openvdb::CoordBBox& box, DenseVolume& out)
{
  auto acc = grid.getConstAccessor();
  const openvdb::Coord lo = box.min();
  std::size_t k = 0;
  for (int z = 0; z < out.dims[2]; ++z) {
    for (int y = 0; y < out.dims[1]; ++y) {
      for (int x = 0; x < out.dims[0]; ++x) {
        const auto v = acc.getValue(lo + openvdb::Coord(x, y, z));
        if constexpr (Components == 1) {
          out.values[k++] = float(v);
        } else {
          for (int c = 0; c < 3; ++c) {
            out.values[k++] = float(v[c]);
          }
        }
      }
    }
  }
}

/// A grid of v's box with voxel i's value value(i); voxels equal to the
/// background stay inactive.
template<class GridT, class Value>
typename GridT::Ptr fillGrid(const DenseVolume& v,
                             const typename GridT::ValueType& background,
                             Value&& value)
{
  auto grid = GridT::create(background);
  auto acc = grid->getAccessor();
  const openvdb::Coord lo(v.indexLower[0], v.indexLower[1], v.indexLower[2]);
  std::size_t i = 0;
  for (int z = 0; z < v.dims[2]; ++z) {
    for (int y = 0; y < v.dims[1]; ++y) {
      for (int x = 0; x < v.dims[0]; ++x, ++i) {
        const typename GridT::ValueType val = value(i);
        if (val != background) {
          acc.setValue(lo + openvdb::Coord(x, y, z), val);
        }
      }
    }
  }
  grid->setName(v.name);
  return grid;
}

} // namespace

std::vector<std::pair<std::string, std::string>> listVdbGrids(const std::string& path)
{
  auto file = openFile(path);
  std::vector<std::pair<std::string, std::string>> grids;
  for (auto it = file->beginName(); it != file->endName(); ++it) {
    grids.emplace_back(it.gridName(), readFrom(path, [&] {
                         return file->readGridMetadata(it.gridName())->valueType();
                       }));
  }
  return grids;
}

DenseVolume readVdbGrid(const std::string& path, const std::string& name, std::size_t maxVoxels)
{
  auto file = openFile(path);
  std::string gridName = name;
  if (gridName.empty()) {
    auto it = file->beginName();
    if (it == file->endName()) {
      throw Error("'" + path + "' holds no grid");
    }
    gridName = it.gridName();
  }
  if (!file->hasGrid(gridName)) {
    std::string names;
    for (auto it = file->beginName(); it != file->endName(); ++it) {
      names += (names.empty() ? "" : ", ") + it.gridName();
    }
    throw Error("'" + path + "' has no grid '" + gridName + "' (its grids: " + names + ")");
  }
  const openvdb::GridBase::Ptr base = readFrom(path, [&] { return file->readGrid(gridName); });
  const openvdb::math::Transform& xf = base->transform();
  const openvdb::Vec3d h = xf.voxelSize();
  if (!xf.isLinear()) {
    throw Error("grid '" + gridName + "': only linear transforms are supported");
  }
  // A scale and translation only: index (0,0,0) and the unit steps map there.
  const openvdb::Vec3d o = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
  for (int a = 0; a < 3; ++a) {
    openvdb::Vec3d e(0, 0, 0);
    e[a] = 1.0;
    const openvdb::Vec3d step = xf.indexToWorld(e) - o;
    for (int b = 0; b < 3; ++b) {
      if (b != a && std::abs(step[b]) > 1e-9 * h[a]) {
        throw Error("grid '" + gridName +
                    "': its transform rotates or shears; VolRad reads "
                    "axis-aligned grids (scale and translation) only");
      }
    }
  }
  const openvdb::CoordBBox box = base->evalActiveVoxelBoundingBox();
  if (box.empty()) {
    throw Error("grid '" + gridName + "' of '" + path + "' has no active voxels");
  }
  DenseVolume out;
  out.name = gridName;
  const openvdb::Coord ext = box.dim();
  const double count = double(ext[0]) * ext[1] * ext[2];
  if (count > double(maxVoxels)) {
    std::ostringstream msg;
    msg << "grid '" << gridName << "': its active box of " << ext[0] << " x " << ext[1] << " x "
        << ext[2] << " voxels is over the limit of " << maxVoxels << " voxels";
    throw Error(msg.str());
  }
  for (int a = 0; a < 3; ++a) {
    out.dims[a] = ext[a];
    out.indexLower[a] = box.min()[a];
    out.spacing[a] = h[a];
  }
  const openvdb::Vec3d first = xf.indexToWorld(box.min().asVec3d());
  out.origin = Vec3(first[0], first[1], first[2]);
  if (base->isType<openvdb::FloatGrid>()) {
    out.values.resize(std::size_t(count));
    copyValues<openvdb::FloatGrid, 1>(
      *openvdb::gridConstPtrCast<openvdb::FloatGrid>(base), box, out);
  } else if (base->isType<openvdb::DoubleGrid>()) {
    out.values.resize(std::size_t(count));
    copyValues<openvdb::DoubleGrid, 1>(
      *openvdb::gridConstPtrCast<openvdb::DoubleGrid>(base), box, out);
  } else if (base->isType<openvdb::Vec3SGrid>()) {
    out.components = 3;
    out.values.resize(std::size_t(count) * 3);
    copyValues<openvdb::Vec3SGrid, 3>(
      *openvdb::gridConstPtrCast<openvdb::Vec3SGrid>(base), box, out);
  } else if (base->isType<openvdb::Vec3DGrid>()) {
    out.components = 3;
    out.values.resize(std::size_t(count) * 3);
    copyValues<openvdb::Vec3DGrid, 3>(
      *openvdb::gridConstPtrCast<openvdb::Vec3DGrid>(base), box, out);
  } else {
    throw Error("grid '" + gridName + "' holds " + base->valueType() +
                " values; VolRad reads float, double and vec3 grids");
  }
  return out;
}

void writeVdbGrids(const std::string& path,
                   const std::vector<DenseVolume>& volumes,
                   float background)
{
  openvdb::initialize();
  openvdb::GridPtrVec grids;
  for (const DenseVolume& v : volumes) {
    if (v.components != 1 && v.components != 3) {
      throw Error("grid '" + v.name + "': 1 or 3 components per voxel");
    }
    if (v.values.size() != std::size_t(v.dims[0]) * v.dims[1] * v.dims[2] * v.components) {
      throw Error("grid '" + v.name + "': the values do not fill its box");
    }
    // Voxel centres at index * spacing + translation, as readVdbGrid reads them.
    openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(1.0);
    xf->preScale(openvdb::Vec3d(v.spacing[0], v.spacing[1], v.spacing[2]));
    xf->postTranslate(openvdb::Vec3d(v.origin[0] - v.indexLower[0] * v.spacing[0],
                                     v.origin[1] - v.indexLower[1] * v.spacing[1],
                                     v.origin[2] - v.indexLower[2] * v.spacing[2]));
    if (v.components == 1) {
      auto grid =
        fillGrid<openvdb::FloatGrid>(v, background, [&](std::size_t i) { return v.values[i]; });
      grid->setGridClass(openvdb::GRID_FOG_VOLUME);
      grid->setTransform(xf);
      grids.push_back(grid);
    } else {
      auto grid = fillGrid<openvdb::Vec3SGrid>(v, openvdb::Vec3s(background), [&](std::size_t i) {
        return openvdb::Vec3s(v.values[3 * i], v.values[3 * i + 1], v.values[3 * i + 2]);
      });
      grid->setTransform(xf);
      grids.push_back(grid);
    }
  }
  // Written next to the target and renamed: a failed write leaves no file.
  const std::string partial = path + ".partial.vdb";
  try {
    openvdb::io::File(partial).write(grids);
  } catch (const std::exception& e) {
    std::remove(partial.c_str());
    throw Error("cannot write '" + path + "': " + e.what());
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    std::remove(partial.c_str());
    throw Error("cannot write '" + path + "'");
  }
}

#endif

} // namespace volrad
