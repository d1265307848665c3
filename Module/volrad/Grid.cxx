// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Grid.h"

namespace volrad {

Vec3 faceInwardNormal(Face f)
{
  Vec3 n = Vec3::Zero();
  n[faceAxis(f)] = faceIsMax(f) ? -1.0 : 1.0;
  return n;
}

const char* faceName(Face f)
{
  static const char* names[kFaceCount] = { "xmin", "xmax", "ymin", "ymax", "zmin", "zmax" };
  return names[static_cast<int>(f)];
}

PatchLocation Grid::patchLocation(Index p) const
{
  for (int fi = 0; fi < kFaceCount; ++fi) {
    const Face f = static_cast<Face>(fi);
    const Index n = facePatchCount(f);
    if (p < n) {
      const int na = dims[faceAxesInPlane(f)[0]];
      return { f, int(p % na), int(p / na) };
    }
    p -= n;
  }
  return {};
}

Vec3 Grid::patchLower(Index p) const
{
  const PatchLocation loc = patchLocation(p);
  const auto ax = faceAxesInPlane(loc.face);
  Vec3 x = lower();
  x[ax[0]] += loc.a * spacing[ax[0]];
  x[ax[1]] += loc.b * spacing[ax[1]];
  if (faceIsMax(loc.face)) {
    x[faceAxis(loc.face)] = upper()[faceAxis(loc.face)];
  }
  return x;
}

Vec3 Grid::patchCentre(Index p) const
{
  const auto ax = faceAxesInPlane(patchLocation(p).face);
  Vec3 x = patchLower(p);
  x[ax[0]] += 0.5 * spacing[ax[0]];
  x[ax[1]] += 0.5 * spacing[ax[1]];
  return x;
}

Index Grid::patchVoxel(Index p) const
{
  const PatchLocation loc = patchLocation(p);
  const auto ax = faceAxesInPlane(loc.face);
  std::array<int, 3> c{};
  c[ax[0]] = loc.a;
  c[ax[1]] = loc.b;
  const int axis = faceAxis(loc.face);
  c[axis] = faceIsMax(loc.face) ? dims[axis] - 1 : 0;
  return index(c[0], c[1], c[2]);
}

} // namespace volrad
