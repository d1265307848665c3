// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/NearField.h"

#include "volrad/Error.h"
#include "volrad/LineGathering.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace volrad {

namespace {

using namespace detail;

/// A near pair before it is a row entry: rows and columns in 32 bits
/// (elements and voxels are refused past that), 24 bytes instead of 32, since
/// a scan's front sides make tens of millions of them at once.
struct Triplet
{
  Triplet() = default;
  Triplet(Index r, Index c, double v)
    : row(NearField::Column(r))
    , col(NearField::Column(c))
    , value(v)
  {
  }
  NearField::Column row = 0, col = 0;
  double value = 0.0;
  bool mirrored = false; ///< (row, col) swapped to key an unordered pair
};

bool byRowThenColumn(const Triplet& a, const Triplet& b)
{
  return a.row != b.row ? a.row < b.row : a.col < b.col;
}

using TripletLists = tbb::combinable<std::vector<Triplet>>;

/// The threads' triplets in one vector, sorted (a thread-independent order,
/// so that the sums below are deterministic). Reserved whole first, each
/// thread's list freed once copied: no growing copy beside the lists.
std::vector<Triplet> gatherTriplets(TripletLists& lists)
{
  std::size_t total = 0;
  lists.combine_each([&](const std::vector<Triplet>& l) { total += l.size(); });
  std::vector<Triplet> all;
  all.reserve(total);
  lists.combine_each([&](std::vector<Triplet>& l) {
    all.insert(all.end(), l.begin(), l.end());
    std::vector<Triplet>().swap(l);
  });
  std::sort(all.begin(), all.end(), byRowThenColumn);
  return all;
}

/// Compressed rows from triplets sorted by row: row r is [start[r], start[r + 1]).
void toRows(const std::vector<Triplet>& t,
            Index rows,
            std::vector<Index>& start,
            std::vector<NearField::Column>& column,
            std::vector<float>& value)
{
  start.assign(rows + 1, 0);
  column.resize(t.size());
  value.resize(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    ++start[t[k].row + 1];
    column[k] = t[k].col;
    value[k] = float(t[k].value);
  }
  for (Index r = 0; r < rows; ++r) {
    start[r + 1] += start[r];
  }
}

/// Rows that are the same, up to a translation, for every voxel (or patch)
/// with the same medium around it and the same distances to the domain's
/// sides: its neighbourhood box, clipped to the domain, holds one extinction
/// and no front sides. Distances count up to r + 1 (then the box, cut
/// before the boundary, sees no patch). A patch's class is its voxel's and
/// its face.
struct RowClass
{
  double kappaT = 0.0;
  std::array<int, 7> place{}; // distances to the six sides, then the face (-1: a voxel row)
  bool operator<(const RowClass& o) const
  {
    return kappaT != o.kappaT ? kappaT < o.kappaT : place < o.place;
  }
};

/// v's row class, or false when its neighbourhood is not one medium.
bool rowClass(const Grid& g,
              const std::vector<double>& kt,
              const ExchangeElements& el,
              Index v,
              int r,
              int face,
              RowClass& out)
{
  const auto c = g.ijk(v);
  std::array<int, 3> lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, c[a] - r);
    hi[a] = std::min(g.dims[a] - 1, c[a] + r);
    out.place[2 * a] = std::min(c[a], r + 1);
    out.place[2 * a + 1] = std::min(g.dims[a] - 1 - c[a], r + 1);
  }
  out.place[6] = face;
  out.kappaT = kt[v];
  for (int k = lo[2]; k <= hi[2]; ++k) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const Index u = g.index(i, j, k);
        if (kt[u] != kt[v] || el.front[u] >= 0) {
          return false;
        }
      }
    }
  }
  return true;
}

/// The class index of a row of class k, its first row (`index`) becoming
/// the class's representative.
std::int32_t joinClass(std::map<RowClass, std::int32_t>& classes,
                       const RowClass& k,
                       Index index,
                       std::vector<Index>& representatives)
{
  const auto it = classes.emplace(k, std::int32_t(representatives.size())).first;
  if (it->second == std::int32_t(representatives.size())) {
    representatives.push_back(index);
  }
  return it->second;
}

