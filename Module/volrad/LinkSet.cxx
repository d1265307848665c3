// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/LinkSet.h"

#include "volrad/LatticeLines.h"
#include "volrad/Error.h"
#include "volrad/Sampling.h"
#include "volrad/VoxelGain.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif
#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

namespace volrad {

namespace {

// Node indices in 32 bits (refineLinks checks the tree's size): candidates
// and accepted links are most of the refinement's peak memory.
struct Pair
{
  std::int32_t a, b;
};

/// sigma of a node towards direction w (pointing away from it), for the
/// error estimate: empty voxels count with viewSigma each, since their views
/// (G of empty space) come from the same links.
double directedSigma(const ClusterTree& t,
                     Index n,
                     const ClusterTree::Box& box,
                     const Vec3& w,
                     double viewSigma)
{
  if (!t.isPatch(n)) {
    const auto e = box.extent();
    const double voxels = double(e[0]) * e[1] * e[2];
    return std::max(t.sigma(n), viewSigma * voxels);
  }
  return t.sigma(n) * std::max(0.0, faceInwardNormal(t.face(n)).dot(w));
}

/// Distance from c, inside node n's box (box), along the unit w to the
/// box's boundary (0 for patch nodes, which have no inside).
double exitDistance(const ClusterTree& t,
                    Index n,
                    const ClusterTree::Box& box,
                    const Vec3& c,
                    const Vec3& w)
{
  if (t.isPatch(n)) {
    return 0.0;
  }
  Vec3 lo, hi;
  t.spaceBox(box, lo, hi);
  double d = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (w[a] != 0.0) {
      d = std::min(d, ((w[a] > 0.0 ? hi[a] : lo[a]) - c[a]) / w[a]);
    }
  }
  return std::max(0.0, d);
}

/// The part of a line's optical depth from p, inside leaf n, along the unit
/// w to n's boundary (0 for patches).
double insideDepth(const ClusterTree& t, Index n, const Vec3& p, const Vec3& w)
{
  return t.isPatch(n) ? 0.0 : t.meanKappaT(n) * exitDistance(t, n, t.box(n), p, w);
}

/// The share of voxel leaf n's extinction that the medium just past the
/// faces it shows towards w has: the voxels across them, weighted by the
/// faces' projected areas (nothing past the grid's edge), at most 1.
double outsideShare(const ClusterTree& t, Index n, const Vec3& w)
{
  const double kappa = t.meanKappaT(n);
  const Grid& g = t.grid(0);
  const auto ijk = g.ijk(n);
  double sum = 0.0, area = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (w[a] == 0.0) {
      continue;
    }
    const double face = std::abs(w[a]) * g.spacing[(a + 1) % 3] * g.spacing[(a + 2) % 3];
    auto q = ijk;
    q[a] += w[a] > 0.0 ? 1 : -1;
    area += face;
    if (q[a] >= 0 && q[a] < g.dims[a]) {
      sum += face * t.pyramid().meanKappaT(0, g.index(q[0], q[1], q[2]));
    }
  }
  return area > 0.0 && kappa > 0.0 ? std::min(1.0, sum / (area * kappa)) : 1.0;
}

/// A leaf as the end of a link towards w.
struct LeafEnd
{
  /// log of what the leaf collides with or emits towards w relative to its
  /// cross-section, per unit of the transmittance of the line from its
  /// centre: log(kappa V / sigma) plus the voxel's gain (VoxelGain.h) for
  /// the medium outside it. 0 for patches.
  double logFactor = 0.0;
  /// How much an off-centre line's own depth inside the voxel counts, the
  /// rest being the centre line's (depthFromCentres): the gain's share of
  /// the medium outside, less in thick voxels (leafEnd). 1 for patches,
  /// which have no inside, and unless asked for.
  double lineShare = 1.0;
  /// The centre line's depth inside the voxel towards w (when lineShare is
  /// asked for; 0 for patches).
  double centreDepth = 0.0;
};

/// The end towards w of a link from leaf n; lines: whether its lineShare is
/// wanted (only links marched along other lines than the centres' need it).
LeafEnd leafEnd(const ClusterTree& t, Index n, const Vec3& w, bool lines = false)
{
  LeafEnd e;
  const double sigma = t.sigma(n), kappa = t.meanKappaT(n);
  if (t.isPatch(n) || !(sigma > 0.0) || !(kappa > 0.0)) {
    return e;
  }
  const Grid& g = t.grid(0);
  const double share = outsideShare(t, n, w);
  e.logFactor = std::log(kappa * g.voxelVolume() / sigma) + logVoxelGain(kappa, share, g.spacing, w);
  if (lines) {
    // The neighbours' extinction is a coarse guess of the medium outside:
    // an error d in the share scales a Gauss line's light by up to
    // exp(0.6 d D), D the centre line's depth inside the voxel, which in
    // thick voxels (bone: tens of optical depths) made near-field rows sum
    // above 1 and the shooting diverge. So lines count the share less as D
    // grows, by exp(-(D/2)^2) (BenchAccuracy's scenes, D below 1, as with
    // the share).
    e.centreDepth = insideDepth(t, n, t.centroid(n), w);
    const double half = 0.5 * e.centreDepth;
    e.lineShare = share * std::exp(-half * half);
  }
  return e;
}

/// The optical depth `depth` of a line from pa in leaf a to pb in leaf b,
/// parallel to the line between their centres (w from a to b), with each
/// end's own part as its gain is relative to: with the same medium outside
/// (lineShare 1) the line's own part, as marched (the depth is linear, and
/// the gain is the same from any point); with nothing outside, the centre
/// line's (else an off-centre Gauss point would count its voxel's light as
/// less attenuated twice: e^{kappa h / 4} and more a side).
double depthFromCentres(const ClusterTree& t,
                        Index a,
                        Index b,
                        const Vec3& pa,
                        const Vec3& pb,
                        const Vec3& w,
                        double depth,
                        const LeafEnd& ea,
                        const LeafEnd& eb)
{
  // (A line's own part counts whole at lineShare 1: no box to intersect.)
  const double offA = ea.lineShare < 1.0 ? insideDepth(t, a, pa, w) - ea.centreDepth : 0.0;
  const double offB = eb.lineShare < 1.0 ? insideDepth(t, b, pb, -w) - eb.centreDepth : 0.0;
  return std::max(0.0, depth - (1.0 - ea.lineShare) * offA - (1.0 - eb.lineShare) * offB);
}

