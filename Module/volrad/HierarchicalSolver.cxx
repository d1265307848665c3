// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/HierarchicalSolver.h"

#include "volrad/ClusterTree.h"
#include "volrad/DirectLight.h"
#include "volrad/EnergyBalance.h"
#include "volrad/FarField.h"
#include "volrad/LinkSet.h"
#include "volrad/Memory.h"
#include "volrad/NearField.h"
#include "volrad/ZonalSystem.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace volrad {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

using Vector = Eigen::VectorXd;

/// Radiosity every element counts with in the link refinement, relative to
/// the largest.
constexpr double kRadiosityFloor = 1e-2;

/// Voxels (128^3) past which the budget's floor of links stops growing.
constexpr double kFewestLinksFlatFrom = 128.0 * 128.0 * 128.0;

/// How much coarser the first pass's links are than the final ones. The
/// first pass only estimates where the light goes, and its power scale is
/// the emission and direct light's, before the many bounces of a
/// high-albedo medium multiply it: at 10x coarser, the 61-mfp cube at 64^3
/// had more links in the first pass (41 M) than in the second (26 M). At
/// 100x: the same G on the test scenes, 15-30% less time, the cube's
/// peak memory 29% lower. At 300x: G within 0.04 points of 100x's on the
/// accuracy scenes, 8-20% less time again at 32^3-64^3 (fewer first-pass
/// links to refine, balance and iterate over); 1000x gave no more.
constexpr double kFirstPassCoarsening = 300.0;

/// The default link tolerance per unit of epsilon (HierarchicalOptions).
constexpr double kLinkToleranceOfEpsilon = 3e-4;

/// A converged solve whose energy terms miss each other by more than this
/// share of the light is no solution but an operator that amplifies light
/// (thick bone once made one: energy terms of 1e10 on the CT head); the
/// solver's own imbalance is under 1e-3 on the test scenes and the
/// benchmarks (the iterations hold the unshot power under epsilon).
constexpr double kMaxConvergedResidual = 0.5;

/// Deterministic parallel reductions: the same split whatever the threads.
template<class F>
double reduceSum(Index n, F&& f)
{
  return tbb::parallel_deterministic_reduce(
    tbb::blocked_range<Index>(0, n, 4096),
    0.0,
    [&](const tbb::blocked_range<Index>& r, double acc) {
      for (Index i = r.begin(); i != r.end(); ++i) {
        acc += f(i);
      }
      return acc;
    },
    std::plus<double>());
}

double maxAbs(const Vector& v)
{
  return tbb::parallel_deterministic_reduce(
    tbb::blocked_range<Index>(0, v.size(), 4096),
    0.0,
    [&](const tbb::blocked_range<Index>& r, double m) {
      for (Index i = r.begin(); i != r.end(); ++i) {
        m = std::max(m, std::abs(v[i]));
      }
      return m;
    },
    [](double a, double b) { return std::max(a, b); });
}

/// Everything one channel's solve shares: the near field, the hierarchy,
/// the links and the equations, with y = M x the scattered response of
/// every element to radiosities x (self terms implicit).
struct ChannelOperator
{
  const Scene& scene;
  const NearField& near;
  int ch;
  Vector gain;                   // c / (1 - c S_self): the self term implicit
  const FarField* far = nullptr; // shared by the channels of one geometry

  /// The power of radiosities v in the equations' own terms: |v| times
  /// each element's power per unit radiosity (its exchange row's target)
  /// times 1 - c S_self = 1 / (1 + gain S_self), since the self term is
  /// implicit (x0 and the residuals are the zonal equations' divided by
  /// it). Of x0, the power first shot; of a residual, the power the
  /// energy balance misses. Without the factor a thick, high-albedo voxel
  /// (1 - c S_self down to 0.01) would count a hundred times its share.
  double power(const Vector& v) const
  {
    const ExchangeElements& el = near.elements;
    return reduceSum(v.size(), [&](Index e) {
      return v[e] != 0.0 ? std::abs(v[e]) * exchangeRowTarget(scene, ch, el, e) /
                             (1.0 + gain[e] * near.diagonal(e))
                         : 0.0;
    });
  }