/// A shared row's entry that is not a full side in the stencil: a patch
/// (its face; -1 for the full side of the voxel at `offset`, in a patch's
/// row), by its voxel's offset from the row's voxel.
struct ClassEntry
{
  int face;
  std::array<int, 3> offset;
  double value;
};

/// The element a class entry names for the row of voxel c.
Index classElement(const Grid& g,
                   const ExchangeElements& el,
                   const std::array<int, 3>& c,
                   const ClassEntry& x)
{
  const int i = c[0] + x.offset[0], j = c[1] + x.offset[1], k = c[2] + x.offset[2];
  if (x.face < 0) {
    return el.full[g.index(i, j, k)];
  }
  const Face f = static_cast<Face>(x.face);
  const auto ax = faceAxesInPlane(f);
  const std::array<int, 3> u{ i, j, k };
  return el.patchElement(g.patchIndex(f, u[ax[0]], u[ax[1]]));
}

/// An element's place relative to voxel c: its face (-1: a voxel's full
/// side) and its voxel's offset; none past the box of radius r (a sliver
/// from round-off).
using Place = std::pair<int, std::array<int, 3>>;
bool placeOfElement(const Grid& g,
                    const ExchangeElements& el,
                    int r,
                    Index e,
                    const std::array<int, 3>& c,
                    Place& out)
{
  const bool patch = el.isPatch(e);
  const auto u = g.ijk(patch ? g.patchVoxel(e - el.fullCount) : el.voxelOf[e]);
  out = { patch ? int(g.patchLocation(e - el.fullCount).face) : -1,
          { u[0] - c[0], u[1] - c[1], u[2] - c[2] } };
  return std::max({ std::abs(out.second[0]), std::abs(out.second[1]), std::abs(out.second[2]) }) <=
         r;
}

std::vector<ClassEntry> toEntries(const std::map<Place, double>& m)
{
  std::vector<ClassEntry> out;
  for (const auto& [place, value] : m) {
    out.push_back({ place.first, place.second, value });
  }
  return out;
}

double raysPerSurface(const QuadratureSettings& q, const Grid& g)
{
  const Vec3& h = g.spacing;
  const double surface = 2.0 * (h[0] * h[1] + h[1] * h[2] + h[0] * h[2]);
  return 6.0 * q.voxelPointsPerAxis * q.voxelPointsPerAxis * q.voxelDirections / surface;
}

} // namespace

float NearField::stencilEntry(const Grid& g, Index e, int o) const
{
  if (o >= offsetIndex(0, 0, 0)) {
    return entryTowards(e, -1, o);
  }
  const int w = 2 * radius + 1;
  const auto c = g.ijk(elements.voxelOf[e]);
  const int i = c[0] + o % w - radius, j = c[1] + (o / w) % w - radius,
            k = c[2] + o / (w * w) - radius;
  if (i < 0 || j < 0 || k < 0 || i >= g.dims[0] || j >= g.dims[1] || k >= g.dims[2]) {
    return 0.f;
  }
  const Index f = elements.full[g.index(i, j, k)];
  return f < 0 ? 0.f : entryTowards(e, f, o);
}

double NearField::diagonal(Index e) const
{
  if (e < elements.fullCount) {
    return stencil[std::size_t(e) * stencilHalf()];
  }
  for (Index k = extraStart[e]; k < extraStart[e + 1]; ++k) {
    if (extraColumn[k] == e) {
      return extraValue[k];
    }
  }
  return 0.0;
}

