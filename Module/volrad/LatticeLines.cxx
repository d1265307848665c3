// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/LatticeLines.h"

#include "volrad/Error.h"
#include "volrad/VoxelTraversal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace volrad {

LatticeLines::LatticeLines(const Grid& grid, int reach, const std::vector<Vec3>& shifts)
  : reach_(std::max(0, std::min(reach, *std::max_element(grid.dims.begin(), grid.dims.end()) - 1)))
  , lines_(int(shifts.size()))
{
  const Index strideJ = grid.dims[0], strideK = Index(grid.dims[0]) * grid.dims[1];
  if (double(reach_) * double(1 + strideJ + strideK) > double(std::numeric_limits<std::int32_t>::max())) {
    throw Error("lattice lines: the grid's slabs are too large for 32-bit steps");
  }
  // The walks are made in a small grid of the same spacing around voxel
  // (reach, reach, reach); each crossed voxel is stored as its index step in
  // the real grid.
  const int w = 2 * reach_ + 1;
  Grid local;
  local.dims = { w, w, w };
  local.spacing = grid.spacing;
  local.origin = Vec3::Zero();
  const Vec3 centre = local.voxelCentre(local.index(reach_, reach_, reach_));
  start_.reserve(std::size_t(w) * w * w * lines_ + 1);
  start_.push_back(0);
  for (int dk = -reach_; dk <= reach_; ++dk) {
    for (int dj = -reach_; dj <= reach_; ++dj) {
      for (int di = -reach_; di <= reach_; ++di) {
        const Vec3 ab(di * grid.spacing[0], dj * grid.spacing[1], dk * grid.spacing[2]);
        const double length = ab.norm();
        for (const Vec3& shift : shifts) {
          if (length > 0.0) {
            traverseVoxels(local, centre + shift, ab / length, length, [&](Index c, double l, double) {
              const auto ijk = local.ijk(c);
              step_.push_back(std::int32_t((ijk[0] - reach_) + strideJ * (ijk[1] - reach_) +
                                           strideK * (ijk[2] - reach_)));
              length_.push_back(float(l));
              return true;
            });
          }
          if (step_.size() > std::numeric_limits<std::uint32_t>::max()) {
            throw Error("lattice lines: too many crossings for 32-bit offsets");
          }
          start_.push_back(std::uint32_t(step_.size()));
        }
      }
    }
  }
}

} // namespace volrad