/// A voxel end's factor exceeds its own attenuation by kappa h / 2 at most;
/// past this a line's depth is so large that nothing arrives anyway.
constexpr double kMaxLogGain = 50.0;

/// How far along the unit w from c the plane normal to w through node n's
/// foremost corner lies: there every line parallel to w has left the box
/// (what its light loses on the way is ClusterTree::frontFactor). 0 for
/// patches.
double frontPlane(const ClusterTree& t, Index n, const Vec3& c, const Vec3& w)
{
  if (t.isPatch(n)) {
    return 0.0;
  }
  Vec3 lo, hi;
  t.spaceBox(n, lo, hi);
  double d = 0.0;
  for (int a = 0; a < 3; ++a) {
    d += ((w[a] > 0.0 ? hi[a] : lo[a]) - c[a]) * w[a];
  }
  return std::max(0.0, d);
}

/// Mean over the lines between the boxes the two ends' light towards each
/// other comes from (ClusterTree::emissionBox; thick clusters: their facing
/// surfaces), 2x2x2 Gauss points in each, of exp(-depth (1/cos - 1)) / l^2:
/// 1/r^2 and the transmittance relative to the line between their centres
/// (depth), whose medium a line at an angle to it crosses for 1/cos longer.
/// w from a to b.
double meanSpread(const ClusterTree& t, Index a, Index b, const Vec3& w, double depth)
{
  Vec3 ca, ha, cb, hb;
  t.emissionBox(a, w, ca, ha);
  t.emissionBox(b, -w, cb, hb);
  const double q = 1.0 / std::sqrt(3.0);
  const int na = ha.isZero() ? 1 : 8, nb = hb.isZero() ? 1 : 8;
  auto point = [q](const Vec3& c, const Vec3& h, int k) {
    return Vec3(c[0] + (k & 1 ? q : -q) * h[0],
                c[1] + (k & 2 ? q : -q) * h[1],
                c[2] + (k & 4 ? q : -q) * h[2]);
  };
  const Vec3 axis = (cb - ca).normalized();
  double sum = 0.0;
  for (int i = 0; i < na; ++i) {
    const Vec3 p = point(ca, ha, i);
    for (int j = 0; j < nb; ++j) {
      const Vec3 d = point(cb, hb, j) - p;
      const double l2 = d.squaredNorm(), along = std::abs(d.dot(axis));
      if (depth == 0.0) {
        sum += 1.0 / l2; // nothing between (air around a scan): no exp to take
        continue;
      }
      // An oblique line crosses the medium between for 1/cos longer.
      const double stretch = along > 0.0 ? std::sqrt(l2) / along : 1.0;
      sum += std::exp(-std::min(depth * (stretch - 1.0), kMaxLogGain)) / l2;
    }
  }
  return sum / (na * nb);
}

/// Mean of d^2 / |x - y|^2 over two voxels whose centres are d apart, by
/// offset (|di|, |dj|, |dk|) up to kCorrectedReach: the point-to-point 1/r^2
/// of a link between two voxels is this much too small (about 4% two voxels
/// apart). Gauss-Legendre, 4 points per axis in each voxel.
constexpr int kCorrectedReach = 4;

struct SpreadCorrection
{
  double factor[kCorrectedReach + 1][kCorrectedReach + 1][kCorrectedReach + 1];

  explicit SpreadCorrection(const Vec3& h)
  {
    const double gx[4] = {
      -0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526
    };
    const double gw[4] = {
      0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538
    };
    // Differences of two points, one per voxel, along one axis: their
    // weights multiply; sum over the 4x4 pairs per axis.
    double diff[16], weight[16];
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        diff[4 * a + b] = 0.5 * (gx[a] - gx[b]);
        weight[4 * a + b] = 0.25 * gw[a] * gw[b];
      }
    }
    for (int i = 0; i <= kCorrectedReach; ++i) {
      for (int j = 0; j <= kCorrectedReach; ++j) {
        for (int k = 0; k <= kCorrectedReach; ++k) {
          const Vec3 d(i * h[0], j * h[1], k * h[2]);
          const double d2 = d.squaredNorm();
          double sum = 0.0;
          for (int a = 0; a < 16 && d2 > 0.0; ++a) {
            for (int b = 0; b < 16; ++b) {
              for (int c = 0; c < 16; ++c) {
                const Vec3 r = d + Vec3(diff[a] * h[0], diff[b] * h[1], diff[c] * h[2]);
                sum += weight[a] * weight[b] * weight[c] * d2 / r.squaredNorm();
              }
            }
          }
          factor[i][j][k] = d2 > 0.0 ? sum : 1.0;
        }
      }
    }
  }
  double operator()(const std::array<int, 3>& a, const std::array<int, 3>& b) const
  {
    const int i = std::abs(a[0] - b[0]), j = std::abs(a[1] - b[1]), k = std::abs(a[2] - b[2]);
    if (i > kCorrectedReach || j > kCorrectedReach || k > kCorrectedReach) {
      return 1.0;
    }
    return factor[i][j][k];
  }
};

/// Half the distance between 2-point Gauss-Legendre points, per unit width.
const double kGaussHalf = 0.5 / std::sqrt(3.0);

/// Gauss point k (of 8) of a voxel of spacing h, from its centre.
Vec3 gaussShift(const Vec3& h, int k)
{
  const double q = kGaussHalf;
  return Vec3((k & 1 ? q : -q) * h[0], (k & 2 ? q : -q) * h[1], (k & 4 ? q : -q) * h[2]);
}

/// The lines of closeLeafGamma, as LatticeLines' shifts: from each of a
/// voxel's Gauss points to the same point of the other voxel, then between
/// the centres.
constexpr int kCentreLine = 8;
std::vector<Vec3> closeLineShifts(const Vec3& h)
{
  std::vector<Vec3> s;
  for (int k = 0; k < 8; ++k) {
    s.push_back(gaussShift(h, k));
  }
  s.push_back(Vec3::Zero());
  return s;
}

