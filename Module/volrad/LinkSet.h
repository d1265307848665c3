// SPDX-License-Identifier: BSD-3-Clause
/// @file LinkSet.h
/// @brief The links of the hierarchical solver: which pairs of cluster-tree
/// nodes exchange light directly, found by error-driven refinement from the
/// roots (Hanrahan et al. 1991 "BF refinement", Sillion 1995 clusters), and
/// how they carry it.
///
/// A link between nodes A and B stands for the exchange areas between all
/// their elements, S(A, B) ~ sigma_A(w) sigma_B(-w) gamma. A voxel end is
/// its centre: the line is marched from there, times its exact far-field
/// factor kappa V prod sinh(z_a)/z_a / sigma, z_a = kappa h_a w_a / 2. A
/// cluster end shows what its sides facing the other end let out
/// (ClusterTree::sigmaTowards: its voxels seen through the ones in front),
/// measured at the plane normal to w through its box's foremost corner, so
/// the line is marched from that plane on, times what the light loses
/// between its sides and that plane (ClusterTree::frontFactor, at the
/// extinction of the line's next radius beyond it), and gamma takes the mean
/// of 1/r^2 and of the line's transmittance over the lines between the boxes
/// each end's light comes from (its surface when it is thick); tau marched
/// in the voxel pyramid within a tolerance. sigma(w) of a patch node is its
/// area times the cosine towards the other end. Front sides inside clusters
/// emit and receive through an order-1 spherical-harmonic mask (exact at
/// voxels).
///
/// Refinement: the pair (A, B) is linked when their voxel boxes are more
/// than the near-field radius apart and the power the link may carry wrongly,
///   max(x_A, x_B) S(A, B) err(A, B),
/// is at most `tolerance` times the scene's total power; otherwise the
/// larger node is split. err is the link's relative error estimate: the
/// spread of 1/r^2 over the two nodes ((rho_A^2 + rho_B^2) / r^2), the
/// heterogeneity of the medium between them (the width of the pyramid's
/// optical-depth bounds at the link's level) and the optical size of each
/// cluster ((kappa_t rho)^2 / 4). x is each node's largest radiosity; in
/// S, empty voxels count with LinkRefinement::viewSigma.
/// Pairs closer than that at the voxels are left to the near field.
#pragma once

#include "volrad/ClusterTree.h"
#include "volrad/LatticeLines.h"
#include "volrad/Progress.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

namespace volrad {

struct LinkRefinement
{
  int nearRadius = 1;
  double tolerance = 1e-4;      ///< relative to powerScale
  double powerScale = 1.0;      ///< total power leaving all elements [W]
  std::vector<float> radiosity; ///< per tree node, the largest radiosity under it
  /// Optical-depth error of tau along a voxel link; a cluster link's line
  /// may take what its oracle left unspent (up to 0.25), never less than this.
  double depthTolerance = 0.01;
  /// Cross-section an empty voxel counts with in the error estimate, so that
  /// the views of empty space (their G) are refined like a typical voxel's.
  double viewSigma = 0.0;
  /// Per tree node without medium: the least direct incident radiation
  /// (from the lights, exact) of its voxels times viewSigma per voxel, the
  /// direct power it would intercept, relative to powerScale; empty: not
  /// used. A view (a link with an end without medium) is also fine enough
  /// when the power it may carry wrongly is under viewTolerance of this:
  /// it changes only that end's G, whose direct part is already exact.
  std::vector<float> viewLight;
  double viewTolerance = 0.0;
  /// Links with an end that holds no medium (its views only) are left out:
  /// a sparse solve, where empty space costs no links. The others are the
  /// same links as with them.
  bool emptyViews = true;
  /// Refinement stops with volrad::Error past this many links (0: no limit).
  std::size_t maxLinks = 0;
};

/// Peak bytes one link costs while links are refined and stored (measured
/// 10-14 on the benchmark scenes at 32^3-64^3 with 12-byte accepted links,
/// the whole solve's peak less what it needs without links, per link; 2-3
/// fewer with PackedLink where the rows' writing is the peak, as many where
/// the candidates are, such as the smoke at full size; the margin keeps the
/// budget check from letting an out-of-memory crash through).
constexpr std::size_t kBytesPerLink = 20;

/// An allocator whose resize leaves new elements uninitialised, so that a
/// large array's pages are only faulted in where it is written.
template<class T>
struct UninitialisedAllocator : std::allocator<T>
{
  template<class U>
  struct rebind
  {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template<class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept
  {
  }
  template<class U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template<class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// gamma in 16 bits: the top 10 bits of its mantissa, rounded to nearest
/// (at most 2^-11 = 0.05% off, far below the error a link is refined to),
/// and 6 bits of exponent counted from `base` (a double's biased exponent):
/// 2^62 from the largest gamma of a set down to the smallest kept; below,
/// code 0 is 0. Monotone, so codes order as the values do.
struct GammaCode
{
  std::int64_t base = 0;

