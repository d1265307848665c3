// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/MonteCarlo.h"

#include "volrad/Error.h"
#include "volrad/Sampling.h"
#include "volrad/VoxelTraversal.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace volrad {

namespace {

struct Source
{
  enum class Kind
  {
    VoxelIsotropic,
    VoxelHemispherical,
    Patch,
    Directional,
    Point
  } kind;
  Index id = 0;       ///< voxel, patch, face or light
  double power = 0.0; ///< [W]
  Vec3 direction{ 0, 0, 0 };
  double cosMax = -1.0; ///< point lights: cone of directions that can reach the domain
};

struct Photon
{
  Vec3 x, w;
};

class ChannelTracer
{
public:
  ChannelTracer(const Scene& s, int ch, bool zonal)
    : scene_(s)
    , g_(s.grid)
    , ch_(ch)
    , zonal_(zonal)
  {
    kt_ = s.extinction(ch);
    buildSources();
  }

  double totalPower() const { return total_; }

  /// Traces n photons and adds their track lengths (unnormalised) to G, Gp.
  void trace(long long n, Rng& rng, std::vector<double>& G, std::vector<double>& Gp) const
  {
    for (long long i = 0; i < n; ++i) {
      Photon ph;
      if (emit(rng, ph)) {
        walk(ph, rng, G, Gp);
      }
    }
  }

private:
  void add(Source s)
  {
    if (s.power > 0.0) {
      total_ += s.power;
      sources_.push_back(s);
      cdf_.push_back(total_);
    }
  }

  bool open(Face f) const
  {
    return scene_.boundary[static_cast<int>(f)].type == BoundaryCondition::Type::Open;
  }

  void buildSources()
  {
    const double V = g_.voxelVolume();
    for (Index v = 0; v < g_.voxelCount(); ++v) {
      const double ka = scene_.kappaAAt(v, ch_);
      add({ Source::Kind::VoxelIsotropic, v, 4.0 * ka * scene_.emissionIAt(v, ch_) * V });
      add({ Source::Kind::VoxelHemispherical, v, 2.0 * ka * scene_.emissionDAt(v, ch_) * V });
    }
    for (Index p = 0; p < g_.patchCount(); ++p) {
      const Face f = g_.patchLocation(p).face;
      const BoundaryCondition& bc = scene_.boundary[static_cast<int>(f)];
      const double exitance =
        bc.type == BoundaryCondition::Type::Wall ? bc.emission[ch_] : kPi * bc.radiance[ch_];
      add({ Source::Kind::Patch, p, exitance * g_.patchArea(f) });
    }
    for (const auto& l : scene_.directionalLights) {
      const Vec3 d = l.direction.stableNormalized();
      for (int fi = 0; fi < kFaceCount; ++fi) {
        const double cosIn = d.dot(faceInwardNormal(Face(fi)));
        if (cosIn > 0.0 && open(Face(fi))) {
          add({ Source::Kind::Directional,
                fi,
                l.irradiance[ch_] * cosIn * g_.faceArea(Face(fi)),
                d });
        }
      }
    }
    const Vec3 lo = g_.lower(), hi = g_.upper();
    const Vec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * (hi - lo).norm();
    for (std::size_t i = 0; i < scene_.pointLights.size(); ++i) {
      const auto& l = scene_.pointLights[i];
      const Vec3 to = centre - l.position;
      const double dist = to.norm();
      const double cosMax =
        dist > radius ? std::sqrt(1.0 - (radius / dist) * (radius / dist)) : -1.0;
      const Vec3 axis = dist > 0.0 ? Vec3(to / dist) : Vec3::UnitZ();
      add({ Source::Kind::Point,
            Index(i),
            l.intensity[ch_] * 2.0 * kPi * (1.0 - cosMax),
            axis,
            cosMax });
    }
  }

  bool emit(Rng& rng, Photon& ph) const
  {
    if (sources_.empty()) {
      return false;
    }
    const double u = rng.uniform() * total_;
    const std::size_t k = std::min<std::size_t>(
      std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), sources_.size() - 1);
    const Source& s = sources_[k];
    switch (s.kind) {
      case Source::Kind::VoxelIsotropic:
      case Source::Kind::VoxelHemispherical: {
        const Vec3 lo = g_.voxelLower(s.id);
        ph.x = lo + Vec3(rng.uniform() * g_.spacing[0],
                         rng.uniform() * g_.spacing[1],
                         rng.uniform() * g_.spacing[2]);
        ph.w = s.kind == Source::Kind::VoxelIsotropic
                 ? sampleSphere(rng)
                 : sampleHemisphereUniform(scene_.normalAt(s.id).normalized(), rng);
        return true;
      }
      case Source::Kind::Patch: {
        const Face f = g_.patchLocation(s.id).face;
        const auto ax = faceAxesInPlane(f);
        ph.x = g_.patchLower(s.id);
        ph.x[ax[0]] += rng.uniform() * g_.spacing[ax[0]];
        ph.x[ax[1]] += rng.uniform() * g_.spacing[ax[1]];
        ph.w = sampleHemisphereCosine(faceInwardNormal(f), rng);
        return true;
      }
      case Source::Kind::Directional: {
        const Face f = Face(s.id);
        const auto ax = faceAxesInPlane(f);
        const Vec3 lo = g_.lower(), hi = g_.upper();
        ph.x = lo;
        ph.x[faceAxis(f)] = faceIsMax(f) ? hi[faceAxis(f)] : lo[faceAxis(f)];
        ph.x[ax[0]] += rng.uniform() * (hi[ax[0]] - lo[ax[0]]);
        ph.x[ax[1]] += rng.uniform() * (hi[ax[1]] - lo[ax[1]]);
        ph.w = s.direction;
        return true;
      }
      case Source::Kind::Point: {
        const double cosT = 1.0 - rng.uniform() * (1.0 - s.cosMax);
        const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        const double phi = 2.0 * kPi * rng.uniform();
        ph.w = frameAround(s.direction) * Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
        ph.x = scene_.pointLights[s.id].position;
        double t0, t1;
        Face entry;
        if (!clipToDomain(g_, ph.x, ph.w, t0, t1, &entry) || t1 <= std::max(t0, 0.0)) {
          return false; // misses the domain
        }
        if (t0 > 0.0) {
          if (!open(entry)) {
            return false; // blocked by a wall
          }
          ph.x += ph.w * t0;
        }
        return true;
      }
    }
    return false;
  }