/// Voxel links up to this many voxels apart along each axis take their
/// centre line's optical depth from LatticeLines, exact, instead of an
/// adaptive march (most voxel links are fewer than 16 voxels apart: past
/// that their parents are linked).
constexpr int kLatticeLineReach = 16;

/// The coarsest optical-depth tolerance a cluster link's line is marched to
/// when the oracle leaves it slack (BenchAccuracy's G the same as with 0.01
/// on every link).
constexpr double kMaxLinkDepthError = 0.25;

/// 2-point Gauss-Legendre points of a leaf: 8 in a voxel, 4 on a patch.
int leafPoints(const ClusterTree& t, Index n, std::array<Vec3, 8>& out)
{
  const Grid& g = t.grid(0);
  const double q = kGaussHalf;
  const Vec3 c = t.centroid(n);
  if (!t.isPatch(n)) {
    for (int k = 0; k < 8; ++k) {
      out[k] = c + gaussShift(g.spacing, k);
    }
    return 8;
  }
  const auto ax = faceAxesInPlane(t.face(n));
  for (int k = 0; k < 4; ++k) {
    out[k] = c;
    out[k][ax[0]] += (k & 1 ? q : -q) * g.spacing[ax[0]];
    out[k][ax[1]] += (k & 2 ? q : -q) * g.spacing[ax[1]];
  }
  return 4;
}

/// Whether the box spanning voxels a and b holds one extinction: checked on
/// the pyramid's cells of the level where it spans at most two per axis.
bool homogeneousBetween(const VoxelPyramid& p,
                        const std::array<int, 3>& a,
                        const std::array<int, 3>& b)
{
  std::array<int, 3> lo, hi;
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(a[k], b[k]);
    hi[k] = std::max(a[k], b[k]);
  }
  int l = 0;
  while (l + 1 < p.levels() &&
         ((hi[0] >> l) - (lo[0] >> l) > 1 || (hi[1] >> l) - (lo[1] >> l) > 1 ||
          (hi[2] >> l) - (lo[2] >> l) > 1)) {
    ++l;
  }
  const Grid& g = p.grid(l);
  const double first = p.minKappaT(l, g.index(lo[0] >> l, lo[1] >> l, lo[2] >> l));
  for (int i = lo[0] >> l; i <= hi[0] >> l; ++i) {
    for (int j = lo[1] >> l; j <= hi[1] >> l; ++j) {
      for (int k = lo[2] >> l; k <= hi[2] >> l; ++k) {
        const Index c = g.index(i, j, k);
        if (p.minKappaT(l, c) != first || p.maxKappaT(l, c) != first) {
          return false;
        }
      }
    }
  }
  return true;
}

/// gamma of a link between two leaves a few voxels apart, where neither the
/// medium between them nor the geometry is one line's: the transmittance
/// is averaged over parallel lines between the Gauss points of two voxels
/// (their 1/r^2 mean is the exact table's), and links with a patch
/// integrate cosines, 1/r^2 and transmittance over the Gauss points of both
/// ends, per unit of the centroids' cosines the gathering applies. Lines are
/// marched whole, each voxel end's factor (leafEnd) included.
double closeLeafGamma(const ClusterTree& t,
                      const LatticeLines& lines,
                      Index a,
                      Index b,
                      double spread)
{
  const Vec3 ca = t.centroid(a), cb = t.centroid(b);
  const double rc = (cb - ca).norm();
  const VoxelPyramid& pyramid = t.pyramid();
  if (!t.isPatch(a) && !t.isPatch(b)) {
    const Vec3 w = (cb - ca) / rc;
    const LeafEnd ea = leafEnd(t, a, w, true), eb = leafEnd(t, b, -w, true);
    const double ends = ea.logFactor + eb.logFactor;
    const auto ia = t.grid(0).ijk(a), ib = t.grid(0).ijk(b);
    const int di = ib[0] - ia[0], dj = ib[1] - ia[1], dk = ib[2] - ia[2];
    const auto kappa = [&](Index v) { return pyramid.meanKappaT(0, v); };
    if (homogeneousBetween(pyramid, ia, ib)) {
      // Every parallel line crosses the same medium: one is enough.
      const double depth = lines.depth(kappa, a, di, dj, dk, kCentreLine);
      return spread * std::exp(std::min(ends - depth, kMaxLogGain)) / (kPi * rc * rc);
    }
    double depth[8], least = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 8; ++k) {
      const Vec3 s = gaussShift(t.grid(0).spacing, k);
      depth[k] =
        depthFromCentres(t, a, b, ca + s, cb + s, w, lines.depth(kappa, a, di, dj, dk, k), ea, eb);
      least = std::min(least, depth[k]);
    }
    double tau = 0.0;
    for (int k = 0; k < 8; ++k) {
      tau += std::exp(least - depth[k]);
    }
    return spread * std::exp(std::min(ends - least, kMaxLogGain)) * tau / (8.0 * kPi * rc * rc);
  }
  std::array<Vec3, 8> pa, pb;
  const int na = leafPoints(t, a, pa), nb = leafPoints(t, b, pb);
  auto cosine = [&](Index n, const Vec3& w) {
    return t.isPatch(n) ? faceInwardNormal(t.face(n)).dot(w) : 1.0;
  };
  const Vec3 wc = (cb - ca) / rc;
  const double centre = cosine(a, wc) * cosine(b, -wc);
  if (!(centre > 0.0)) {
    return 0.0;
  }
  double sum = 0.0;
  for (int i = 0; i < na; ++i) {
    for (int j = 0; j < nb; ++j) {
      const Vec3 d = pb[j] - pa[i];
      const double r2 = d.squaredNorm();
      const Vec3 w = d / std::sqrt(r2);
      const double c = std::max(0.0, cosine(a, w)) * std::max(0.0, cosine(b, -w));
      if (c > 0.0) {
        const LeafEnd ea = leafEnd(t, a, w, true), eb = leafEnd(t, b, -w, true);
        const double ends = ea.logFactor + eb.logFactor;
        const double depth = depthFromCentres(
          t, a, b, pa[i], pb[j], w, pyramid.opticalDepth(pa[i], pb[j], 0).estimate, ea, eb);
        sum += c * std::exp(std::min(ends - depth, kMaxLogGain)) / (kPi * r2);
      }
    }
  }
  return sum / (double(na) * nb * centre);
}