  /// `progress` hears within the far field's sweep (and may abort).
  Vector apply(const Vector& x, const ProgressRange& progress) const
  {
    Vector y = Vector::Zero(x.size());
    near.apply(scene.grid, x.data(), y.data(), true);
    far->apply(x.data(), y.data(), nullptr, progress);
    scaleByGain(y);
    return y;
  }

  void scaleByGain(Vector& y) const
  {
    tbb::parallel_for(Index(0), Index(y.size()), [&](Index e) {
      y[e] *= gain[e];
    });
  }

  /// (I - N)^-1 v to second order, v + N v + N^2 v, N = gain * near field:
  /// the Krylov solve's right preconditioner. In a high-albedo medium most
  /// of a voxel's scattered light lands in its near field, so two stencil
  /// sweeps each time the operator is applied save many applications
  /// (cloud 32^3: 53 -> 29); always the same linear map, as BiCGSTAB
  /// needs. Two vectors while it runs, one returned.
  Vector nearSeries(const Vector& v) const
  {
    auto applyN = [&](const Vector& x) {
      Vector y = Vector::Zero(x.size());
      near.apply(scene.grid, x.data(), y.data(), true);
      scaleByGain(y);
      return y;
    };
    const Vector nv = applyN(v);
    Vector z = applyN(nv);
    z += nv + v;
    return z;
  }
};

/// Largest radiosity under every tree node, each element's at least
/// `floor`: the far field's balancing relies on every link's row sums, so
/// the links between dark elements must not be arbitrarily coarse.
std::vector<float> nodeRadiosity(const ClusterTree& tree,
                                 const ExchangeElements& el,
                                 const Vector& x,
                                 double floor)
{
  std::vector<float> r(tree.size(), 0.f);
  const Grid& g = tree.grid(0);
  for (Index v = 0; v < g.voxelCount(); ++v) {
    if (el.full[v] < 0) {
      continue;
    }
    double m = std::max(floor, x[el.full[v]]);
    if (el.front[v] >= 0) {
      m = std::max(m, x[el.front[v]]);
    }
    r[v] = float(m);
  }
  for (Index p = 0; p < g.patchCount(); ++p) {
    r[tree.patchNode(0, p)] = float(std::max(floor, x[el.patchElement(p)]));
  }
  for (int l = 1; l < tree.levels(); ++l) {
    for (const bool patches : { false, true }) {
      const Index count = patches ? tree.grid(l).patchCount() : tree.grid(l).voxelCount();
      for (Index c = 0; c < count; ++c) {
        const Index node = patches ? tree.patchNode(l, c) : tree.voxelNode(l, c);
        std::array<Index, 8> kids;
        const int k = tree.children(node, kids);
        float m = 0.f;
        for (int i = 0; i < k; ++i) {
          m = std::max(m, r[kids[i]]);
        }
        r[node] = m;
      }
    }
  }
  return r;
}

/// Per node without medium: the least direct incident radiation of its
/// voxels (track / V) times `scale` per voxel of its box (the count the
/// links' error estimate gives it), the direct power the node's views
/// would intercept (LinkRefinement::viewLight); 0 where there is medium.
std::vector<float> viewDirectPower(const ClusterTree& tree, const std::vector<float>& track, double scale)
{
  std::vector<float> least(tree.size(), 0.f); // per voxel, the least under each node
  const Grid& g = tree.grid(0);
  const double perVoxel = scale / g.voxelVolume();
  for (Index v = 0; v < g.voxelCount(); ++v) {
    least[v] = tree.sigma(v) > 0.0 ? 0.f : float(track[v] * perVoxel);
  }
  std::vector<float> d = least;
  for (int l = 1; l < tree.levels(); ++l) {
    for (Index c = 0; c < tree.grid(l).voxelCount(); ++c) {
      const Index node = tree.voxelNode(l, c);
      if (tree.sigma(node) > 0.0) {
        continue;
      }
      std::array<Index, 8> kids;
      const int k = tree.children(node, kids);
      float m = k > 0 ? std::numeric_limits<float>::max() : 0.f;
      for (int i = 0; i < k; ++i) {
        m = std::min(m, least[kids[i]]);
      }
      const auto e = tree.box(node).extent();
      least[node] = m;
      d[node] = m * float(e[0]) * float(e[1]) * float(e[2]);
    }
  }
  return d;
}

