// SPDX-License-Identifier: BSD-3-Clause
/// @file LatticeLines.h
/// @brief The voxels that lines between two voxels cross, by the voxels'
/// lattice offset. A line from a point of one voxel to the same point of
/// another (shifted alike from both centres) crosses the same voxels, for
/// the same lengths, relative to its start wherever the pair lies: the walks
/// are made once per offset, and a link between voxels sums its crossed
/// voxels' extinction instead of walking the grid (most of the optical
/// depths the link refinement computed were these lines between voxels a
/// few to a few tens apart).
#pragma once

#include "volrad/Grid.h"

#include <cstdint>
#include <cstdlib>
#include <vector>

namespace volrad {

class LatticeLines
{
public:
  /// The lines through `shifts` (from each voxel's centre) between voxels
  /// up to `reach` apart along each axis (at most the grid's largest
  /// extent less one), for voxels of `grid` (its spacing and index strides).
  LatticeLines(const Grid& grid, int reach, const std::vector<Vec3>& shifts);

  /// Whether voxels (di, dj, dk) apart are in the table.
  bool covers(int di, int dj, int dk) const
  {
    return std::abs(di) <= reach_ && std::abs(dj) <= reach_ && std::abs(dk) <= reach_;
  }

  /// Optical depth of line `line` (an index into the shifts) from voxel
  /// `from` to the voxel (di, dj, dk) from it (covered; both in the grid),
  /// kappa(voxel) its extinction: the crossed voxels' sum, in the order the
  /// walk met them.
  template<class Kappa>
  double depth(Kappa&& kappa, Index from, int di, int dj, int dk, int line) const
  {
    const int w = 2 * reach_ + 1;
    const std::size_t l =
      std::size_t((di + reach_) + w * ((dj + reach_) + w * (dk + reach_))) * lines_ + line;
    double d = 0.0;
    for (std::uint32_t k = start_[l]; k < start_[l + 1]; ++k) {
      d += kappa(from + step_[k]) * double(length_[k]);
    }
    return d;
  }

private:
  int reach_ = 0;
  int lines_ = 0;
  std::vector<std::uint32_t> start_; ///< per offset and line, into step_ and length_
  std::vector<std::int32_t> step_;   ///< the crossed voxel's index less the start voxel's
  std::vector<float> length_;        ///< the length the line spends in it
};

} // namespace volrad