  /// The base for gammas up to `largest` (> 0).
  static GammaCode forLargest(double largest);
  std::uint16_t encode(double gamma) const;
  double decode(std::uint16_t code) const
  {
    const std::uint64_t bits = (std::uint64_t((code >> 10) + base) << 52) |
                               (std::uint64_t(code & 0x3ffu) << 42);
    double g;
    std::memcpy(&g, &bits, sizeof g);
    return code == 0 ? 0.0 : g;
  }
};

/// Links by receiving node, each row ordered by source. A source is stored
/// as its step from the row's previous source (the first from -1) in 16 bits
/// and gamma in 16 (GammaCode): 4 bytes a link direction instead of 8, since
/// the rows are most of the solver's memory, and the far field streams
/// through them at every iteration. A step of kFarStep or more is stored as
/// kFarStep and its source in farSource (rare: jumps between levels, z slabs
/// of grids past 256^2 voxels a slab).
struct LinkSet
{
  static constexpr std::uint16_t kFarStep = 0xffff;
  /// Per receiving node, the links into it: [start[b], start[b + 1]).
  std::vector<Index> start;
  std::vector<std::uint16_t, UninitialisedAllocator<std::uint16_t>> step;
  std::vector<std::uint16_t, UninitialisedAllocator<std::uint16_t>> gamma; ///< tau / (pi r^2), as above
  GammaCode code;                       ///< how gamma is stored
  std::vector<std::int32_t> farSource;  ///< the sources of far steps, in order
  std::vector<std::uint32_t> farStart;  ///< per node, its first in farSource
  long long pairs = 0;                  ///< links (each serves both directions)
  std::vector<long long> pairsPerLevel; ///< by the finer end's level

  /// f(source, gamma) for the links into node b, in the order of sources.
  template<class F>
  void forEachInto(Index b, F&& f) const
  {
    std::int64_t a = -1;
    std::uint32_t far = farStart[b];
    for (Index k = start[b]; k < start[b + 1]; ++k) {
      const std::uint16_t s = step[k];
      a = s == kFarStep ? std::int64_t(farSource[far++]) : a + s;
      f(Index(a), code.decode(gamma[k]));
    }
  }

  std::size_t bytes() const
  {
    return start.size() * sizeof(Index) + step.size() * 2 * sizeof(std::uint16_t) +
           (farSource.size() + farStart.size()) * sizeof(std::int32_t);
  }
};

/// An accepted link (by its lower end), or a direction of one waiting for
/// its row (by its receiver), in 8 bytes instead of two indices and a float's
/// 12: the accepted links are the refinement's peak memory. LinkPacking
/// says how.
struct PackedLink
{
  std::uint64_t bits;
};

/// PackedLink's fields: the row's node as its offset in its slice (or in a
/// piece of it), the other node, then the top bits of gamma's (positive)
/// float, at least 19 of them: its 8 exponent bits and 11 of mantissa, all
/// that GammaCode's rounding to 10 reads, so the rows are those of whole
/// floats. The slices, a power of two from kFewestSlices, are more in trees
/// too large for that.
struct LinkPacking
{
  /// The rows are written a slice at a time through a full 32-bit copy of
  /// the slice's rows (refineLinks): with 64 slices, not 16, that copy took
  /// 76 MiB off the peak of the smoke's full-size solve (82 M links), for
  /// the same rows. A slice whose rows hold more than 1/kFewestSlices of
  /// the entries (the clusters') is written in pieces of about that many.
  static constexpr int kFewestSlices = 64;

  explicit LinkPacking(Index nodes)
  {
    nodeBits = bitsFor(nodes);
    for (slices = kFewestSlices;; slices *= 2) {
      sliceSize = (nodes + slices - 1) / slices;
      offsetBits = bitsFor(sliceSize);
      gammaBits = std::min(31, 64 - offsetBits - nodeBits);
      if (gammaBits >= 19) {
        break;
      }
    }
  }
  static int bitsFor(Index count) // bits to hold 0 .. count - 1
  {
    int b = 0;
    while ((Index(1) << b) < count) {
      ++b;
    }
    return b;
  }
  int sliceOf(Index n) const { return int(n / sliceSize); }
  /// `slice` is sliceOf(row), which the caller has already (no division here).
  PackedLink pack(Index row, int slice, Index other, float gamma) const
  {
    return packFrom(Index(slice) * sliceSize, row, other, gamma);
  }
  Index row(const PackedLink& x, int slice) const { return rowFrom(Index(slice) * sliceSize, x); }
  /// The same with the row as its offset from `first`, a node at most
  /// sliceSize - 1 before it (a part of a slice).
  PackedLink packFrom(Index first, Index row, Index other, float gamma) const
  {
    std::uint32_t g;
    std::memcpy(&g, &gamma, sizeof g);
    return { std::uint64_t(row - first) | (std::uint64_t(other) << offsetBits) |
             (std::uint64_t(g >> (31 - gammaBits)) << (offsetBits + nodeBits)) };
  }
  Index rowFrom(Index first, const PackedLink& x) const
  {
    return first + Index(x.bits & ((std::uint64_t(1) << offsetBits) - 1));
  }
  Index other(const PackedLink& x) const
  {
    return Index((x.bits >> offsetBits) & ((std::uint64_t(1) << nodeBits) - 1));
  }
  float gamma(const PackedLink& x) const
  {
    const std::uint32_t g = std::uint32_t(x.bits >> (offsetBits + nodeBits)) << (31 - gammaBits);
    float f;
    std::memcpy(&f, &g, sizeof f);
    return f;
  }

  int slices = kFewestSlices;
  Index sliceSize = 1;
  int offsetBits = 0, nodeBits = 0, gammaBits = 31;
};

/// gamma of a link (see above); between two voxels that `centreLines` (if
/// given) covers, with the exact depth of the line between their centres.
double linkGamma(const ClusterTree& tree,
                 Index a,
                 Index b,
                 double depthTolerance,
                 const LatticeLines* centreLines = nullptr);

LinkSet refineLinks(const ClusterTree& tree,
                    const LinkRefinement& refinement,
                    const ProgressRange& progress = ProgressRange());

} // namespace volrad