struct IterationState
{
  Vector x, dx; // radiosity and its unshot part

  /// Largest change relative to each element's radiosity (a floor of
  /// 1e-3 of the largest keeps dark elements from ruling).
  double change(const Vector& v) const
  {
    const double floor = 1e-3 * maxAbs(x);
    return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, v.size(), 4096),
      0.0,
      [&](const tbb::blocked_range<Index>& r, double m) {
        for (Index i = r.begin(); i != r.end(); ++i) {
          if (v[i] != 0.0) {
            m = std::max(m, std::abs(v[i]) / (std::abs(x[i]) + floor));
          }
        }
        return m;
      },
      [](double a, double b) { return std::max(a, b); });
  }
  /// The power x0 shoots first (emission and the direct light's first
  /// scattering): the scale of the power still unshot.
  double firstPower = 0.0;
  /// The power of v (what is still unshot, or the residual) relative to
  /// it: the share of the light whose absorption or escape the fields
  /// would still miss, the energy balance's residual.
  /// (NaN when the powers are not finite: the iterations then stop,
  /// unconverged, instead of sweeping on to maxIterations.)
  double unshotShare(const ChannelOperator& op, const Vector& v) const
  {
    if (firstPower == 0.0) {
      return 0.0; // no light: nothing to shoot
    }
    return std::isfinite(firstPower) ? op.power(v) / firstPower
                                     : std::numeric_limits<double>::quiet_NaN();
  }
  long long iterations = 0, shots = 0;
  bool converged = false;
  /// Progress of the iterations: how far the change fell from the first
  /// one towards epsilon, on a log scale.
  double first = -1.0, reported = 0.0;
  void reportChange(double change, double epsilon, const ProgressRange& progress)
  {
    first = first < 0.0 ? change : first;
    if (first > epsilon && change > 0.0) {
      reported = std::clamp(std::log(first / change) / std::log(first / epsilon), reported, 1.0);
    }
    progress.report(reported);
  }
};

/// Sweeps of shooting; returns false when they are slow (Automatic mode).
bool shoot(const ChannelOperator& op,
           IterationState& s,
           double epsilon,
           int maxIterations,
           bool stopWhenStalling,
           HierarchicalReport& report,
           const ProgressRange& progress)
{
  double previous = s.change(s.dx), ratio = 0.0;
  double share = s.unshotShare(op, s.dx);
  s.reportChange(std::max(previous, share), epsilon, progress);
  int slow = 0;
  while (s.iterations < maxIterations) {
    // What is still unshot, and what the sweeps it will take still add
    // (a geometric tail of the observed contraction ratio); and the
    // power still unshot, which the energy balance misses.
    const double tail = ratio < 1.0 ? std::max(1.0, ratio / (1.0 - ratio)) : 1e30;
    if (!std::isfinite(share)) {
      return true; // not converged, and no Krylov solve will mend it
    }
    if (previous * tail <= epsilon && share <= epsilon) {
      s.converged = true;
      return true;
    }
    s.shots +=
      (long long)reduceSum(s.dx.size(), [&](Index e) { return s.dx[e] != 0.0 ? 1.0 : 0.0; });
    s.dx = op.apply(s.dx, progress.sub(s.reported, s.reported));
    s.x += s.dx;
    ++s.iterations;
    const double now = s.change(s.dx);
    share = s.unshotShare(op, s.dx);
    report.dQmaxHistory.push_back(now);
    s.reportChange(std::max(now, share), epsilon, progress);
    ratio = previous > 0.0 ? now / previous : 0.0;
    // Slow: less than 40% of the unshot light goes per sweep. BiCGSTAB (two
    // sweeps' work per step) then converges in fewer sweeps' work: measured
    // 2x less iteration time on the phantom and point-light scenes, the
    // same G (at "less than 10%" they stayed with shooting).
    slow = ratio > 0.6 ? slow + 1 : 0;
    previous = now;
    if (stopWhenStalling && slow >= 3) {
      return false;
    }
  }
  return true;
}