/// A list of up to hundreds of millions of items, in chunks of 256 KiB:
/// unlike a vector it never copies itself to grow (seconds in one block,
/// which no stop request would interrupt), and as it is drained from the
/// front each chunk is freed whole, so its pages can go back to the system
/// (a deque's 512-byte blocks, interleaved with other lists', seldom free
/// a whole page).
template<class T>
class ChunkedList
{
  static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_copyable_v<T>,
                "chunks are left uninitialised until written");

public:
  std::size_t size() const { return size_; }
  const T& operator[](std::size_t i) const
  {
    const std::size_t k = head_ + i;
    return chunks_[k / kChunk][k % kChunk];
  }
  void push_back(const T& x)
  {
    const std::size_t k = head_ + size_;
    if (k == chunks_.size() * kChunk) {
      std::unique_ptr<T[]> chunk(new T[kChunk]); // default-initialised: untouched pages
      chunks_.push_back(std::move(chunk));
    }
    chunks_[k / kChunk][k % kChunk] = x;
    ++size_;
  }
  void pop_front()
  {
    --size_;
    if (size_ == 0) {
      chunks_.clear();
      head_ = 0;
    } else if (++head_ == kChunk) {
      chunks_.pop_front();
      head_ = 0;
    }
  }

private:
  static constexpr std::size_t kChunk = (std::size_t(1) << 18) / sizeof(T);
  std::deque<std::unique_ptr<T[]>> chunks_;
  std::size_t head_ = 0, size_ = 0;
};

/// Per-thread lists of candidates.
template<class T>
using ThreadLists = tbb::combinable<ChunkedList<T>>;

/// Accepted links are kept by the slice of nodes their lower end is in, so
/// that the rows can be written one slice of nodes at a time (refineLinks).
template<class T>
using Sliced = std::vector<ChunkedList<T>>;

/// The lists of a combinable, one per thread that used it.
template<class T>
std::vector<ChunkedList<T>*> partsOf(ThreadLists<T>& c)
{
  std::vector<ChunkedList<T>*> parts;
  c.combine_each([&](ChunkedList<T>& l) { parts.push_back(&l); });
  return parts;
}

/// f(x) for every item of `parts` in turn, in blocks between progress
/// reports: sequential passes over up to hundreds of millions of items.
/// Draining removes each item after f: the memory goes back chunk by chunk,
/// not in one long free at the end.
template<bool Drain, class T, class F>
void forEachInParts(const std::vector<ChunkedList<T>*>& parts, const ProgressRange& range, F&& f)
{
  std::int64_t total = 0;
  for (const auto* l : parts) {
    total += std::int64_t(l->size());
  }
  std::size_t part = 0, at = 0;
  range.forBlocks(
    total, std::int64_t(1) << 16, std::int64_t(1) << 22, [&](std::int64_t k0, std::int64_t k1) {
      for (std::int64_t k = k0; k < k1; ++k) {
        while (at == parts[part]->size()) {
          ++part;
          at = 0;
        }
        f((*parts[part])[at]);
        if (Drain) {
          parts[part]->pop_front();
        } else {
          ++at;
        }
      }
    });
}

/// f(item, part) for every item of `parts`, the parts in parallel (each by
/// one task at a time, in its order), in blocks between progress reports,
/// each block shared among the parts by what each has left: so f may run
/// for two parts at once. Draining as forEachInParts.
template<bool Drain, class T, class F>
void forEachInPartsInParallel(const std::vector<ChunkedList<T>*>& parts,
                              const ProgressRange& range,
                              F&& f)
{
  const std::size_t P = parts.size();
  std::vector<std::int64_t> size(P), done(P, 0), take(P);
  std::int64_t total = 0;
  for (std::size_t p = 0; p < P; ++p) {
    size[p] = std::int64_t(parts[p]->size());
    total += size[p];
  }
  range.forBlocks(
    total, std::int64_t(1) << 16, std::int64_t(1) << 22, [&](std::int64_t k0, std::int64_t k1) {
      const std::int64_t want = k1 - k0, left = total - k0;
      std::int64_t given = 0;
      for (std::size_t p = 0; p < P; ++p) {
        take[p] = want * (size[p] - done[p]) / left;
        given += take[p];
      }
      for (std::size_t p = 0; p < P && given < want; ++p) {
        const std::int64_t extra = std::min(size[p] - done[p] - take[p], want - given);
        take[p] += extra;
        given += extra;
      }
      tbb::parallel_for(std::size_t(0), P, [&](std::size_t p) {
        ChunkedList<T>& l = *parts[p];
        for (std::int64_t i = 0; i < take[p]; ++i) {
          if (Drain) {
            f(l[0], p);
            l.pop_front();
          } else {
            f(l[std::size_t(done[p] + i)], p);
          }
        }
        done[p] += take[p];
      });
    });
}

/// Hands the heap's free pages back to the system (glibc keeps them).
void releaseFreedMemory()
{
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

/// Gives the whole pages within [begin, end) of a live block back to the
/// system, which maps zeros there if they are touched again: for a large
/// array whose front is no longer read (a vector cannot shrink from the
/// front).
template<class T>
void releasePages(T* begin, T* end)
{
#ifdef __linux__
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) / page * page;
  const std::uintptr_t e = reinterpret_cast<std::uintptr_t>(end) / page * page;
  if (e > b) {
    madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED);
  }
#else
  (void)begin;
  (void)end;
#endif
}
constexpr std::size_t kReleaseBytes = std::size_t(8) << 20;

} // namespace

GammaCode GammaCode::forLargest(double largest)
{
  GammaCode c;
  if (largest > 0.0) {
    std::uint64_t bits;
    std::memcpy(&bits, &largest, sizeof bits);
    c.base = std::int64_t(bits >> 52) - 62; // the largest, rounded up, at exponent 63 at most
  }
  return c;
}