void NearField::apply(const Grid& g, const double* x, double* y, bool skipDiagonal) const
{
  const ExchangeElements& el = elements;
  const int r = radius, centre = offsetIndex(0, 0, 0);
  tbb::parallel_for(tbb::blocked_range<Index>(0, el.size(), 4096), [&](const auto& range) {
    for (Index e = range.begin(); e != range.end(); ++e) {
      double sum = 0.0;
      if (e < el.fullCount) {
        const Index v = el.voxelOf[e];
        const auto c = g.ijk(v);
        for (int dz = -r; dz <= r; ++dz) {
          if (c[2] + dz < 0 || c[2] + dz >= g.dims[2]) {
            continue;
          }
          for (int dy = -r; dy <= r; ++dy) {
            if (c[1] + dy < 0 || c[1] + dy >= g.dims[1]) {
              continue;
            }
            for (int dx = -r; dx <= r; ++dx) {
              if (c[0] + dx < 0 || c[0] + dx >= g.dims[0]) {
                continue;
              }
              const int o = offsetIndex(dx, dy, dz);
              const Index f = el.full[g.index(c[0] + dx, c[1] + dy, c[2] + dz)];
              if (f < 0 || (skipDiagonal && o == centre)) {
                continue;
              }
              const float s = entryTowards(e, f, o);
              if (s != 0.f) {
                sum += double(s) * x[f];
              }
            }
          }
        }
      }
      for (Index k = extraStart[e]; k < extraStart[e + 1]; ++k) {
        if (!(skipDiagonal && extraColumn[k] == e)) {
          sum += double(extraValue[k]) * x[extraColumn[k]];
        }
      }
      y[e] += sum;
    }
  });
}

std::size_t NearField::bytes() const
{
  return stencil.size() * sizeof(float) + extraStart.size() * sizeof(Index) +
         extraColumn.size() * (sizeof(Column) + sizeof(float)) + far.size() * sizeof(double) +
         views.bytes() + (elements.full.size() + elements.front.size() + elements.voxelOf.size()) *
           sizeof(ExchangeElements::Number);
}

std::size_t ViewRows::bytes() const
{
  return start.size() * sizeof(Index) +
         column.size() * (sizeof(ExchangeElements::Number) + sizeof(float));
}

namespace {

void checkOptions(const NearFieldOptions& opt)
{
  if (opt.radius < 0) {
    throw Error("the near-field radius must be >= 0");
  }
  for (const QuadratureSettings* q : { &opt.quadrature, &opt.homogeneousQuadrature }) {
    if (!q->exchangeCountsValid()) {
      throw Error("quadrature settings must all be >= 1");
    }
  }
}

/// computeViewRows with the channel's medium given: computeNearField's own,
/// not a second copy of its extinction.
ViewRows viewRows(const ChannelMedium& medium,
                  const ExchangeElements& el,
                  const NearFieldOptions& opt,
                  const ProgressRange& progress)
{
  const int r = opt.radius;
  const Grid& g = medium.scene.grid;
  const Index nv = g.voxelCount();
  // Views of the empty voxels next to elements. Those whose box is all
  // empty see only walls: one row per row class.
  TripletLists views;
  const auto viewDirs = fibonacciSphere(8 * opt.quadrature.voxelDirections);
  std::vector<std::int32_t> sharedView(opt.reuseHomogeneous ? nv : 0, -1);
  std::vector<Index> viewRepresentatives;
  if (!sharedView.empty()) {
    std::map<RowClass, std::int32_t> classes;
    RowClass k;
    for (Index v = 0; v < nv; ++v) {
      if (el.full[v] < 0 && rowClass(g, medium.kappaT, el, v, r, -1, k)) {
        sharedView[v] = joinClass(classes, k, v, viewRepresentatives);
      }
    }
  }
  auto gatherView = [&](Index v, auto&& sink) {
    gatherVoxelView(medium, el, v, viewDirs, opt.quadrature, false, neighbourhood(g, v, r), sink);
  };
  std::vector<std::vector<ClassEntry>> sharedViews(viewRepresentatives.size());
  tbb::parallel_for(Index(0), Index(viewRepresentatives.size()), [&](Index k) {
    const Index v = viewRepresentatives[k];
    const auto c = g.ijk(v);
    std::map<Place, double> row;
    Place at;
    gatherView(v, [&](Index e, double p, bool) {
      if (placeOfElement(g, el, r, e, c, at)) {
        row[at] += p;
      }
    });
    sharedViews[k] = toEntries(row);
  });
  // In blocks, with a progress report (and a chance to abort) after each:
  // the empty voxels around a head or a cloud are many.
  progress.sub(0.0, 0.99).forBlocks(nv, 256, 1024, [&](Index b0, Index b1) {
    tbb::parallel_for(b0, b1, [&](Index v) {
      if (el.full[v] >= 0) {
        return;
      }
      const auto c = g.ijk(v);
      bool seesSomething = false;
      for (int dz = -r; dz <= r && !seesSomething; ++dz) {
        for (int dy = -r; dy <= r && !seesSomething; ++dy) {
          for (int dx = -r; dx <= r && !seesSomething; ++dx) {
            const int i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
            if (i < 0 || j < 0 || k < 0 || i >= g.dims[0] || j >= g.dims[1] || k >= g.dims[2]) {
              continue;
            }
            // An element, or a boundary voxel: the patches behind it are near.
            seesSomething = el.full[g.index(i, j, k)] >= 0 || i == 0 || j == 0 || k == 0 ||
                            i == g.dims[0] - 1 || j == g.dims[1] - 1 || k == g.dims[2] - 1;
          }
        }
      }
      if (!seesSomething) {
        return;
      }
      if (!sharedView.empty() && sharedView[v] >= 0) {
        auto& local = views.local();
        for (const ClassEntry& x : sharedViews[sharedView[v]]) {
          local.push_back({ v, classElement(g, el, c, x), x.value });
        }
        return;
      }
      std::map<Index, double> row;
      gatherView(v, [&](Index e, double p, bool) { row[e] += p; });
      auto& local = views.local();
      for (const auto& [e, w] : row) {
        local.push_back({ v, e, w });
      }
    });
  });
  ViewRows out;
  toRows(gatherTriplets(views), nv, out.start, out.column, out.value);
  progress.report(1.0);
  return out;
}

} // namespace