/// BiCGSTAB on (I - M) x = x0 from the current x, right-preconditioned by
/// ChannelOperator::nearSeries (so r stays the true residual that the
/// stopping test reads); dx becomes the residual (what the next sweep would
/// shoot).
void krylov(const ChannelOperator& op,
            const Vector& x0,
            IterationState& s,
            double epsilon,
            int maxIterations,
            HierarchicalReport& report,
            const ProgressRange& progress)
{
  auto A = [&](const Vector& v) -> Vector {
    Vector y = op.apply(v, progress.sub(s.reported, s.reported));
    y = v - y; // in place: one temporary, not two
    return y;
  };
  auto dot = [](const Vector& a, const Vector& b) {
    return reduceSum(a.size(), [&](Index i) { return a[i] * b[i]; });
  };
  report.usedKrylov = true;
  // Vectors of elements are the iterations' memory (8 bytes an element:
  // 134 MB or more at 256^3): dx is remade at the end, and s = r - alpha v
  // is made in r's place.
  s.dx = Vector();
  Vector r = x0 - A(s.x);
  const Vector r0 = r;
  Vector p = Vector::Zero(r.size()), v = Vector::Zero(r.size());
  double rho = 1.0, alpha = 1.0, omega = 1.0;
  while (s.iterations < maxIterations) {
    // The residual is what the next sweep would shoot: both its change
    // and its power (in a 0.99-albedo medium the power of a residual
    // 1e-3 of the radiosities is several percent of the light).
    const double res = s.change(r), share = s.unshotShare(op, r);
    report.dQmaxHistory.push_back(res);
    s.reportChange(std::max(res, share), epsilon, progress);
    if (!std::isfinite(share)) {
      break; // not converged
    }
    if (res <= epsilon && share <= epsilon) {
      s.converged = true;
      break;
    }
    const double rho1 = dot(r0, r);
    if (rho1 == 0.0) {
      break;
    }
    const double beta = (rho1 / rho) * (alpha / omega);
    p = r + beta * (p - omega * v);
    {
      const Vector ph = op.nearSeries(p);
      v = A(ph);
      alpha = rho1 / dot(r0, v);
      s.x += alpha * ph;
    }
    r -= alpha * v; // s
    s.iterations += 1;
    const double half = s.change(r);
    if (half <= epsilon && s.unshotShare(op, r) <= epsilon) {
      report.dQmaxHistory.push_back(half);
      s.converged = true;
      break;
    }
    const Vector sh = op.nearSeries(r);
    const Vector t = A(sh);
    const double tt = dot(t, t);
    omega = tt > 0.0 ? dot(t, r) / tt : 0.0;
    s.x += omega * sh;
    r -= omega * t;
    rho = rho1;
    s.iterations += 1;
    if (omega == 0.0) {
      break;
    }
  }
  s.dx = r;
}

} // namespace