  void walk(Photon ph, Rng& rng, std::vector<double>& G, std::vector<double>& Gp) const
  {
    const bool normals = !scene_.normals.empty();
    for (int event = 0; event < 100000; ++event) {
      double tau = -std::log(1.0 - rng.uniform());
      bool collided = false;
      Index where = -1;
      double tCollision = 0.0;
      const Vec3 w = ph.w;
      auto tally = [&](Index v, double l) {
        G[v] += l;
        if (normals && scene_.normalDot(v, w) < 0.0) {
          Gp[v] += l;
        }
      };
      const DomainExit exit = traverseVoxels(
        g_, ph.x, w, std::numeric_limits<double>::infinity(), [&](Index v, double l, double t0) {
          const double k = kt_[v];
          if (k > 0.0 && k * l >= tau) {
            const double s = tau / k;
            tally(v, s);
            collided = true;
            where = v;
            tCollision = t0 + s;
            return false;
          }
          tau -= k * l;
          tally(v, l);
          return true;
        });
      if (collided) {
        ph.x += w * tCollision;
        if (zonal_) {
          ph.x = g_.voxelLower(where) + Vec3(rng.uniform() * g_.spacing[0],
                                             rng.uniform() * g_.spacing[1],
                                             rng.uniform() * g_.spacing[2]);
        }
        const double u = rng.uniform() * kt_[where];
        const double ka = scene_.kappaAAt(where, ch_), si = scene_.sigmaIAt(where, ch_);
        if (u < ka) {
          return;
        }
        if (u < ka + si) {
          ph.w = sampleSphere(rng);
          continue;
        }
        const Vec3 n = scene_.normalAt(where).normalized();
        if (n.dot(w) >= 0.0) {
          return; // arrived from the back side: absorbed
        }
        ph.w = sampleHemisphereUniform(n, rng);
        continue;
      }
      if (!exit.exited || open(exit.face)) {
        return; // escaped
      }
      const BoundaryCondition& bc = scene_.boundary[static_cast<int>(exit.face)];
      if (rng.uniform() >= bc.reflectance[ch_]) {
        return; // absorbed by the wall
      }
      ph.x += w * exit.t;
      const int axis = faceAxis(exit.face);
      ph.x[axis] = faceIsMax(exit.face) ? g_.upper()[axis] : g_.lower()[axis];
      ph.w = sampleHemisphereCosine(faceInwardNormal(exit.face), rng);
    }
  }

  const Scene& scene_;
  const Grid& g_;
  int ch_;
  bool zonal_;
  std::vector<double> kt_;
  std::vector<Source> sources_;
  std::vector<double> cdf_;
  double total_ = 0.0;
};

} // namespace

MonteCarloEstimate estimateMonteCarlo(const Scene& scene, const MonteCarloOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  scene.validate();
  if (options.batches < 2 || options.photons < options.batches) {
    throw Error("Monte Carlo needs at least 2 batches and one photon per batch");
  }
  const Grid& g = scene.grid;
  const Index nv = g.voxelCount();
  const int C = scene.channels;
  const int B = options.batches;
  MonteCarloEstimate out;
  out.channels = C;
  for (auto* a : { &out.G, &out.GStdErr, &out.Gplus, &out.GplusStdErr }) {
    a->assign(std::size_t(nv) * C, 0.0);
  }
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const double V = g.voxelVolume();
  for (int ch = 0; ch < C; ++ch) {
    const ChannelTracer tracer(scene, ch, options.zonal);
    std::vector<std::vector<double>> G(B), Gp(B);
    std::vector<long long> counts(B);
    arena.execute([&] {
      tbb::parallel_for(0, B, [&](int b) {
        G[b].assign(nv, 0.0);
        Gp[b].assign(nv, 0.0);
        counts[b] = options.photons / B + (b < options.photons % B ? 1 : 0);
        Rng rng(options.seed, std::uint64_t(ch) * 1000003ULL + std::uint64_t(b));
        tracer.trace(counts[b], rng, G[b], Gp[b]);
      });
    });
    for (Index v = 0; v < nv; ++v) {
      for (int which = 0; which < 2; ++which) {
        const auto& acc = which == 0 ? G : Gp;
        double sum = 0.0, sum2 = 0.0;
        for (int b = 0; b < B; ++b) {
          const double est = tracer.totalPower() / double(counts[b]) * acc[b][v] / V;
          sum += est;
          sum2 += est * est;
        }
        const double mean = sum / B;
        const double var = std::max(0.0, (sum2 / B - mean * mean) * B / (B - 1.0));
        const std::size_t o = std::size_t(v) * C + ch;
        (which == 0 ? out.G : out.Gplus)[o] = mean;
        (which == 0 ? out.GStdErr : out.GplusStdErr)[o] = std::sqrt(var / B);
      }
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

} // namespace volrad
