// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/FarField.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace volrad {

namespace {

Vec3 unitNormal(const Scene& s, Index v)
{
  const Vec3 n = s.normalAt(v);
  const double l = n.norm();
  return l > 0.0 ? Vec3(n / l) : Vec3::Zero();
}

template<class F>
void forEachIn(Index begin, Index end, F&& f)
{
  tbb::parallel_for(tbb::blocked_range<Index>(begin, end, 2048), [&](const auto& r) {
    for (Index i = r.begin(); i != r.end(); ++i) {
      f(i);
    }
  });
}

template<class F>
void forEach(Index n, F&& f)
{
  forEachIn(0, n, f);
}

std::array<float, 6> toFloat(const std::array<double, 6>& a)
{
  std::array<float, 6> f;
  for (int i = 0; i < 6; ++i) {
    f[i] = float(a[i]);
  }
  return f;
}

/// Links in the gather's blocks between progress reports: the first, the
/// most (tens of ns each).
constexpr std::int64_t kFirstLinks = 1 << 18, kMaxLinks = 1 << 22;
/// Links a task of the gather takes (its chunks cost about one ms).
constexpr std::int64_t kLinksPerTask = 1 << 14;

/// f(node) for every voxel node and patch node of one level, in parallel.
template<class F>
void forEachNodeOfLevel(const ClusterTree& t, int level, F&& f)
{
  forEach(t.grid(level).voxelCount(), [&](Index c) { f(t.voxelNode(level, c), false); });
  forEach(t.grid(level).patchCount(), [&](Index c) { f(t.patchNode(level, c), true); });
}

} // namespace

FarField::FarField(const Scene& scene,
                   const ClusterTree& tree,
                   const LinkSet& links,
                   const NearField& near,
                   const ProgressRange& progress)
  : scene_(scene)
  , tree_(tree)
  , links_(links)
  , el_(near.elements)
  , fronts_(near.elements.frontCount > 0)
{
  const Index nodes = tree.size();
  const Index nv = tree.grid(0).voxelCount();
  voxels_ = nv;
  centroid_.resize(nodes - nv);
  forEach(nodes - nv, [&](Index k) { centroid_[k] = tree.centroid(nv + k).cast<float>(); });
  clusters_ = tree.voxelNode(tree.levels() - 1, 0) + 1 - nv;
  slopeLimit_.resize(clusters_);
  forEach(clusters_, [&](Index c) { slopeLimit_[c] = float(1.0 / tree.radius(nv + c)); });
  sideEmit_.assign(clusters_, {});
  sidePhi_.assign(clusters_, {});
  moment_.assign(clusters_, Vec3f::Zero());
  gradient_.assign(clusters_, Vec3f::Zero());
  emit_.assign(nodes, 0.f);
  phi_.assign(nodes, 0.f);
  if (fronts_) {
    frontEmit_.assign(nodes, 0.f);
    frontMoment_.assign(nodes, Vec3f::Zero());
    psi_.assign(nodes, Vec3f::Zero());
    open_.assign(nodes, 0.f);
    leafDirect_.assign(tree.grid(0).voxelCount(), 0.f);
    leafFront_.assign(tree.grid(0).voxelCount(), 0.f);
  }
  // Balance the links' operator F symmetrically, F' = D F D, towards every
  // element receiving exactly its far weight for radiosity 1 on the
  // partition (d_e (F d)_e = far_e; damped symmetric Sinkhorn steps, d kept
  // within [1/2, 2] since far weights that are small differences carry the
  // near field's quadrature noise). What remains goes to each element's
  // self exchange: then rows and, by symmetry, columns are exact, and the
  // far field neither loses nor makes energy. Front sides (inside the
  // partition's full sides) are scaled per row, and their sources alike.
  const Index n = el_.size(), partition = el_.partitionSize();
  // The balance's source weights: the partition's d, front sides silent.
  std::vector<double> d(n, 0.0);
  std::fill(d.begin(), d.begin() + partition, 1.0);
  scale_.assign(n, 1.0);
  self_.assign(n, 0.0);
  std::vector<double> received(n);
  for (int step = 0; step < kBalanceSteps; ++step) {
    std::fill(received.begin(), received.end(), 0.0);
    gather(
      d.data(),
      received.data(),
      nullptr,
      false,
      progress.sub(double(step) / (kBalanceSteps + 1), double(step + 1) / (kBalanceSteps + 1)));
    for (Index e = 0; e < partition; ++e) {
      if (received[e] > 0.0) {
        const double ratio = std::max(0.0, near.far[e]) / received[e];
        d[e] = std::clamp(std::sqrt(d[e] * ratio), 0.5, 2.0);
      }
    }
  }
  std::fill(received.begin(), received.end(), 0.0);
  gather(d.data(),
         received.data(),
         nullptr,
         false,
         progress.sub(double(kBalanceSteps) / (kBalanceSteps + 1), 1.0));
  for (Index e = 0; e < n; ++e) {
    if (e < partition) {
      scale_[e] = d[e];
      self_[e] = near.far[e] - d[e] * received[e];
    } else if (received[e] > 0.0) {
      scale_[e] = near.far[e] / received[e];
    }
  }
  // Sources are scaled by scale_ too (apply), front sides included: their
  // links are symmetric, so each one's column then sums to its far weight
  // and what it sends is what its receivers take (with 1 there, the
  // phantom's bone shell sent 1.3% too much and its energy residual was 1%).
}