ViewRows computeViewRows(const Scene& scene,
                         int channel,
                         const ExchangeElements& el,
                         const NearFieldOptions& opt,
                         const ProgressRange& progress)
{
  checkOptions(opt);
  if (Index(el.full.size()) != scene.grid.voxelCount()) {
    throw Error("view rows: the elements are not of this scene's grid");
  }
  return viewRows(ChannelMedium(scene, channel), el, opt, progress);
}

NearField computeNearField(const Scene& scene,
                           int channel,
                           const NearFieldOptions& opt,
                           const ProgressRange& progress)
{
  checkOptions(opt);
  const int r = opt.radius;
  const Grid& g = scene.grid;
  const ChannelMedium medium(scene, channel);
  NearField out;
  out.radius = r;
  out.elements = makeExchangeElements(scene, channel);
  const ExchangeElements& el = out.elements;
  const Index nv = g.voxelCount(), n = el.size();
  const int width = out.stencilSize();
  out.stencil.assign(std::size_t(el.fullCount) * width, 0.f);

  // Voxels of one row class share one row, and so do patches (rowClass):
  // uniform media and their walls cost one quadrature per class.
  const Index np = el.patchCount;
  std::vector<std::int32_t> shared(opt.reuseHomogeneous ? nv : 0, -1);
  std::vector<std::int32_t> sharedPatch(opt.reuseHomogeneous ? np : 0, -1);
  std::vector<Index> representatives, patchRepresentatives;
  if (opt.reuseHomogeneous) {
    std::map<RowClass, std::int32_t> classes, patchClasses;
    RowClass k;
    for (Index v = 0; v < nv; ++v) {
      if (el.full[v] >= 0 && rowClass(g, medium.kappaT, el, v, r, -1, k)) {
        shared[v] = joinClass(classes, k, v, representatives);
      }
    }
    // A class of one voxel would only pay for the finer quadrature.
    std::vector<int> members(representatives.size(), 0);
    for (Index v = 0; v < nv; ++v) {
      if (shared[v] >= 0) {
        ++members[shared[v]];
      }
    }
    std::vector<std::int32_t> renumber(representatives.size(), -1);
    std::vector<Index> kept;
    for (std::size_t c = 0; c < representatives.size(); ++c) {
      if (members[c] > 1) {
        renumber[c] = std::int32_t(kept.size());
        kept.push_back(representatives[c]);
      }
    }
    for (Index v = 0; v < nv; ++v) {
      shared[v] = shared[v] >= 0 ? renumber[shared[v]] : -1;
    }
    representatives = std::move(kept);
    for (Index p = 0; p < np; ++p) {
      if (rowClass(g, medium.kappaT, el, g.patchVoxel(p), r, int(g.patchLocation(p).face), k)) {
        sharedPatch[p] = joinClass(patchClasses, k, p, patchRepresentatives);
      }
    }
  }
  std::vector<double> sharedRows(representatives.size() * width, 0.0);
  std::vector<std::vector<ClassEntry>> sharedPatches(representatives.size()),
    sharedPatchRows(patchRepresentatives.size());
  tbb::parallel_for(Index(0), Index(representatives.size()), [&](Index k) {
    const Index v = representatives[k];
    const auto c = g.ijk(v);
    double* row = sharedRows.data() + k * width;
    std::map<Place, double> patches;
    Place at;
    gatherVoxelLinesInto(medium,
                         el,
                         v,
                         opt.homogeneousQuadrature,
                         neighbourhood(g, v, r),
                         [&](Index e, double p, bool) {
                           if (!placeOfElement(g, el, r, e, c, at)) {
                             return;
                           }
                           if (at.first >= 0) {
                             patches[at] += p;
                           } else {
                             row[out.offsetIndex(at.second[0], at.second[1], at.second[2])] += p;
                           }
                         });
    sharedPatches[k] = toEntries(patches);
  });
  tbb::parallel_for(Index(0), Index(patchRepresentatives.size()), [&](Index k) {
    const Index p = patchRepresentatives[k];
    const auto c = g.ijk(g.patchVoxel(p));
    std::map<Place, double> row;
    Place at;
    gatherPatch(
      medium, el, p, opt.quadrature, neighbourhood(g, g.patchVoxel(p), r), [&](Index e, double w) {
        if (placeOfElement(g, el, r, e, c, at)) {
          row[at] += w;
        }
      });
    sharedPatchRows[k] = toEntries(row);
  });
  progress.report(0.05);

  // Raw voxel rows: full-full into the stencil, the rest as triplets.
  TripletLists extras;
  progress.sub(0.05, 0.8).forBlocks(nv, 256, 1024, [&](Index b0, Index b1) {
    tbb::parallel_for(
      tbb::blocked_range<Index>(b0, b1), [&](const tbb::blocked_range<Index>& range) {
        std::vector<double> row(width);
        auto& local = extras.local();
        for (Index v = range.begin(); v != range.end(); ++v) {
          const Index self = el.full[v];
          if (self < 0) {
            continue;
          }
          float* dst = out.stencil.data() + std::size_t(self) * width;
          if (!shared.empty() && shared[v] >= 0) {
            const double* src = sharedRows.data() + std::size_t(shared[v]) * width;
            for (int o = 0; o < width; ++o) {
              dst[o] = float(src[o]);
            }
            const auto c = g.ijk(v);
            for (const ClassEntry& x : sharedPatches[shared[v]]) {
              local.push_back({ self, classElement(g, el, c, x), x.value });
            }
            continue;
          }
          std::fill(row.begin(), row.end(), 0.0);
          const auto c = g.ijk(v);
          const Index selfFront = el.front[v];
          const std::size_t first = local.size();
          gatherVoxelLinesInto(medium,
                               el,
                               v,
                               opt.quadrature,
                               neighbourhood(g, v, r),
                               [&](Index e, double p, bool front) {
                                 const auto u = g.ijk(el.isPatch(e) ? g.patchVoxel(e - el.fullCount)
                                                                    : el.voxelOf[e]);
                                 const int dx = u[0] - c[0], dy = u[1] - c[1], dz = u[2] - c[2];
                                 if (std::max({ std::abs(dx), std::abs(dy), std::abs(dz) }) > r) {
                                   return; // a sliver past the box edge from round-off: far
                                 }
                                 if (front) {
                                   local.push_back({ selfFront, e, p });
                                 }
                                 if (el.isPatch(e) || el.isFront(e)) {
                                   local.push_back({ self, e, p });
                                 } else {
                                   row[out.offsetIndex(dx, dy, dz)] += p;
                                 }
                               });
          for (int o = 0; o < width; ++o) {
            dst[o] = float(row[o]);
          }
          // Merge this voxel's repeated triplets.
          std::sort(local.begin() + first, local.end(), byRowThenColumn);
          std::size_t out_ = first;
          for (std::size_t k = first; k < local.size(); ++k) {
            if (out_ > first && local[out_ - 1].row == local[k].row &&
                local[out_ - 1].col == local[k].col) {
              local[out_ - 1].value += local[k].value;
            } else {
              local[out_++] = local[k];
            }
          }
          local.resize(out_);
        }
      });
  });

  // Patch rows, cut at the box around the voxel behind each patch.
  progress.sub(0.8, 0.85).forBlocks(np, 64, 256, [&](Index b0, Index b1) {
    tbb::parallel_for(Index(b0), Index(b1), [&](Index p) {
      auto& local = extras.local();
      const auto c = g.ijk(g.patchVoxel(p));
      if (!sharedPatch.empty() && sharedPatch[p] >= 0) {
        for (const ClassEntry& x : sharedPatchRows[sharedPatch[p]]) {
          local.push_back({ el.patchElement(p), classElement(g, el, c, x), x.value });
        }
        return;
      }
      std::map<Index, double> row;
      gatherPatch(
        medium,
        el,
        p,
        opt.quadrature,
        neighbourhood(g, g.patchVoxel(p), r),
        [&](Index e, double w) {
          const auto u = g.ijk(el.isPatch(e) ? g.patchVoxel(e - el.fullCount) : el.voxelOf[e]);
          if (std::max({ std::abs(u[0] - c[0]), std::abs(u[1] - c[1]), std::abs(u[2] - c[2]) }) <=
              r) {
            row[e] += w;
          }
        });
      for (const auto& [e, w] : row) {
        local.push_back({ el.patchElement(p), e, w });
      }
    });
  });
  progress.report(0.85);

  // Reciprocity: weights by each row's rays per unit of emitting surface.
  const double uVoxel = raysPerSurface(opt.quadrature, g);
  const double uShared = raysPerSurface(opt.homogeneousQuadrature, g);
  const double patchRays = double(opt.quadrature.patchPointsPerAxis) *
                           opt.quadrature.patchPointsPerAxis * opt.quadrature.patchDirections;
  auto weight = [&](Index e) {
    if (el.isPatch(e)) {
      return patchRays / g.patchArea(g.patchLocation(e - el.fullCount).face);
    }
    const Index v = el.voxelOf[e];
    return (!shared.empty() && shared[v] >= 0) ? uShared : uVoxel;
  };
  // Full-full pairs: each unordered pair is owned by its lower voxel.
  tbb::parallel_for(Index(0), nv, [&](Index v) {
    if (el.full[v] < 0) {
      return;
    }
    const auto c = g.ijk(v);
    const double wv = weight(el.full[v]);
    for (int o = out.offsetIndex(0, 0, 0) + 1; o < width; ++o) {
      const int w2 = 2 * r + 1;
      const int dx = o % w2 - r, dy = (o / w2) % w2 - r, dz = o / (w2 * w2) - r;
      const int i = c[0] + dx, j = c[1] + dy, k = c[2] + dz;
      if (i < 0 || j < 0 || k < 0 || i >= g.dims[0] || j >= g.dims[1] || k >= g.dims[2]) {
        continue;
      }
      const Index u = g.index(i, j, k);
      if (el.full[u] < 0) {
        continue;
      }
      const double wu = weight(el.full[u]);
      float& a = out.stencil[std::size_t(el.full[v]) * width + o];
      float& b = out.stencil[std::size_t(el.full[u]) * width + out.offsetIndex(-dx, -dy, -dz)];
      const float s = float((wv * double(a) + wu * double(b)) / (wv + wu));
      a = s;
      b = s;
    }
  });

  // The other pairs: combine (a, b) with (b, a), then both directions.
  std::vector<Triplet> raw = gatherTriplets(extras);
  for (Triplet& t : raw) {
    // Key the unordered pair by its lower element; remember the direction.
    if (t.row > t.col) {
      std::swap(t.row, t.col);
      t.mirrored = true;
    }
  }
  std::sort(raw.begin(), raw.end(), byRowThenColumn);
  // Each unordered pair (a, b), a <= b, is one run of raw: its symmetric
  // value goes to rows a and b. The rows are written straight from the runs
  // (counted first), not through a second list of triplets: the runs come
  // by (a, b), so each row receives its lower columns (from the runs keyed
  // by them) before its higher ones, in order.
  auto forEachPair = [&](auto&& f) {
    for (std::size_t k = 0; k < raw.size();) {
      const Index a = raw[k].row, b = raw[k].col;
      double ab = 0.0, ba = 0.0;
      for (; k < raw.size() && raw[k].row == a && raw[k].col == b; ++k) {
        if (raw[k].mirrored) {
          ba += raw[k].value;
        } else {
          ab += raw[k].value;
        }
      }
      const double wa = weight(a), wb = weight(b);
      const double s = a == b ? ab : (wa * ab + wb * ba) / (wa + wb);
      if (s != 0.0) {
        f(a, b, s);
      }
    }
  };
  out.extraStart.assign(n + 1, 0);
  forEachPair([&](Index a, Index b, double) {
    ++out.extraStart[a + 1];
    if (a != b) {
      ++out.extraStart[b + 1];
    }
  });
  for (Index e = 0; e < n; ++e) {
    out.extraStart[e + 1] += out.extraStart[e];
  }
  out.extraColumn.resize(out.extraStart[n]);
  out.extraValue.resize(out.extraStart[n]);
  {
    std::vector<Index> cursor(out.extraStart.begin(), out.extraStart.end() - 1);
    auto put = [&](Index row, Index col, double s) {
      out.extraColumn[cursor[row]] = NearField::Column(col);
      out.extraValue[cursor[row]++] = float(s);
    };
    forEachPair([&](Index a, Index b, double s) {
      put(a, b, s);
      if (a != b) {
        put(b, a, s);
      }
    });
  }
  std::vector<Triplet>().swap(raw);

  // Far weights: what each row's near part leaves of its target.
  out.far.assign(n, 0.0);
  tbb::parallel_for(Index(0), n, [&](Index e) {
    double nearSum = 0.0;
    if (e < el.fullCount) {
      const float* row = out.stencil.data() + std::size_t(e) * width;
      for (int o = 0; o < width; ++o) {
        nearSum += row[o];
      }
    }
    for (Index k = out.extraStart[e]; k < out.extraStart[e + 1]; ++k) {
      if (!el.isFront(out.extraColumn[k])) {
        nearSum += out.extraValue[k];
      }
    }
    // Not clamped: where quadrature noise puts the near sum over the target, a
    // slightly negative far weight keeps the row exact.
    out.far[e] = exchangeRowTarget(scene, channel, el, e) - nearSum;
  });
  // Keep the upper half of each (symmetric) row, in place: each row's part
  // moves to an earlier place, after every entry read before it.
  {
    const int half = out.stencilHalf(), centre = out.offsetIndex(0, 0, 0);
    for (Index e = 0; e < el.fullCount; ++e) {
      for (int k = 0; k < half; ++k) {
        out.stencil[std::size_t(e) * half + k] = out.stencil[std::size_t(e) * width + centre + k];
      }
    }
    out.stencil.resize(std::size_t(el.fullCount) * half);
    out.stencil.shrink_to_fit();
  }
  progress.report(0.9);

  if (opt.emptyViews) {
    out.views = viewRows(medium, el, opt, progress.sub(0.9, 1.0));
  }
  progress.report(1.0);
  return out;
}

} // namespace volrad
