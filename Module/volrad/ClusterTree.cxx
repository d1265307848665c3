// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/ClusterTree.h"

#include <algorithm>
#include <cmath>

namespace volrad {

double effectiveCrossSection(double kappaT, const Vec3& h)
{
  const double surface = 2.0 * (h[0] * h[1] + h[1] * h[2] + h[0] * h[2]);
  const double meanChord = 4.0 * h.prod() / surface;
  return 0.25 * surface * -std::expm1(-kappaT * meanChord);
}

ClusterTree::ClusterTree(const Scene& scene, int channel, const VoxelPyramid& pyramid)
  : pyramid_(pyramid)
{
  for (int l = 0; l < pyramid.levels(); ++l) {
    grids_.push_back(pyramid.grid(l));
  }
  const int L = levels();
  voxelOffset_.assign(L + 1, 0);
  for (int l = 0; l < L; ++l) {
    voxelOffset_[l + 1] = voxelOffset_[l] + grids_[l].voxelCount();
  }
  patchOffset_.assign(L + 1, voxelOffset_[L]);
  for (int l = 0; l < L; ++l) {
    patchOffset_[l + 1] = patchOffset_[l] + grids_[l].patchCount();
  }
  level_.resize(patchOffset_[L]);
  for (int l = 0; l < L; ++l) {
    std::fill(
      level_.begin() + voxelOffset_[l], level_.begin() + voxelOffset_[l + 1], std::uint8_t(l));
    std::fill(
      level_.begin() + patchOffset_[l], level_.begin() + patchOffset_[l + 1], std::uint8_t(l));
  }

  const Grid& g = grids_[0];
  voxelSigma_.resize(g.voxelCount());
  for (Index v = 0; v < g.voxelCount(); ++v) {
    voxelSigma_[v] = float(effectiveCrossSection(scene.kappaTAt(v, channel), g.spacing));
  }
  sigma_.resize(L);
  centroid_.resize(L);
  for (int l = 1; l < L; ++l) {
    const Grid& coarse = grids_[l];
    sigma_[l].assign(coarse.voxelCount(), 0.0);
    centroid_[l].assign(coarse.voxelCount(), Vec3::Zero());
    for (Index c = 0; c < coarse.voxelCount(); ++c) {
      std::array<Index, 8> kids;
      const int n = children(voxelNode(l, c), kids);
      double s = 0.0;
      Vec3 m = Vec3::Zero();
      for (int k = 0; k < n; ++k) {
        const double sk = sigma(kids[k]);
        s += sk;
        m += sk * centroid(kids[k]);
      }
      sigma_[l][c] = s;
      if (s > 0.0) {
        centroid_[l][c] = m / s;
      } else { // empty: the middle of the voxels it covers
        std::array<int, 3> lo, hi;
        box(voxelNode(l, c), lo, hi);
        for (int a = 0; a < 3; ++a) {
          centroid_[l][c][a] = g.origin[a] + 0.5 * (lo[a] + hi[a]) * g.spacing[a];
        }
      }
    }
  }
  buildSideTransmittance(scene, channel);
  patchArea_.resize(L);
  patchCentroid_.resize(L);
  patchArea_[0].resize(g.patchCount());
  patchCentroid_[0].resize(g.patchCount());
  for (Index p = 0; p < g.patchCount(); ++p) {
    patchArea_[0][p] = g.patchArea(g.patchLocation(p).face);
    patchCentroid_[0][p] = g.patchCentre(p);
  }
  for (int l = 1; l < L; ++l) {
    patchArea_[l].assign(grids_[l].patchCount(), 0.0);
    patchCentroid_[l].assign(grids_[l].patchCount(), Vec3::Zero());
    for (Index p = 0; p < grids_[l].patchCount(); ++p) {
      std::array<Index, 8> kids;
      const int n = children(patchNode(l, p), kids);
      double a = 0.0;
      Vec3 m = Vec3::Zero();
      for (int k = 0; k < n; ++k) {
        const Index kc = cell(kids[k]);
        a += patchArea_[l - 1][kc];
        m += patchArea_[l - 1][kc] * patchCentroid_[l - 1][kc];
      }
      patchArea_[l][p] = a;
      patchCentroid_[l][p] = m / a;
    }
  }
}

void ClusterTree::buildSideTransmittance(const Scene& scene, int channel)
{
  const int L = levels();
  const Grid& g = grids_[0];
  exitTransmittance_.assign(std::size_t(voxelOffset_[L]) * 6, Eigen::half(1.0f));
  sideSigma_.assign(L, {});
  sideShift_.assign(L, {});
  // Mean transmittance straight across each cell of the level below, per axis.
  std::vector<std::array<float, 3>> across(g.voxelCount()), coarser;
  for (Index v = 0; v < g.voxelCount(); ++v) {
    for (int a = 0; a < 3; ++a) {
      across[v][a] = float(std::exp(-scene.kappaTAt(v, channel) * g.spacing[a]));
    }
  }
  for (int l = 1; l < L; ++l) {
    const Grid& fine = grids_[l - 1];
    const Grid& coarse = grids_[l];
    coarser.assign(coarse.voxelCount(), { 1.0f, 1.0f, 1.0f });
    sideSigma_[l].assign(coarse.voxelCount(), {});
    sideShift_[l].assign(coarse.voxelCount(), {});
    for (Index c = 0; c < coarse.voxelCount(); ++c) {
      const auto ijk = coarse.ijk(c);
      std::array<Index, 8> kid; // by octant (bit a: the upper half along axis a), -1 outside
      for (int o = 0; o < 8; ++o) {
        const int i = 2 * ijk[0] + (o & 1), j = 2 * ijk[1] + ((o >> 1) & 1),
                  k = 2 * ijk[2] + (o >> 2);
        kid[o] =
          i < fine.dims[0] && j < fine.dims[1] && k < fine.dims[2] ? fine.index(i, j, k) : -1;
      }
      for (int a = 0; a < 3; ++a) {
        const int bit = 1 << a;
        double sum = 0.0;
        int columns = 0;
        for (int o = 0; o < 8; ++o) {
          if ((o & bit) || (kid[o] < 0 && kid[o | bit] < 0)) {
            continue;
          }
          const double t0 = kid[o] >= 0 ? across[kid[o]][a] : 1.0;
          const double t1 = kid[o | bit] >= 0 ? across[kid[o | bit]][a] : 1.0;
          sum += t0 * t1;
          ++columns;
        }
        coarser[c][a] = columns > 0 ? float(sum / columns) : 1.0f;
      }
      std::array<float, 6>& sides = sideSigma_[l][c];
      sides.fill(0.0f);
      std::array<double, 6> weight{}, position{};
      for (int o = 0; o < 8; ++o) {
        if (kid[o] < 0) {
          continue;
        }
        const Index node = voxelNode(l - 1, kid[o]);
        for (int a = 0; a < 3; ++a) {
          const int bit = 1 << a;
          const Index sibling = kid[o ^ bit];
          const double through = sibling >= 0 ? across[sibling][a] : 1.0;
          // A voxel shows its face times its opacity along the axis, not its
          // mean cross-section over all directions.
          double own = 1.0;
          if (l == 1 && voxelSigma_[kid[o]] > 0.0f) {
            own = g.voxelVolume() / g.spacing[a] *
                  -std::expm1(-scene.kappaTAt(kid[o], channel) * g.spacing[a]) /
                  double(voxelSigma_[kid[o]]);
          }
          // Towards the side the voxel node is on: nothing in between.
          exitTransmittance_[std::size_t(node) * 6 + side(a, true)] =
            Eigen::half(float(own * ((o & bit) ? 1.0 : through)));
          exitTransmittance_[std::size_t(node) * 6 + side(a, false)] =
            Eigen::half(float(own * ((o & bit) ? through : 1.0)));
        }
        const Vec3 kc = centroid(node);
        for (int s = 0; s < 6; ++s) {
          const double below = l == 1 ? double(voxelSigma_[kid[o]]) : sideSigma_[l - 1][kid[o]][s];
          const double out = below * double(toParentSide(node, s));
          sides[s] += float(out);
          // Where along the axis that light leaves from: a voxel's from
          // nearer its face the thicker it is (the mean of x in e^(-kappa x)).
          const int a = s / 2;
          double shift;
          if (l == 1) {
            const double x = scene.kappaTAt(kid[o], channel) * g.spacing[a];
            const double depth = x < 1e-4 ? 0.5 - x / 12.0 : 1.0 / x - 1.0 / std::expm1(x);
            shift = (s % 2 ? 1.0 : -1.0) * (0.5 - depth) * g.spacing[a];
          } else {
            shift = sideShift_[l - 1][kid[o]][s];
          }
          weight[s] += out;
          position[s] += out * (kc[a] + shift);
        }
      }
      const Vec3 centre = centroid(voxelNode(l, c));
      for (int s = 0; s < 6; ++s) {
        sideShift_[l][c][s] =
          weight[s] > 0.0 ? float(position[s] / weight[s] - centre[s / 2]) : 0.0f;
      }
    }
    across.swap(coarser);
  }
  // Side sigma / sigma of every cluster, for every link that mixes its sides.
  sideOpen_.clear();
  for (int l = 1; l < L; ++l) {
    for (Index c = 0; c < grids_[l].voxelCount(); ++c) {
      std::array<float, 6> open;
      open.fill(1.0f);
      const double s = sigma_[l][c];
      if (s > 0.0) {
        for (int f = 0; f < 6; ++f) {
          open[f] = float(std::min(1.0, sideSigma_[l][c][f] / s));
        }
      }
      sideOpen_.push_back(open);
    }
  }
}

double ClusterTree::sigmaTowards(Index node, const Vec3& w) const
{
  const int l = level(node);
  if (isPatch(node) || l == 0) {
    return sigma(node);
  }
  return towards(w, sideOpenness(node).data(), sideSigma_[l][cell(node)]);
}

double ClusterTree::frontFactor(Index node, const Vec3& w, double kappa) const
{
  const int l = level(node);
  if (isPatch(node) || l == 0) {
    return 1.0;
  }
  Vec3 lo, hi;
  spaceBox(node, lo, hi);
  // (1 - e^-x) / x: the mean of e^(-x u), u uniform in [0, 1].
  auto mean = [](double x) { return x < 1e-6 ? 1.0 - 0.5 * x : -std::expm1(-x) / x; };
  double g[3];
  for (int a = 0; a < 3; ++a) {
    g[a] = mean(kappa * std::abs(w[a]) * (hi[a] - lo[a]));
  }
  const auto& sides = sideSigma_[l][cell(node)];
  double weight[3], all = 0.0, front = 0.0;
  sideWeights(w, sideOpenness(node).data(), weight);
  for (int a = 0; a < 3; ++a) {
    const double s = weight[a] * sides[side(a, w[a] > 0.0)];
    all += s;
    front += s * g[(a + 1) % 3] * g[(a + 2) % 3];
  }
  return all > 0.0 ? front / all : 1.0;
}

void ClusterTree::emissionBox(Index node, const Vec3& w, Vec3& centre, Vec3& half) const
{
  centre = centroid(node);
  half = Vec3::Zero();
  const int l = level(node);
  if (isPatch(node) || l == 0) {
    return;
  }
  Vec3 lo, hi;
  spaceBox(node, lo, hi);
  const auto& shift = sideShift_[l][cell(node)];
  for (int a = 0; a < 3; ++a) {
    const double extent = hi[a] - lo[a];
    const double moved = w[a] * w[a] * shift[side(a, w[a] > 0.0)];
    const double h = 0.5 * extent * std::max(0.0, 1.0 - 2.0 * std::abs(moved) / extent);
    // Within the cluster's box (its centroid may sit off the middle).
    const double from = std::max(lo[a], centre[a] + moved - h);
    const double to = std::min(hi[a], centre[a] + moved + h);
    centre[a] = 0.5 * (from + to);
    half[a] = 0.5 * std::max(0.0, to - from);
  }
}

std::vector<Index> ClusterTree::roots() const
{
  const int top = levels() - 1;
  std::vector<Index> r{ voxelNode(top, 0) };
  for (Index p = 0; p < grids_[top].patchCount(); ++p) {
    r.push_back(patchNode(top, p));
  }
  return r;
}

int ClusterTree::children(Index node, std::array<Index, 8>& out) const
{
  const int l = level(node);
  if (l == 0) {
    return 0;
  }
  const Grid& fine = grids_[l - 1];
  const Index c = cell(node);
  int n = 0;
  if (!isPatch(node)) {
    const auto ijk = grids_[l].ijk(c);
    for (int k = 0; k < 8; ++k) {
      const int i = 2 * ijk[0] + (k & 1), j = 2 * ijk[1] + ((k >> 1) & 1),
                m = 2 * ijk[2] + (k >> 2);
      if (i < fine.dims[0] && j < fine.dims[1] && m < fine.dims[2]) {
        out[n++] = voxelNode(l - 1, fine.index(i, j, m));
      }
    }
    return n;
  }
  const PatchLocation loc = grids_[l].patchLocation(c);
  const auto ax = faceAxesInPlane(loc.face);
  for (int k = 0; k < 4; ++k) {
    const int a = 2 * loc.a + (k & 1), b = 2 * loc.b + (k >> 1);
    if (a < fine.dims[ax[0]] && b < fine.dims[ax[1]]) {
      out[n++] = patchNode(l - 1, fine.patchIndex(loc.face, a, b));
    }
  }
  return n;
}

double ClusterTree::sigma(Index node) const
{
  const int l = level(node);
  if (isPatch(node)) {
    return patchArea_[l][cell(node)];
  }
  return l == 0 ? double(voxelSigma_[node]) : sigma_[l][cell(node)];
}

Vec3 ClusterTree::centroid(Index node) const
{
  const int l = level(node);
  if (isPatch(node)) {
    return patchCentroid_[l][cell(node)];
  }
  return l == 0 ? grids_[0].voxelCentre(node) : centroid_[l][cell(node)];
}

double ClusterTree::radius(Index node) const
{
  return radius(node, box(node));
}

double ClusterTree::radius(Index node, const Box& b) const
{
  const auto voxels = b.extent();
  Vec3 extent;
  for (int a = 0; a < 3; ++a) {
    extent[a] = voxels[a] * grids_[0].spacing[a];
  }
  if (isPatch(node)) {
    extent[faceAxis(face(node))] = 0.0;
  }
  return 0.5 * extent.norm();
}

double ClusterTree::meanKappaT(Index node) const
{
  return isPatch(node) ? 0.0 : pyramid_.meanKappaT(level(node), cell(node));
}

Face ClusterTree::face(Index node) const
{
  return grids_[level(node)].patchLocation(cell(node)).face;
}

void ClusterTree::box(Index node, std::array<int, 3>& lo, std::array<int, 3>& hi) const
{
  const int l = level(node);
  const int s = 1 << l;
  const auto& dims = grids_[0].dims;
  if (!isPatch(node)) {
    // Element by element: a vectorised loop over the axes reloaded the
    // cell's indices as one 64-bit word from two 32-bit stores (a
    // store-forwarding stall, 5% of a 64^3 solve's time).
    const auto c = grids_[l].ijk(cell(node));
    const int i = c[0] * s, j = c[1] * s, k = c[2] * s;
    lo[0] = i;
    lo[1] = j;
    lo[2] = k;
    hi[0] = std::min(i + s - 1, dims[0] - 1);
    hi[1] = std::min(j + s - 1, dims[1] - 1);
    hi[2] = std::min(k + s - 1, dims[2] - 1);
    return;
  }
  const PatchLocation loc = grids_[l].patchLocation(cell(node));
  const auto ax = faceAxesInPlane(loc.face);
  const int n = faceAxis(loc.face);
  lo[ax[0]] = loc.a * s;
  hi[ax[0]] = std::min(lo[ax[0]] + s - 1, dims[ax[0]] - 1);
  lo[ax[1]] = loc.b * s;
  hi[ax[1]] = std::min(lo[ax[1]] + s - 1, dims[ax[1]] - 1);
  lo[n] = hi[n] = faceIsMax(loc.face) ? dims[n] - 1 : 0;
}

void ClusterTree::spaceBox(const Box& b, Vec3& lo, Vec3& hi) const
{
  const Grid& g = grids_[0];
  for (int a = 0; a < 3; ++a) {
    lo[a] = g.origin[a] + (b.lo[a] - 0.5) * g.spacing[a];
    hi[a] = g.origin[a] + (b.hi[a] + 0.5) * g.spacing[a];
  }
}

int ClusterTree::gap(const Box& a, const Box& b)
{
  int g = 0;
  for (int k = 0; k < 3; ++k) {
    g = std::max({ g, b.lo[k] - a.hi[k], a.lo[k] - b.hi[k] });
  }
  return g;
}

std::size_t ClusterTree::bytes() const
{
  std::size_t b = level_.size() + voxelSigma_.size() * sizeof(float) +
                  exitTransmittance_.size() * sizeof(Eigen::half) +
                  sideOpen_.size() * sizeof(std::array<float, 6>);
  for (int l = 0; l < levels(); ++l) {
    b += sigma_[l].size() * sizeof(double) + centroid_[l].size() * sizeof(Vec3) +
         (sideSigma_[l].size() + sideShift_[l].size()) * sizeof(std::array<float, 6>) +
         patchArea_[l].size() * sizeof(double) + patchCentroid_[l].size() * sizeof(Vec3);
  }
  return b;
}

} // namespace volrad