void FarField::apply(const double* x,
                     double* y,
                     double* viewOut,
                     const ProgressRange& progress) const
{
  scaled_.resize(el_.size());
  forEach(el_.size(), [&](Index e) { scaled_[e] = scale_[e] * x[e]; });
  gather(scaled_.data(), y, viewOut, true, progress);
  forEach(el_.size(), [&](Index e) { y[e] += self_[e] * x[e]; });
}

void FarField::gather(const double* x,
                      double* y,
                      double* viewOut,
                      bool normalised,
                      const ProgressRange& progress) const
{
  const Grid& g = tree_.grid(0);
  const Index nv = g.voxelCount(), np = g.patchCount();
  const int L = tree_.levels();

  // Pull: the elements' emission per unit gamma, summed up the tree.
  forEach(nv, [&](Index v) {
    const Index e = el_.full[v];
    emit_[v] = e >= 0 ? float(tree_.sigma(v) * x[e]) : 0.f;
    if (fronts_) {
      const Index f = el_.front[v];
      frontEmit_[v] = f >= 0 ? float(tree_.sigma(v) * x[f]) : 0.f;
      frontMoment_[v] = frontEmit_[v] != 0.f
                          ? Vec3f((double(frontEmit_[v]) * unitNormal(scene_, v)).cast<float>())
                          : Vec3f::Zero();
    }
  });
  forEach(np, [&](Index p) {
    emit_[tree_.patchNode(0, p)] =
      float(tree_.sigma(tree_.patchNode(0, p)) * x[el_.patchElement(p)]);
  });
  for (int l = 1; l < L; ++l) {
    forEachNodeOfLevel(tree_, l, [&](Index node, bool patches) {
      std::array<Index, 8> kids;
      const int k = tree_.children(node, kids);
      double s = 0.0, d = 0.0;
      Vec3 m = Vec3::Zero(), moment = Vec3::Zero();
      std::array<double, 6> sides{};
      for (int i = 0; i < k; ++i) {
        s += emit_[kids[i]];
        if (!patches) {
          moment += double(emit_[kids[i]]) * (centroid(kids[i]) - centroid(node));
          if (l > 1) {
            moment += moment_[kids[i] - nv].cast<double>();
          }
          for (int f = 0; f < 6; ++f) { // seen through the siblings in front
            sides[f] += double(l == 1 ? emit_[kids[i]] : sideEmit_[kids[i] - nv][f]) *
                        double(tree_.toParentSide(kids[i], f));
          }
        }
        if (fronts_ && !patches) {
          d += frontEmit_[kids[i]];
          m += frontMoment_[kids[i]].cast<double>();
        }
      }
      emit_[node] = float(s);
      if (!patches) {
        moment_[node - nv] = moment.cast<float>();
        sideEmit_[node - nv] = toFloat(sides);
      }
      if (fronts_ && !patches) {
        frontEmit_[node] = float(d);
        frontMoment_[node] = m.cast<float>();
      }
    });
  }

  // Gather over the links into receiving node b.
  auto gatherInto = [&](Index b) {
    const bool patchB = tree_.isPatch(b), leafB = tree_.isLeaf(b);
    const bool frontB = fronts_ && !patchB && leafB && el_.front[b] >= 0;
    const Vec3 cb = centroid(b);
    Vec3 nb = Vec3::Zero();
    if (patchB) {
      nb = faceInwardNormal(tree_.face(b));
    } else if (frontB) {
      nb = unitNormal(scene_, b);
    }
    const bool clusterB = isVoxelCluster(b, nv);
    const double limitB = clusterB ? double(slopeLimit_[b - nv]) : 0.0;
    std::array<double, 6> sides{};
    double phi = 0.0, direct = 0.0, front = 0.0, open = 0.0;
    Vec3 psi = Vec3::Zero(), gradient = Vec3::Zero();
    // Voxel to voxel without front sides (most links): no direction, no
    // sides, no slope.
    const bool plainB = !clusterB && !patchB && !frontB;
    links_.forEachInto(b, [&](Index a, float gamma) {
      // a voxel leaf (voxel nodes come first)
      if (plainB && a < nv && (!fronts_ || frontEmit_[a] == 0.f)) {
        phi += emit_[a] * double(gamma);
        return;
      }
      const bool patchA = tree_.isPatch(a);
      const bool frontA = fronts_ && !patchA && frontEmit_[a] != 0.f;
      double e = emit_[a];
      if (e == 0.0 && !frontA) {
        return;
      }
      const bool clusterA = isVoxelCluster(a, nv);
      const Vec3 ab = cb - centroid(a);
      // One division a link (it runs at every link of every gather).
      const double inverseR = 1.0 / ab.norm(), twoOverR = 2.0 * inverseR;
      const Vec3 w = ab * inverseR; // from a towards b
      // A cluster emits towards b what its sides facing b let out, and
      // 1/r^2 grows by 2/r per length of its elements' offsets towards b
      // (to first order, limited so that no element's weight is negative).
      if (clusterA) {
        e = std::min(twoOverR, double(slopeLimit_[a - nv])) * w.dot(moment_[a - nv].cast<double>()) +
            ClusterTree::towards(w, tree_.sideOpenness(a).data(), sideEmit_[a - nv]);
      }
      if (patchA) {
        e *= std::max(0.0, faceInwardNormal(tree_.face(a)).dot(w));
      } else if (frontA) {
        const double d = frontEmit_[a];
        if (a < nv) { // a voxel leaf (voxel nodes come first)
          e += unitNormal(scene_, a).dot(w) > 0.0 ? d : 0.0;
        } else {
          e +=
            std::clamp(0.5 * d + 0.75 * frontMoment_[a].cast<double>().dot(w), std::min(0.0, d), std::max(0.0, d));
        }
      }
      const double c = e * double(gamma);
      if (patchB) {
        phi += c * std::max(0.0, -nb.dot(w));
        return;
      }
      if (clusterB) { // received on b's sides facing a, falling away from a
        double weight[3];
        ClusterTree::sideWeights(-w, tree_.sideOpenness(b).data(), weight);
        for (int x = 0; x < 3; ++x) {
          sides[ClusterTree::side(x, w[x] < 0.0)] += weight[x] * c;
        }
        gradient -= (std::min(twoOverR, limitB) * c) * w;
      } else {
        phi += c;
      }
      if (frontB) {
        direct += c;
        front += -nb.dot(w) > 0.0 ? c : 0.0; // light arriving from the front
      } else if (fronts_ && !leafB) {
        psi -= c * w; // towards the source
        open += c;
      }
    });
    phi_[b] = float(phi);
    if (clusterB) {
      gradient_[b - nv] = gradient.cast<float>();
      sidePhi_[b - nv] = toFloat(sides);
    }
    if (fronts_ && !patchB) {
      psi_[b] = psi.cast<float>();
      open_[b] = float(open);
      if (leafB) {
        leafDirect_[b] = float(direct);
        leafFront_[b] = float(front);
      }
    }
  };

  // Gather over the links, per receiving node, in blocks of links with a
  // progress report (a stop request) after each.
  const auto& start = links_.start;
  const Index nodes = tree_.size();
  progress.forBlocks(start[nodes], kFirstLinks, kMaxLinks, [&](std::int64_t k0, std::int64_t k1) {
    // The nodes whose links begin in [k0, k1); the last block takes the
    // trailing nodes without links.
    const Index b0 = std::lower_bound(start.begin(), start.end() - 1, Index(k0)) - start.begin();
    const Index b1 =
      k1 == start[nodes]
        ? nodes
        : std::lower_bound(start.begin(), start.end() - 1, Index(k1)) - start.begin();
    // Split by links, not nodes: nodes hold a thousand links each on small
    // grids, where 2048-node chunks left a block one or two tasks (the
    // phantom's iterations at 32^3 kept 1.25 of 2 cores busy).
    const std::int64_t parts = std::max<std::int64_t>(1, (k1 - k0) / kLinksPerTask);
    std::vector<Index> first(std::size_t(parts) + 1, b1); // each task's first node
    first[0] = b0;
    for (std::int64_t i = 1; i < parts; ++i) {
      first[i] = std::lower_bound(start.begin() + b0, start.begin() + b1,
                                  Index(k0 + (k1 - k0) * i / parts)) -
                 start.begin();
    }
    tbb::parallel_for(std::int64_t(0), parts, [&](std::int64_t p) {
      for (Index b = first[p]; b < first[p + 1]; ++b) {
        gatherInto(b);
      }
    });
  });
  if (start[nodes] == 0) {
    forEach(nodes, [&](Index b) { gatherInto(b); });
  }

  // Push: every node hands what it received to its children.
  for (int l = L - 1; l >= 1; --l) {
    {
      forEachNodeOfLevel(tree_, l, [&](Index node, bool patches) {
        std::array<Index, 8> kids;
        const int k = tree_.children(node, kids);
        for (int i = 0; i < k; ++i) {
          phi_[kids[i]] += phi_[node];
          if (!patches) { // through the siblings in front; first-order variation
            const auto& in = sidePhi_[node - nv];
            double seen = 0.0;
            for (int f = 0; f < 6; ++f) {
              const float t = tree_.toParentSide(kids[i], f);
              if (l > 1) {
                sidePhi_[kids[i] - nv][f] += in[f] * t;
              } else {
                seen += in[f] * t;
              }
            }
            const Vec3f& gradient = gradient_[node - nv];
            phi_[kids[i]] +=
              float(seen + gradient.cast<double>().dot(centroid(kids[i]) - centroid(node)));
            if (l > 1) {
              gradient_[kids[i] - nv] += gradient;
            }
          }
          if (fronts_ && !patches) {
            psi_[kids[i]] += psi_[node];
            open_[kids[i]] += open_[node];
          }
        }
      });
    }
  }

  // Elements: cross-section times what reached them.
  forEach(nv, [&](Index v) {
    const Index e = el_.full[v];
    if (e < 0) {
      if (viewOut) {
        viewOut[v] += phi_[v];
      }
      return;
    }
    y[e] += (normalised ? scale_[e] : 1.0) * tree_.sigma(v) * phi_[v];
    if (fronts_ && el_.front[v] >= 0) {
      const Index f = el_.front[v];
      // Front sides emit into clusters as if these were transparent
      // (frontEmit_), so they receive from them the same way: symmetric.
      const double pushed = open_[v];
      const double front =
        leafFront_[v] + std::clamp(0.5 * pushed + 0.75 * unitNormal(scene_, v).dot(psi_[v].cast<double>()),
                                   std::min(0.0, pushed),
                                   std::max(0.0, pushed));
      y[f] += (normalised ? scale_[f] : 1.0) * tree_.sigma(v) * front;
    }
  });
  forEach(np, [&](Index p) {
    const Index e = el_.patchElement(p);
    y[e] += (normalised ? scale_[e] : 1.0) * tree_.sigma(tree_.patchNode(0, p)) *
            phi_[tree_.patchNode(0, p)];
  });
}

std::size_t FarField::bytes() const
{
  return (emit_.size() + phi_.size() + open_.size() + frontEmit_.size() + leafDirect_.size() +
          leafFront_.size() + slopeLimit_.size()) *
           sizeof(float) +
         (scale_.size() + self_.size() + scaled_.size()) * sizeof(double) +
         (frontMoment_.size() + psi_.size() + centroid_.size() + moment_.size() +
          gradient_.size()) *
           sizeof(Vec3f) +
         (sideEmit_.size() + sidePhi_.size()) * sizeof(std::array<float, 6>);
}

} // namespace volrad