std::uint16_t GammaCode::encode(double gamma) const
{
  if (!(gamma > 0.0)) {
    return 0;
  }
  std::uint64_t bits;
  std::memcpy(&bits, &gamma, sizeof bits);
  bits += std::uint64_t(1) << 41; // to the nearest 10-bit mantissa (a carry raises the exponent)
  const std::int64_t e = std::int64_t(bits >> 52) - base;
  if (e < 1) {
    return 0; // below 2^-61 of the largest
  }
  if (e > 63) {
    return 0xffff; // past the largest this code was made for
  }
  return std::uint16_t((std::uint64_t(e) << 10) | ((bits >> 42) & 0x3ffu));
}

double linkGamma(const ClusterTree& tree,
                 Index a,
                 Index b,
                 double depthTolerance,
                 const LatticeLines* centreLines)
{
  const Vec3 ca = tree.centroid(a), cb = tree.centroid(b);
  const Vec3 ab = cb - ca;
  const double r = ab.norm();
  if (!(r > 0.0)) {
    return 0.0;
  }
  const Vec3 w = ab / r;
  // Voxel leaves: the whole line and their factor; clusters: from their
  // box, since what they let out of it their sides hold (ClusterTree).
  const double t0 = tree.isLeaf(a) ? 0.0 : frontPlane(tree, a, ca, w);
  const double t1 = r - (tree.isLeaf(b) ? 0.0 : frontPlane(tree, b, cb, -w));
  double depth = 0.0;
  const bool voxels = tree.isLeaf(a) && tree.isLeaf(b) && !tree.isPatch(a) && !tree.isPatch(b);
  const auto ia = tree.grid(0).ijk(voxels ? a : 0), ib = tree.grid(0).ijk(voxels ? b : 0);
  if (voxels && centreLines && centreLines->covers(ib[0] - ia[0], ib[1] - ia[1], ib[2] - ia[2])) {
    // Two voxels: the exact depth between their centres.
    const VoxelPyramid& p = tree.pyramid();
    depth = centreLines->depth(
      [&](Index v) { return p.meanKappaT(0, v); }, a, ib[0] - ia[0], ib[1] - ia[1], ib[2] - ia[2], 0);
  } else if (t1 > t0) {
    depth = tree.pyramid().opticalDepthAdaptive(ca + t0 * w, ca + t1 * w, depthTolerance).estimate;
  }
  const double ends = (tree.isLeaf(a) ? leafEnd(tree, a, w).logFactor : 0.0) +
                      (tree.isLeaf(b) ? leafEnd(tree, b, -w).logFactor : 0.0);
  // The medium beside a cluster's sides, which its light crosses before all
  // of it has passed the box's foremost corner: the next radius of the line.
  auto beside = [&](Index n, double from, double to) {
    if (tree.isLeaf(n)) {
      return 0.0;
    }
    const double d = std::min(tree.radius(n), std::abs(to - from));
    if (!(d > 0.0)) {
      return tree.meanKappaT(n);
    }
    const double s = from < to ? 1.0 : -1.0;
    return tree.pyramid()
             .opticalDepth(ca + from * w, ca + (from + s * d) * w, tree.level(n))
             .estimate /
           d;
  };
  return std::exp(std::min(ends - depth, kMaxLogGain)) * tree.frontFactor(a, w, beside(a, t0, t1)) *
         tree.frontFactor(b, -w, beside(b, t1, t0)) * meanSpread(tree, a, b, w, depth) / kPi;
}

