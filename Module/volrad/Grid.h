// SPDX-License-Identifier: BSD-3-Clause
/// @file Grid.h
/// @brief The regular voxel grid of a scene and its boundary patches.
///
/// Voxel i is the box of size `spacing` centred on point i of the input
/// image (physics.md section 2). Lengths are in the units of the spacing.
/// The domain's six faces are split into patches, one per voxel face on the
/// boundary.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace volrad {

using Vec3 = Eigen::Vector3d;
/// Per-node work arrays of the far field (half the bytes; sums in double).
using Vec3f = Eigen::Vector3f;
using Index = std::int64_t;

/// The six faces of the domain, in index directions (VTK's i, j, k).
enum class Face : int
{
  XMin = 0,
  XMax,
  YMin,
  YMax,
  ZMin,
  ZMax
};
constexpr int kFaceCount = 6;

inline int faceAxis(Face f)
{
  return static_cast<int>(f) / 2;
}
inline bool faceIsMax(Face f)
{
  return static_cast<int>(f) % 2 == 1;
}
inline Face makeFace(int axis, bool isMax)
{
  return static_cast<Face>(2 * axis + (isMax ? 1 : 0));
}
/// Unit normal of a face pointing into the domain.
Vec3 faceInwardNormal(Face f);
/// "xmin", "xmax", ... as in the scene file.
const char* faceName(Face f);

/// The two in-plane axes of a face, in increasing order.
inline std::array<int, 2> faceAxesInPlane(Face f)
{
  const int a = faceAxis(f);
  return a == 0 ? std::array<int, 2>{ 1, 2 }
                : (a == 1 ? std::array<int, 2>{ 0, 2 } : std::array<int, 2>{ 0, 1 });
}

struct PatchLocation
{
  Face face = Face::XMin;
  int a = 0; ///< index along the first in-plane axis
  int b = 0; ///< index along the second in-plane axis
};

struct Grid
{
  std::array<int, 3> dims{ 0, 0, 0 };
  Vec3 spacing{ 1.0, 1.0, 1.0 };
  Vec3 origin{ 0.0, 0.0, 0.0 }; ///< centre of voxel (0, 0, 0)

  Index voxelCount() const { return Index(dims[0]) * dims[1] * dims[2]; }
  /// VTK point order: i fastest.
  Index index(int i, int j, int k) const { return i + Index(dims[0]) * (j + Index(dims[1]) * k); }
  std::array<int, 3> ijk(Index v) const
  {
    if (std::uint64_t(v) <= 0xffffffffu) { // 32-bit division: cheaper, and asked per link candidate
      const std::uint32_t u = std::uint32_t(v), d0 = std::uint32_t(dims[0]),
                          d1 = std::uint32_t(dims[1]), r = u / d0;
      return { int(u - r * d0), int(r % d1), int(r / d1) };
    }
    const int i = int(v % dims[0]);
    const Index r = v / dims[0];
    return { i, int(r % dims[1]), int(r / dims[1]) };
  }
  double voxelVolume() const { return spacing.prod(); }
  Vec3 lower() const { return origin - 0.5 * spacing; }
  Vec3 upper() const
  {
    return origin + Vec3((dims[0] - 0.5) * spacing[0],
                         (dims[1] - 0.5) * spacing[1],
                         (dims[2] - 0.5) * spacing[2]);
  }
  Vec3 voxelLower(Index v) const
  {
    const auto c = ijk(v);
    return lower() + Vec3(c[0] * spacing[0], c[1] * spacing[1], c[2] * spacing[2]);
  }
  Vec3 voxelCentre(Index v) const { return voxelLower(v) + 0.5 * spacing; }

  // Boundary patches.
  Index facePatchCount(Face f) const
  {
    const auto ax = faceAxesInPlane(f);
    return Index(dims[ax[0]]) * dims[ax[1]];
  }
  /// Patches are numbered face by face (xmin, xmax, ymin, ...); closed form
  /// because the traversal asks for it once per ray.
  Index facePatchOffset(Face f) const
  {
    const Index yz = Index(dims[1]) * dims[2], xz = Index(dims[0]) * dims[2], xy = Index(dims[0]) * dims[1];
    const Index before[kFaceCount] = { 0, yz, 2 * yz, 2 * yz + xz, 2 * (yz + xz), 2 * (yz + xz) + xy };
    return before[static_cast<int>(f)];
  }
  Index patchCount() const { return facePatchOffset(Face::ZMax) + facePatchCount(Face::ZMax); }
  Index patchIndex(Face f, int a, int b) const
  {
    return facePatchOffset(f) + a + Index(dims[faceAxesInPlane(f)[0]]) * b;
  }
  PatchLocation patchLocation(Index p) const;
  double patchArea(Face f) const
  {
    const auto ax = faceAxesInPlane(f);
    return spacing[ax[0]] * spacing[ax[1]];
  }
  /// Lower corner of the patch (a point on the face plane).
  Vec3 patchLower(Index p) const;
  Vec3 patchCentre(Index p) const;
  /// The voxel whose face the patch is.
  Index patchVoxel(Index p) const;
  /// Area of a whole face of the domain.
  double faceArea(Face f) const { return patchArea(f) * double(facePatchCount(f)); }
};

} // namespace volrad