Solution solveHierarchical(const Scene& scene,
                           const HierarchicalOptions& opt,
                           HierarchicalReport* reportOut)
{
  const auto start = Clock::now();
  scene.validate();
  if (!(opt.epsilon > 0.0) || !(opt.linkTolerance >= 0.0) || opt.maxIterations < 1 ||
      opt.nearRadius < 1 || opt.nearRadius > 3) {
    throw Error("hierarchical solver: epsilon must be > 0, linkTolerance >= 0, maxIterations >= 1 "
                "and the near radius 1 to 3");
  }
  // Memory: what every voxel costs whatever the links (near-field stencil,
  // element vectors, hierarchy, direct light, fields), then the links.
  const double memoryLimit =
    opt.memoryLimitBytes > 0.0 ? opt.memoryLimitBytes : 0.5 * double(physicalMemoryBytes());
  const double linkTolerance = opt.linkTolerance > 0.0 ? opt.linkTolerance : opt.epsilon * kLinkToleranceOfEpsilon;
  // Voxels with links and near rows: those holding medium (in some channel),
  // and the empty ones too unless their fields are skipped.
  Index mediumVoxels = 0, frontSides = 0;
  for (Index v = 0; v < scene.grid.voxelCount(); ++v) {
    bool medium = false;
    for (int c = 0; c < scene.channels && !medium; ++c) {
      medium = scene.kappaTAt(v, c) > 0.0;
    }
    mediumVoxels += medium ? 1 : 0;
    frontSides += medium && needsFrontSide(scene, v) ? 1 : 0;
  }
  const double linkedVoxels = double(opt.emptySpaceFields ? scene.grid.voxelCount() : mediumVoxels);
  // What the solve holds before its links, the caller's scene included:
  // per voxel of the grid (coefficients, normals, element indices, pyramid,
  // tree, direct light) and per element (near-field stencil, far weight,
  // each channel's vectors). Resident memory measured before the link
  // refinement, less the process's own: one channel 125 bytes a voxel and
  // 130 an element (phantom, cloud and cube at 128^3; the phantom 120 + 32
  // of scene at 256^3), RGB 253 a voxel of the smoke's box in all, the CT
  // head (RGB, front sides) 523; 1.25 times that for what is not measured.
  // The solution's fields are allocated once the links are gone.
  const int C = scene.channels;
  const double elements = double(mediumVoxels + frontSides + scene.grid.patchCount());
  const double baseBytes =
    1.25 * ((70.0 + 55.0 * C + (scene.normals.empty() ? 0.0 : sizeof(Normal))) *
              double(scene.grid.voxelCount()) +
            (sizeof(float) * NearField::stencilHalfFor(opt.nearRadius) + 40.0 + 40.0 * C) *
              elements);
  const double fieldBytes = 5.0 * sizeof(double) * C * double(scene.grid.voxelCount());
  // The fewest links a voxel needs: at the default tolerance (3e-7) the
  // fewest measured are 37 a voxel (the smoke at 111x222x112, 2.8 M voxels;
  // the phantom at 128^3 50, the cube 71), and about 2.2x fewer per decade
  // of tolerance. The floor is about half the fewest: a solve that would
  // surely pass the budget is refused now, not after its near field; the
  // others are stopped in the refinement if they do. Past 128^3 voxels the
  // floor is one of links, not of links a voxel: the tolerance is a
  // fraction of the whole scene's power, so links a voxel fall on finer
  // grids (the phantom: 1180 at 32^3, 370 at 64^3, 50 at 128^3, 16 at
  // 256^3), and a floor of 20 a voxel refused the phantom at 256^3 at once
  // (342 M links), which then needed 276 M and 7.7 GiB.
  const double perVoxel = std::min(1.0, kFewestLinksFlatFrom / linkedVoxels);
  const double fewestLinks =
    linkedVoxels * perVoxel * std::max(5.0, 30.0 * std::pow(1e-7 / linkTolerance, 0.35));
  const double linkBytes = std::max(fewestLinks * double(kBytesPerLink), fieldBytes);
  if (baseBytes + linkBytes > memoryLimit) {
    std::ostringstream msg;
    msg << "the hierarchical solve of " << scene.grid.voxelCount() << " voxels needs at least "
        << std::llround((baseBytes + linkBytes) / (1 << 20)) << " MiB ("
        << std::llround(baseBytes / (1 << 20)) << " MiB before any link, "
        << std::llround(linkBytes / (1 << 20)) << " MiB for the fewest links it may need or, if more, its fields), over "
        << "its memory budget of " << memoryLimit / double(1 << 20)
        << " MiB: raise solver.epsilon or the budget, or shrink the volume";
    throw Error(msg.str());
  }
  const std::size_t maxLinks = std::size_t((memoryLimit - baseBytes) / double(kBytesPerLink));
  HierarchicalReport report;
  const Grid& g = scene.grid;
  const Index nv = g.voxelCount();
  // The fields (5 doubles a voxel and channel) are allocated once the first
  // group's links are gone: not at the solve's peak, the link refinement.
  Solution sol = emptySolution(scene, "hierarchical", false);

  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  const ProgressRange progress(opt.progress, 0.0, 1.0);
  const double V = g.voxelVolume();
  NearFieldOptions nearOptions;
  nearOptions.radius = opt.nearRadius;
  nearOptions.quadrature = opt.quadrature;
  // The empty voxels' views serve only the fields: they are computed once
  // the links are gone (at 256^3 the cloud's, about 0.3 GB, were held beside them).
  nearOptions.emptyViews = false;
  // Large grids: fewer lines per heterogeneous voxel (homogeneous
  // neighbourhoods keep the fine shared quadrature).
  if (nv > 64 * 64 * 64) {
    nearOptions.quadrature.voxelPointsPerAxis =
      std::min(nearOptions.quadrature.voxelPointsPerAxis, 2);
  }

  // Channels with the same extinction everywhere (a grey medium under
  // coloured light; every material preset) share the geometry: near field,
  // hierarchy, links and far field. Only their sources and albedos differ.
  std::vector<std::vector<int>> groups;
  {
    bool grey = C > 1;
    for (Index v = 0; v < nv && grey; ++v) {
      for (int c = 1; c < C && grey; ++c) {
        grey = scene.kappaTAt(v, c) == scene.kappaTAt(v, 0);
      }
    }
    for (int c = 0; c < C; ++c) {
      if (grey && c > 0) {
        groups[0].push_back(c);
      } else {
        groups.push_back({ c });
      }
    }
  }

  /// One channel's equations over a shared geometry; op refers to sys, so a
  /// Channel is made in place and never moved.
  struct Channel
  {
    Channel(int c, const DirectLighting& dl, ZonalSystem&& s, const Scene& scene, const NearField& near)
      : track(dl.track.begin(), dl.track.end())
      , trackFront(dl.trackFront.begin(), dl.trackFront.end())
      , entering(dl.entering)
      , sys(std::move(s))
      , op{ scene, near, c, Vector::Zero(sys.e.size()), nullptr }
    {
    }
    /// The direct light's tracks, for the fields at the end: in float
    /// (their doubles were 0.4 GB at 256^3 in three channels, held
    /// through the whole solve).
    std::vector<float> track, trackFront;
    double entering;
    ZonalSystem sys;
    ChannelOperator op;
    Vector x0;
    IterationState state;
  };

  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const std::vector<int>& chans = groups[gi];
    const int K = int(chans.size());
    const ProgressRange gp =
      progress.sub(double(gi) / groups.size(), double(gi + 1) / groups.size());
    arena.execute([&] {
      auto t = Clock::now();
      const NearField near = computeNearField(scene, chans[0], nearOptions, gp.sub(0.0, 0.3));
      report.nearSeconds += since(t);
      const ExchangeElements& el = near.elements;
      const Index n = el.size();
      // Between the steps that report nothing themselves: a chance to abort.
      const ProgressRange setup = gp.sub(0.3, 0.3);
      const VoxelPyramid pyramid(scene, chans[0]);
      setup.report(1.0);
      const ClusterTree tree(scene, chans[0], pyramid);
      setup.report(1.0);

      // Empty voxels' views are refined as if they held the mean medium
      // (one optical depth per voxel in a vacuum).
      double viewSigma = effectiveCrossSection(1.0 / g.spacing.minCoeff(), g.spacing);
      {
        double sum = 0.0;
        Index count = 0;
        for (Index v = 0; v < nv; ++v) {
          if (tree.sigma(v) > 0.0) {
            sum += tree.sigma(v);
            ++count;
          }
        }
        if (count > 0) {
          viewSigma = sum / double(count);
        }
      }

      // A view of lit empty space may carry wrongly epsilon of the direct
      // power it receives (LinkRefinement::viewLight; with the link
      // tolerance set, in the same ratio to it as the default's): it changes
      // only that voxel's G, of which the direct light is already exact.
      const double viewTolerance = linkTolerance / kLinkToleranceOfEpsilon;

      // Each channel's equations (Channel holds references into itself: not moved).
      std::vector<std::unique_ptr<Channel>> channels;
      for (const int ch : chans) {
        DirectLighting dl = computeDirectLight(scene, ch, opt.quadrature, setup);
        setup.report(1.0);
        ZonalSystem sys = buildZonalSystem(scene, ch, el, dl);
        setup.report(1.0);
        auto c = std::make_unique<Channel>(ch, dl, std::move(sys), scene, near);
        c->x0 = c->sys.e;
        for (Index e = 0; e < n; ++e) {
          const double scatter = c->sys.c[e];
          if (scatter > 0.0) {
            const double denominator = 1.0 - scatter * near.diagonal(e);
            if (!(denominator > 1e-12)) {
              throw Error(
                "the hierarchical solve is singular: an element scatters back all it emits");
            }
            c->op.gain[e] = scatter / denominator;
            c->x0[e] = (c->sys.e[e] + scatter * c->sys.D[e]) / denominator;
          }
        }
        // Only D (the fields' direct light) is needed from here on.
        c->sys.e.resize(0);
        c->sys.c.resize(0);
        c->state.x = c->x0;
        c->state.dx = c->x0;
        c->state.firstPower = c->op.power(c->x0);
        channels.push_back(std::move(c));
      }

      LinkSet links;
      std::unique_ptr<FarField> far;
      for (int pass = 0; pass < 2; ++pass) {
        t = Clock::now();
        LinkRefinement refinement;
        refinement.nearRadius = opt.nearRadius;
        // The first pass only estimates where the light goes: coarser links.
        refinement.tolerance = pass == 0 ? kFirstPassCoarsening * linkTolerance : linkTolerance;
        refinement.viewSigma = viewSigma;
        // The first pass's solution, all it is for, takes nothing from the
        // views of empty space: they wait for the second.
        refinement.emptyViews = opt.emptySpaceFields && pass == 1;
        refinement.maxLinks = std::max<std::size_t>(1, maxLinks);
        // Links serve every channel: each node's radiosity relative to its
        // channel's total power, the largest over the channels.
        refinement.powerScale = 1.0;
        refinement.radiosity.assign(tree.size(), 0.f);
        for (const auto& c : channels) {
          const Vector& x = c->state.x;
          const double power = std::max(
            1e-300, reduceSum(n, [&](Index e) {
                       return el.isFront(e) ? 0.0 : x[e] * exchangeRowTarget(scene, chans[0], el, e);
                     }));
          const std::vector<float> r = nodeRadiosity(tree, el, x, kRadiosityFloor * maxAbs(x));
          for (Index k = 0; k < tree.size(); ++k) {
            refinement.radiosity[k] = std::max(refinement.radiosity[k], float(r[k] / power));
          }
          if (refinement.emptyViews) {
            const std::vector<float> d = viewDirectPower(tree, c->track, viewSigma / power);
            if (refinement.viewLight.empty()) {
              refinement.viewLight = d;
            } else {
              for (Index k = 0; k < tree.size(); ++k) {
                refinement.viewLight[k] = std::min(refinement.viewLight[k], d[k]);
              }
            }
          }
        }
        refinement.viewTolerance = viewTolerance;
        // The first pass's links go before the second pass refines: both
        // at once would be the solve's peak.
        far.reset();
        links = LinkSet();
        links = refineLinks(tree, refinement, gp.sub(0.3 + 0.1 * pass, 0.33 + 0.1 * pass));
        far = std::make_unique<FarField>(
          scene, tree, links, near, gp.sub(0.33 + 0.1 * pass, 0.35 + 0.1 * pass));
        report.linkSeconds += since(t);
        report.peakBytes =
          std::max(report.peakBytes,
                   near.bytes() + tree.bytes() + pyramid.grid(0).voxelCount() * 3 * sizeof(float) +
                     links.bytes() + far->bytes() + std::size_t(n) * (2 + 6 * K) * sizeof(double));
        t = Clock::now();
        for (int k = 0; k < K; ++k) {
          Channel& c = *channels[k];
          c.op.far = far.get();
          const double eps = pass == 0 ? std::max(opt.epsilon, 1e-2) : opt.epsilon;
          const double a = pass == 0 ? 0.35 : 0.5, b = pass == 0 ? 0.4 : 0.95;
          const ProgressRange ip = gp.sub(a + (b - a) * k / K, a + (b - a) * (k + 1) / K);
          c.state.first = -1.0;
          c.state.reported = 0.0;
          if (pass == 1) {
            // Continue with the finer links: the change they make is added
            // and becomes the unshot radiosity.
            c.state.dx = c.x0 + c.op.apply(c.state.x, ip.sub(0.0, 0.0)) - c.state.x;
            c.state.x += c.state.dx;
          }
          bool done = false;
          if (opt.iteration != HierarchicalOptions::Iteration::Krylov) {
            done = shoot(c.op,
                         c.state,
                         eps,
                         opt.maxIterations,
                         opt.iteration == HierarchicalOptions::Iteration::Automatic,
                         report,
                         ip);
          }
          if (!done) {
            krylov(c.op, c.x0, c.state, eps, opt.maxIterations, report, ip);
          }
        }
        report.iterationSeconds += since(t);
      }
      sol.stats.links +=
        links.pairs + static_cast<long long>(std::size_t(el.fullCount) * near.stencilSize() / 2 +
                                             near.extraValue.size() / 2);
      if (report.linksPerLevel.size() < links.pairsPerLevel.size()) {
        report.linksPerLevel.resize(links.pairsPerLevel.size(), 0);
      }
      for (std::size_t l = 0; l < links.pairsPerLevel.size(); ++l) {
        report.linksPerLevel[l] += links.pairsPerLevel[l];
      }

      // Every channel's collided power C = S x + D and far views of the
      // voxels that are not elements (none in a sparse solve) first: then
      // the links go before the fields are allocated.
      std::vector<Vector> collidedOf(channels.size());
      std::vector<std::vector<double>> farViewOf(channels.size());
      for (std::size_t k = 0; k < channels.size(); ++k) {
        const Channel& c = *channels[k];
        collidedOf[k] = c.sys.D;
        farViewOf[k].assign(opt.emptySpaceFields ? nv : 0, 0.0);
        near.apply(g, c.state.x.data(), collidedOf[k].data(), false);
        far->apply(c.state.x.data(),
                   collidedOf[k].data(),
                   opt.emptySpaceFields ? farViewOf[k].data() : nullptr,
                   gp.sub(0.95, 0.95));
      }
      far.reset();
      links = LinkSet();
      ViewRows views;
      if (opt.emptySpaceFields) {
        t = Clock::now();
        views = computeViewRows(scene, chans[0], el, nearOptions, gp.sub(0.95, 0.98));
        report.nearSeconds += since(t);
      }
      if (sol.G.empty()) {
        allocateFields(scene, sol);
      }

      for (std::size_t k = 0; k < channels.size(); ++k) {
        const Channel& c = *channels[k];
        const int ch = c.op.ch;
        sol.stats.converged = sol.stats.converged && c.state.converged;
        sol.stats.iterations += c.state.iterations;
        sol.stats.finalUnshot = std::max(sol.stats.finalUnshot, maxAbs(c.state.dx));
        report.shots += c.state.shots;
        const Vector& collided = collidedOf[k];
        const std::vector<double>& farView = farViewOf[k];
        const Vector& x = c.state.x;
        storeChannelFields(
          scene,
          ch,
          el,
          x,
          collided,
          [&](Index v) {
            if (!opt.emptySpaceFields) {
              return 0.0; // not asked for (a sparse solve)
            }
            double s = farView[v] + c.track[v] / V;
            for (Index k = views.start[v]; k < views.start[v + 1]; ++k) {
              s += views.value[k] * x[views.column[k]];
            }
            return s;
          },
          [&](Index v) {
            // No front side: half of the scattered light, the direct light exactly.
            const std::size_t o = std::size_t(v) * C + ch;
            if (!opt.emptySpaceFields && el.full[v] < 0) {
              return 0.0;
            }
            return 0.5 * (sol.G[o] - c.track[v] / V) + c.trackFront[v] / V;
          },
          sol);
        sol.energy[ch] = computeEnergyTerms(scene, ch, sol, c.entering);
      }
    });
  }
  for (std::size_t ch = 0; ch < sol.energy.size(); ++ch) {
    const double r = sol.energy[ch].relativeResidual();
    // (Non-finite terms come from fields beyond double's range, which the
    // output's own check names.)
    if (sol.stats.converged && std::isfinite(r) && r > kMaxConvergedResidual) {
      std::ostringstream m;
      m.precision(3);
      m << "hierarchical solver: the solution's energy does not balance (residual " << r
        << " in channel " << ch << "): its exchange factors amplify light here; use the dense "
        << "solver";
      throw Error(m.str());
    }
  }
  progress.report(1.0);
  sol.stats.seconds = since(start);
  sol.stats.estimatedBytes = report.peakBytes;
  if (reportOut) {
    *reportOut = std::move(report);
  }
  return sol;
}

} // namespace volrad