LinkSet refineLinks(const ClusterTree& tree,
                    const LinkRefinement& opt,
                    const ProgressRange& progress)
{
  if (opt.radiosity.size() != std::size_t(tree.size())) {
    throw Error("link refinement needs one radiosity estimate per tree node");
  }
  if (tree.size() > Index(std::numeric_limits<std::int32_t>::max())) {
    throw Error("the cluster tree is too large for 32-bit link indices");
  }
  std::vector<Pair> todo;
  const auto roots = tree.roots();
  for (std::size_t i = 0; i < roots.size(); ++i) {
    for (std::size_t j = i; j < roots.size(); ++j) {
      todo.push_back({ std::int32_t(roots[i]), std::int32_t(roots[j]) });
    }
  }
  const double budget = opt.tolerance * opt.powerScale;
  const SpreadCorrection spread(tree.grid(0).spacing);
  const LatticeLines lines(tree.grid(0), kCorrectedReach + 1, closeLineShifts(tree.grid(0).spacing));
  const LatticeLines centreLines(tree.grid(0), kLatticeLineReach, { Vec3::Zero() });
  const LinkPacking packing(tree.size());
  tbb::combinable<Sliced<PackedLink>> accepted(
    [&] { return Sliced<PackedLink>(std::size_t(packing.slices)); });
  const Index sliceSize = packing.sliceSize;
  int round = 0;
  // Candidates are examined in blocks, with a progress report (and so a
  // chance to abort) after each; rounds past the ninth share the last tenth.
  while (!todo.empty()) {
    const ProgressRange roundRange =
      progress.sub(std::min(0.9, 0.1 * round), std::min(0.9, 0.1 * (round + 1)));
    ThreadLists<Pair> next;
    std::int64_t released = 0; // todo's candidates before this hold no memory
    roundRange.sub(0.0, 0.9).forBlocks(
      std::int64_t(todo.size()), 1024, 4096, [&](std::int64_t c0, std::int64_t c1) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(c0, c1, 256), [&](const auto& range) {
          auto& out = next.local();
          auto& keep = accepted.local();
          std::array<Index, 8> ka, kb;
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            const Index a = todo[k].a, b = todo[k].b;
            const bool pa = tree.isPatch(a), pb = tree.isPatch(b);
            if (pa && pb && tree.face(a) == tree.face(b)) {
              continue; // coplanar: they cannot see each other
            }
            if (a == b) { // a cluster with itself: its children with each other
              // (an empty one exchanges nothing within itself)
              const int n = pa || tree.sigma(a) > 0.0 ? tree.children(a, ka) : 0;
              for (int i = 0; i < n; ++i) {
                for (int j = i; j < n; ++j) {
                  out.push_back({ std::int32_t(ka[i]), std::int32_t(ka[j]) });
                }
              }
              continue;
            }
            const double sa = tree.sigma(a), sb = tree.sigma(b);
            if (sa <= 0.0 && sb <= 0.0) {
              continue; // two empty clusters exchange nothing
            }
            if (!opt.emptyViews && (sa <= 0.0 || sb <= 0.0)) {
              continue; // an empty end's views are not asked for
            }
            const bool leafA = tree.isLeaf(a), leafB = tree.isLeaf(b);
            const ClusterTree::Box boxA = tree.box(a), boxB = tree.box(b);
            const int gap = ClusterTree::gap(boxA, boxB);
            bool link = false;
            double gamma = 0.0;
            if (gap > opt.nearRadius) {
              if (leafA && leafB) {
                link = true;
                gamma = gap <= kCorrectedReach + 1
                          ? closeLeafGamma(
                              tree,
                              lines,
                              a,
                              b,
                              pa || pb ? 1.0 : spread(tree.grid(0).ijk(a), tree.grid(0).ijk(b)))
                          : linkGamma(tree, a, b, opt.depthTolerance, &centreLines);
              } else {
                const Vec3 ca = tree.centroid(a), cb = tree.centroid(b);
                const double r = (cb - ca).norm();
                const Vec3 w = (cb - ca) / r;
                const double ra = tree.radius(a, boxA), rb = tree.radius(b, boxB);
                const double geometric = (ra * ra + rb * rb) / (r * r);
                const double ka_ = tree.meanKappaT(a) * ra, kb_ = tree.meanKappaT(b) * rb;
                const double size = std::min(1.0, 0.25 * (ka_ * ka_ + kb_ * kb_));
                const double x = std::max(opt.radiosity[a], opt.radiosity[b]);
                const double sigmas = directedSigma(tree, a, boxA, w, opt.viewSigma) *
                                      directedSigma(tree, b, boxB, -w, opt.viewSigma);
                double allowed = budget;
                if ((sa <= 0.0 || sb <= 0.0) && !opt.viewLight.empty()) {
                  const Index view = sa <= 0.0 ? a : b;
                  allowed = std::max(allowed, opt.viewTolerance * double(opt.viewLight[view]));
                }
                // Fine enough whatever the medium between (depthErr <= 1,
                // exp(-between) <= 1; x, sigmas >= 0, and rounding is
                // monotone): the oracle's march would not change the answer,
                // nor the line's tolerance (depthErr + slack >= 1 below, to
                // rounding, far above kMaxLinkDepthError), so such links skip
                // the march.
                const double errAtMost = std::min(1.0, geometric) + 1.0 + size;
                if (x * (sigmas / (kPi * r * r)) * errAtMost <= allowed) {
                  link = true;
                  gamma =
                    linkGamma(tree, a, b, std::max(opt.depthTolerance, kMaxLinkDepthError));
                } else {
                  const int level = std::max(tree.level(a), tree.level(b));
                  // The size of the exchange the link may get wrong is
                  // attenuated only by the medium between the two boxes
                  // (between t0 and t1 on the centroid line), since the
                  // line's depth inside a cluster can hide its lit surface
                  // entirely.
                  const double t0 = exitDistance(tree, a, boxA, ca, w),
                               t1 = r - exitDistance(tree, b, boxB, cb, -w);
                  double between = 0.0;
                  const VoxelPyramid::Depth d =
                    tree.pyramid().opticalDepth(ca, cb, level, t0, t1, between);
                  const double depthErr = std::min(1.0, 0.5 * (d.upper - d.lower));
                  const double err = std::min(1.0, geometric) + depthErr + size;
                  const double S = sigmas * std::exp(-between) / (kPi * r * r);
                  link = x * S * err <= allowed;
                  if (link) {
                    // The oracle has charged this link depthErr for its
                    // depth and left allowed / (x S) - err unspent: the
                    // line's depth need be no finer than both together.
                    const double slack = x * S > 0.0 ? allowed / (x * S) - err : 1.0;
                    gamma = linkGamma(
                      tree,
                      a,
                      b,
                      std::max(opt.depthTolerance, std::min(kMaxLinkDepthError, depthErr + slack)));
                  }
                }
              }
            } else if (leafA && leafB) {
              continue; // the near field holds this pair
            }
            if (link) {
              if (gamma > 0.0) {
                const Index lo = std::min(a, b), hi = std::max(a, b);
                const int slice = packing.sliceOf(lo);
                keep[slice].push_back(packing.pack(lo, slice, hi, float(gamma)));
              }
              continue;
            }
            // Split the larger node (a leaf cannot be split).
            const bool splitA =
              leafB || (!leafA && tree.radius(a, boxA) >= tree.radius(b, boxB));
            if (splitA) {
              const int n = tree.children(a, ka);
              for (int i = 0; i < n; ++i) {
                out.push_back({ std::int32_t(ka[i]), std::int32_t(b) });
              }
            } else {
              const int n = tree.children(b, kb);
              for (int i = 0; i < n; ++i) {
                out.push_back({ std::int32_t(a), std::int32_t(kb[i]) });
              }
            }
          }
        });
        // The examined candidates' pages go back to the system as the round
        // goes: a large round's candidates and the links it accepts were
        // the refinement's peak together.
        if (std::size_t(c1 - released) * sizeof(Pair) >= kReleaseBytes) {
          releasePages(todo.data() + released, todo.data() + c1);
          released = c1;
        }
      });
    // The next round's candidates, in one vector.
    const auto parts = partsOf(next);
    std::size_t candidates = 0;
    for (const auto* l : parts) {
      candidates += l->size();
    }
    std::vector<Pair>().swap(todo);
    todo.reserve(candidates);
    forEachInParts<true>(
      parts, roundRange.sub(0.9, 1.0), [&](const Pair& x) { todo.push_back(x); });
    next.clear();
    ++round;
    if (opt.maxLinks > 0) {
      std::size_t count = todo.size();
      accepted.combine_each([&](const Sliced<PackedLink>& lists) {
        for (const auto& l : lists) {
          count += l.size();
        }
      });
      if (count > opt.maxLinks) {
        throw Error("the hierarchical solve needs more than " + std::to_string(opt.maxLinks) +
                    " links, over its memory budget: raise solver.epsilon or the budget");
      }
    }
  }

  // Both directions of every link, grouped by receiver (a counting sort:
  // a comparison sort of tens of millions of links takes seconds and cannot
  // be interrupted), then each receiver's links ordered by source so that
  // the order does not depend on the threads.
  const int S = packing.slices;
  std::vector<std::vector<ChunkedList<PackedLink>*>> slices(S);
  accepted.combine_each([&](Sliced<PackedLink>& lists) {
    for (int j = 0; j < S; ++j) {
      slices[j].push_back(&lists[j]);
    }
  });
  LinkSet out;
  out.pairsPerLevel.assign(tree.levels(), 0);
  // Rows' lengths, counted by the threads at once (relaxed atomic counts,
  // which become the rows' write cursors below).
  std::vector<std::atomic<Index>> cursor(std::size_t(tree.size()));
  // One cache line each: the threads update theirs at every link, and two
  // tallies sharing a line made the counting bounce it between the cores.
  struct alignas(64) Tally
  {
    float largest = 0.f;
    long long pairs = 0;
    std::vector<long long> perLevel;
  };
  std::vector<Tally> tallies(slices[0].size()); // one per thread that accepted links
  for (auto& t : tallies) {
    t.perLevel.assign(tree.levels(), 0);
  }
  for (int j = 0; j < S; ++j) {
    const double p0 = 0.9 + 0.02 * j / S, p1 = 0.9 + 0.02 * (j + 1) / S;
    forEachInPartsInParallel<false>(
      slices[j], progress.sub(p0, p1), [&](const PackedLink& x, std::size_t part) {
        const Index a = packing.row(x, j), b = packing.other(x);
        Tally& t = tallies[part];
        t.largest = std::max(t.largest, packing.gamma(x));
        ++t.pairs;
        ++t.perLevel[std::min(tree.level(a), tree.level(b))];
        cursor[a].fetch_add(1, std::memory_order_relaxed);
        cursor[b].fetch_add(1, std::memory_order_relaxed);
      });
  }
  float largest = 0.f;
  for (const Tally& t : tallies) {
    largest = std::max(largest, t.largest);
    out.pairs += t.pairs;
    for (int l = 0; l < tree.levels(); ++l) {
      out.pairsPerLevel[l] += t.perLevel[l];
    }
  }
  out.start.assign(tree.size() + 1, 0);
  for (Index n = 0; n < tree.size(); ++n) {
    out.start[n + 1] = out.start[n] + cursor[n].load(std::memory_order_relaxed);
    cursor[n].store(out.start[n], std::memory_order_relaxed);
  }
  out.code = GammaCode::forLargest(largest);
  // The rows are written one piece of a slice of nodes at a time (below),
  // from the links whose lower end is in the slice, which are freed as they
  // go; the direction into a later piece waits in that piece's pending
  // list. Freed pages go back to the system, so that the accepted links and
  // the rows are not all resident at once. A piece's rows are filled in
  // full 32-bit form (by the threads at once, each thread's links in turn),
  // each then ordered by source (so that the order does not depend on the
  // threads), and stored as steps (LinkSet) in the final arrays, whose
  // pages are faulted in only where written.
  const Index total = out.start.back();
  out.step.resize(total);
  out.gamma.resize(total);
  out.farStart.assign(tree.size() + 1, 0);
  std::vector<std::int32_t, UninitialisedAllocator<std::int32_t>> rawSource;
  std::vector<float, UninitialisedAllocator<float>> rawGamma;
  Index pieceBegin = 0; // the current piece's first entry
  // Per part (thread) of the accepted links, in a cache line of its own: a
  // count shared by the threads was an atomic on one line at every entry.
  struct alignas(64) Written
  {
    std::int64_t entries = 0;
  };
  std::vector<Written> written(tallies.size());
  auto write = [&](Index into, Index from, float gamma, std::size_t part) {
    const Index k = cursor[into].fetch_add(1, std::memory_order_relaxed) - pieceBegin;
    rawSource[k] = std::int32_t(from);
    rawGamma[k] = gamma;
    if (++written[part].entries % (std::int64_t(1) << 18) == 0) {
      releaseFreedMemory();
    }
  };
  tbb::enumerable_thread_specific<std::vector<std::pair<std::int32_t, float>>> scratch;
  // The rows are written in pieces of about total / kFewestSlices entries:
  // each slice of nodes is cut where its rows hold more (the clusters'
  // slices: a coarse cluster has thousands of links, a voxel tens, and one
  // slice's 32-bit copy of the cloud's cluster rows at 128^3 was a third of
  // its solve's peak).
  std::vector<Index> pieceFirst; // each piece's first node, then tree.size()
  std::vector<int> firstPiece(std::size_t(S) + 1, 0); // per slice
  const Index pieceEntries = std::max<Index>(1, total / LinkPacking::kFewestSlices);
  for (int j = 0; j < S; ++j) {
    firstPiece[j] = int(pieceFirst.size());
    const Index n0 = std::min(tree.size(), j * sliceSize),
                n1 = std::min(tree.size(), (j + 1) * sliceSize);
    for (Index n = n0; n < n1; ++n) {
      if (n == n0 || out.start[n] - out.start[pieceFirst.back()] >= pieceEntries) {
        pieceFirst.push_back(n);
      }
    }
  }
  firstPiece[S] = int(pieceFirst.size());
  pieceFirst.push_back(tree.size());
  const int P = firstPiece[S];
  auto pieceOf = [&](Index n) {
    const int j = packing.sliceOf(n);
    if (firstPiece[j + 1] - firstPiece[j] == 1) {
      return firstPiece[j];
    }
    return int(std::upper_bound(pieceFirst.begin() + firstPiece[j],
                                pieceFirst.begin() + firstPiece[j + 1],
                                n) -
               pieceFirst.begin()) -
           1;
  };
  // By receiver's piece, per part (thread) of the accepted links: (receiver, source, gamma).
  std::vector<Sliced<PackedLink>> pending(tallies.size());
  // The same for the links of a slice in pieces, by their lower end's piece.
  std::vector<Sliced<PackedLink>> ahead(tallies.size());
  for (std::size_t p = 0; p < tallies.size(); ++p) {
    pending[p] = Sliced<PackedLink>(std::size_t(P));
    ahead[p] = Sliced<PackedLink>(std::size_t(P));
  }
  std::vector<std::uint32_t> farSteps; // per node of the piece
  for (int piece = 0; piece < P; ++piece) {
    const Index n0 = pieceFirst[piece], n1 = pieceFirst[piece + 1];
    const int j = packing.sliceOf(n0);
    pieceBegin = out.start[n0];
    decltype(rawSource)().swap(rawSource); // a new, untouched block each piece
    decltype(rawGamma)().swap(rawGamma);
    rawSource.resize(out.start[n1] - pieceBegin);
    rawGamma.resize(out.start[n1] - pieceBegin);
    const double p0 = 0.92 + 0.08 * piece / P, p1 = 0.92 + 0.08 * (piece + 1) / P;
    const double q1 = p0 + 0.4 * (p1 - p0), q2 = p0 + 0.6 * (p1 - p0);
    // The links whose lower end is in this piece: both directions now, or
    // the later one waits.
    auto place = [&](Index a, Index b, float gamma, std::size_t part) {
      write(a, b, gamma, part);
      const int later = b < n1 ? piece : pieceOf(b);
      if (later == piece) {
        write(b, a, gamma, part);
      } else {
        pending[part][later].push_back(packing.packFrom(pieceFirst[later], b, a, gamma));
      }
    };
    // Each part's list of this piece.
    auto ofPiece = [&](std::vector<Sliced<PackedLink>>& perPart) {
      std::vector<ChunkedList<PackedLink>*> lists;
      for (auto& p : perPart) {
        lists.push_back(&p[piece]);
      }
      return lists;
    };
    const bool whole = firstPiece[j + 1] - firstPiece[j] == 1; // the slice in one piece
    if (!whole && piece == firstPiece[j]) {
      // A slice in pieces: its links first go by their lower end's piece
      // (each still once: the rows of a slice of clusters hold more links
      // among themselves than one piece's, whose both directions waiting
      // at once were the peak of the cloud's rows at 128^3).
      forEachInPartsInParallel<true>(
        slices[j], progress.sub(p0, p0), [&](const PackedLink& x, std::size_t part) {
          const Index a = packing.row(x, j);
          const int q = pieceOf(a);
          ahead[part][q].push_back(
            packing.packFrom(pieceFirst[q], a, packing.other(x), packing.gamma(x)));
        });
    }
    // (A whole slice's first node is n0: its links' rows are rowFrom(n0, x).)
    forEachInPartsInParallel<true>(whole ? slices[j] : ofPiece(ahead),
                                   progress.sub(p0, q1),
                                   [&](const PackedLink& x, std::size_t part) {
                                     place(packing.rowFrom(n0, x),
                                           packing.other(x),
                                           packing.gamma(x),
                                           part);
                                   });
    forEachInPartsInParallel<true>(
      ofPiece(pending), progress.sub(q1, q2), [&](const PackedLink& x, std::size_t part) {
        write(packing.rowFrom(n0, x), packing.other(x), packing.gamma(x), part);
      });
    // The rows are uninitialised until written: every one must be full.
    for (Index n = n0; n < n1; ++n) {
      if (cursor[n].load(std::memory_order_relaxed) != out.start[n + 1]) {
        throw Error("link refinement: node " + std::to_string(n) + "'s row was not filled");
      }
    }
    farSteps.assign(std::size_t(n1 - n0), 0);
    const ProgressRange sortRange = progress.sub(q2, p1);
    sortRange.forBlocks(n1 - n0, 256, 4096, [&](std::int64_t b0, std::int64_t b1) {
      tbb::parallel_for(tbb::blocked_range<Index>(n0 + b0, n0 + b1, 8), [&](const auto& r) {
        auto& links = scratch.local();
        for (Index b = r.begin(); b != r.end(); ++b) {
          const Index k0 = out.start[b] - pieceBegin, k1 = out.start[b + 1] - pieceBegin;
          links.clear();
          for (Index k = k0; k < k1; ++k) {
            links.emplace_back(rawSource[k], rawGamma[k]);
          }
          std::sort(links.begin(), links.end());
          std::int64_t previous = -1;
          for (Index k = k0; k < k1; ++k) {
            const std::int32_t a = links[k - k0].first;
            rawSource[k] = a;
            const std::int64_t d = std::int64_t(a) - previous;
            if (d < LinkSet::kFarStep) {
              out.step[pieceBegin + k] = std::uint16_t(d);
            } else {
              out.step[pieceBegin + k] = LinkSet::kFarStep;
              ++farSteps[b - n0];
            }
            out.gamma[pieceBegin + k] = out.code.encode(links[k - k0].second);
            previous = a;
          }
        }
      });
    });
    // Far steps' sources, in order (few: one pass over the rows that have them).
    for (Index b = n0; b < n1; ++b) {
      if (out.farSource.size() > std::numeric_limits<std::uint32_t>::max()) {
        throw Error("link refinement: too many far steps for 32-bit row offsets");
      }
      out.farStart[b] = std::uint32_t(out.farSource.size());
      if (farSteps[b - n0] > 0) {
        for (Index k = out.start[b]; k < out.start[b + 1]; ++k) {
          if (out.step[k] == LinkSet::kFarStep) {
            out.farSource.push_back(rawSource[k - pieceBegin]);
          }
        }
      }
    }
  }
  out.farStart[tree.size()] = std::uint32_t(out.farSource.size());
  out.farSource.shrink_to_fit();
  accepted.clear();
  std::vector<std::atomic<Index>>().swap(cursor);
  decltype(rawSource)().swap(rawSource);
  decltype(rawGamma)().swap(rawGamma);
  releaseFreedMemory();
  progress.report(1.0);
  return out;
}

} // namespace volrad
