// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/DirectLight.h"

#include "volrad/Sampling.h"
#include "volrad/VoxelTraversal.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

namespace volrad {

namespace {

constexpr double kNegligibleTransmittance = 1e-13;

/// What the rays leave: per voxel (track, and the front part only where
/// some voxel has a normal, else it stays empty) and per exit patch.
struct RayTally
{
  std::vector<double> track, trackFront, patchPower;
  double entering = 0.0;
  RayTally(const Grid& g, bool fronts)
    : track(std::size_t(g.voxelCount()), 0.0)
    , trackFront(fronts ? std::size_t(g.voxelCount()) : 0, 0.0)
    , patchPower(std::size_t(g.patchCount()), 0.0)
  {
  }
};

/// One chunk of rays' tally within a wave: per voxel in blocks of 4x4x4
/// allocated where its rays pass, since a full-size tally per chunk (16 of
/// them) was the solve's peak at 256^3 (4.3 GB with fronts); per patch in
/// full (a surface: small), for all the waves.
class ChunkTally
{
public:
  static constexpr int kSide = 4, kVoxels = kSide * kSide * kSide;

  ChunkTally(const Grid& g, bool fronts)
    : patchPower(std::size_t(g.patchCount()), 0.0)
    , grid_(g)
    , fronts_(fronts)
  {
    for (int a = 0; a < 3; ++a) {
      blocks_[a] = (g.dims[a] + kSide - 1) / kSide;
    }
    slot_.assign(std::size_t(blocks_[0]) * blocks_[1] * blocks_[2], -1);
  }

  void addTrack(Index v, double add, bool front)
  {
    const auto c = grid_.ijk(v);
    const std::size_t b =
      std::size_t(c[0] / kSide) +
      std::size_t(blocks_[0]) * (std::size_t(c[1] / kSide) + std::size_t(blocks_[1]) * (c[2] / kSide));
    if (slot_[b] < 0) {
      slot_[b] = std::int32_t(used_.size());
      used_.push_back(std::int32_t(b));
      values_.resize(values_.size() + (fronts_ ? 2 : 1) * kVoxels, 0.0);
    }
    const int offset = c[0] % kSide + kSide * (c[1] % kSide + kSide * (c[2] % kSide));
    double* block = values_.data() + std::size_t(slot_[b]) * (fronts_ ? 2 : 1) * kVoxels;
    block[offset] += add;
    if (front) {
      block[kVoxels + offset] += add;
    }
  }

  const std::vector<std::int32_t>& usedBlocks() const { return used_; }

  /// Adds this chunk's part in block b (if any) to the total.
  void addBlockTo(std::int32_t b, RayTally& total) const
  {
    if (slot_[b] < 0) {
      return;
    }
    const double* block = values_.data() + std::size_t(slot_[b]) * (fronts_ ? 2 : 1) * kVoxels;
    const int bi = b % blocks_[0], bj = (b / blocks_[0]) % blocks_[1],
              bk = b / (blocks_[0] * blocks_[1]);
    for (int k = 0; k < kSide; ++k) {
      for (int j = 0; j < kSide; ++j) {
        for (int i = 0; i < kSide; ++i) {
          const int x = bi * kSide + i, y = bj * kSide + j, z = bk * kSide + k;
          if (x >= grid_.dims[0] || y >= grid_.dims[1] || z >= grid_.dims[2]) {
            continue;
          }
          const int o = i + kSide * (j + kSide * k);
          const Index v = grid_.index(x, y, z);
          total.track[v] += block[o];
          if (fronts_) {
            total.trackFront[v] += block[kVoxels + o];
          }
        }
      }
    }
  }

  /// Empties the voxel blocks for the next wave (their memory kept).
  void clearBlocks()
  {
    for (const std::int32_t b : used_) {
      slot_[b] = -1;
    }
    used_.clear();
    values_.clear();
  }

  std::vector<double> patchPower;
  double entering = 0.0;

private:
  const Grid& grid_;
  bool fronts_;
  std::array<int, 3> blocks_{};
  std::vector<std::int32_t> slot_; ///< per block, its place in values_, or -1
  std::vector<std::int32_t> used_; ///< the blocks with a place, in that order
  std::vector<double> values_;
};

/// Follows a ray of power w that is inside the domain from parameter 0 on.
void followRay(const Scene& scene,
               const std::vector<double>& kt,
               const Vec3& x,
               const Vec3& d,
               double w,
               ChunkTally& tally)
{
  const bool normals = !scene.normals.empty();
  double T = 1.0;
  const DomainExit exit = traverseVoxels(
    scene.grid, x, d, std::numeric_limits<double>::infinity(), [&](Index v, double l, double) {
      const double k = kt[v];
      const double e = std::exp(-k * l);
      // (1 - e^{-k l}) / k, exact also where k l is tiny.
      const double lengthWeighted = k * l > 1e-300 ? -std::expm1(-k * l) / k : l;
      const double add = w * T * lengthWeighted;
      tally.addTrack(v, add, normals && scene.normalDot(v, d) < 0.0);
      T *= e;
      return T > kNegligibleTransmittance;
    });
  if (exit.exited) {
    tally.patchPower[exit.patch] += w * T;
  }
}

/// Rays traced between two progress reports (a few tenths of a second).
constexpr Index kRaysPerWave = Index(1) << 18;

/// Runs f(begin, end, tally) over [0, count) in waves of `perWave` items,
/// each wave in a fixed number of chunks in parallel, reporting progress (a
/// chance to stop) after each wave. Each wave's chunks are added to the
/// total in order, voxel block by voxel block, and the patches' at the end:
/// the sums do not depend on thread scheduling or count.
template<class F>
void forChunks(const Grid& g,
               Index count,
               Index perWave,
               RayTally& total,
               const ProgressRange& progress,
               F&& f)
{
  const Index chunks = std::min<Index>(std::min(count, perWave), 16);
  std::vector<std::unique_ptr<ChunkTally>> partial(std::max<Index>(0, chunks));
  std::vector<std::int32_t> blocks;
  for (Index w0 = 0; w0 < count; w0 += perWave) {
    const Index n = std::min(count - w0, perWave);
    tbb::parallel_for(Index(0), chunks, [&](Index ci) {
      if (!partial[ci]) {
        partial[ci] = std::make_unique<ChunkTally>(g, !total.trackFront.empty());
      }
      f(w0 + ci * n / chunks, w0 + (ci + 1) * n / chunks, *partial[ci]);
    });
    blocks.clear();
    for (const auto& p : partial) {
      blocks.insert(blocks.end(), p->usedBlocks().begin(), p->usedBlocks().end());
    }
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t i) {
      for (const auto& p : partial) {
        p->addBlockTo(blocks[i], total);
      }
    });
    for (const auto& p : partial) {
      p->clearBlocks();
    }
    progress.report(double(w0 + n) / double(count));
  }
  for (const auto& p : partial) {
    for (std::size_t i = 0; i < total.patchPower.size(); ++i) {
      total.patchPower[i] += p->patchPower[i];
    }
    total.entering += p->entering;
  }
}

bool faceIsOpen(const Scene& s, Face f)
{
  return s.boundary[static_cast<int>(f)].type == BoundaryCondition::Type::Open;
}

void addDirectional(const Scene& scene,
                    const std::vector<double>& kt,
                    const DirectionalLight& light,
                    int c,
                    const QuadratureSettings& q,
                    RayTally& tally,
                    const ProgressRange& progress)
{
  const Grid& g = scene.grid;
  const Vec3 d = light.direction.stableNormalized();
  const double E = light.irradiance[c];
  if (E <= 0.0) {
    return;
  }
  const int s = std::max(1, q.lightRaysPerPatchAxis);
  for (int fi = 0; fi < kFaceCount; ++fi) {
    const Face f = static_cast<Face>(fi);
    const double cosIn = d.dot(faceInwardNormal(f));
    if (cosIn <= 0.0 || !faceIsOpen(scene, f)) {
      continue; // the light does not enter here, or a wall blocks it
    }
    const auto ax = faceAxesInPlane(f);
    const double w = E * cosIn * g.patchArea(f) / double(s * s);
    const Index first = g.facePatchOffset(f);
    forChunks(g,
              g.facePatchCount(f),
              std::max<Index>(1, kRaysPerWave / (s * s)),
              tally,
              progress.sub(fi / double(kFaceCount), (fi + 1) / double(kFaceCount)),
              [&](Index begin, Index end, ChunkTally& local) {
                for (Index p = first + begin; p < first + end; ++p) {
                  const Vec3 lower = g.patchLower(p);
                  for (int b = 0; b < s; ++b) {
                    for (int a = 0; a < s; ++a) {
                      Vec3 x = lower;
                      x[ax[0]] += (a + 0.5) / s * g.spacing[ax[0]];
                      x[ax[1]] += (b + 0.5) / s * g.spacing[ax[1]];
                      followRay(scene, kt, x, d, w, local);
                      local.entering += w;
                    }
                  }
                }
              });
  }
}

void addPoint(const Scene& scene,
              const std::vector<double>& kt,
              const PointLight& light,
              int c,
              const QuadratureSettings& q,
              std::size_t lightIndex,
              RayTally& tally,
              const ProgressRange& progress)
{
  const Grid& g = scene.grid;
  const double I = light.intensity[c];
  if (I <= 0.0) {
    return;
  }
  const Vec3 lo = g.lower(), hi = g.upper();
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  const Vec3 toCentre = centre - light.position;
  const double dist = toCentre.norm();
  // Directions: the whole sphere, or the cone around the domain's bounding sphere.
  double cosMax = -1.0;
  if (dist > radius) {
    cosMax = std::sqrt(1.0 - (radius / dist) * (radius / dist));
  }
  const double solidAngle = 2.0 * kPi * (1.0 - cosMax);
  double farthest = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 x(
      (corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 4) ? hi[2] : lo[2]);
    farthest = std::max(farthest, (x - light.position).norm());
  }
  const double voxelSolidAngle =
    std::pow(g.spacing.minCoeff(), 2) / std::max(farthest * farthest, 1e-300);
  const double wanted = q.pointLightRaysPerVoxel * solidAngle / voxelSolidAngle;
  const Index rays = Index(std::clamp(wanted, 4096.0, 1.6e7));
  const double w = I * solidAngle / double(rays);
  const Eigen::Matrix3d frame =
    dist > 0.0 ? frameAround(toCentre / dist) : Eigen::Matrix3d::Identity();
  Rng rotRng(q.seed ^ 0x706f696e74ULL, lightIndex);
  const Eigen::Matrix3d spin =
    frame * Eigen::AngleAxisd(2 * kPi * rotRng.uniform(), Vec3::UnitZ()).toRotationMatrix();
  forChunks(g, rays, kRaysPerWave, tally, progress, [&](Index begin, Index end, ChunkTally& local) {
    for (Index i = begin; i < end; ++i) {
      // Equal-solid-angle spiral in the cone.
      const double cosT = 1.0 - (1.0 - cosMax) * (i + 0.5) / double(rays);
      const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
      const double phi = 2.0 * kPi * std::fmod(i * 0.61803398874989484820, 1.0);
      const Vec3 d = spin * Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
      double t0, t1;
      Face entry;
      if (!clipToDomain(g, light.position, d, t0, t1, &entry) || t1 <= std::max(t0, 0.0)) {
        continue;
      }
      if (t0 > 0.0 && !faceIsOpen(scene, entry)) {
        continue; // blocked by a wall
      }
      followRay(scene, kt, light.position, d, w, local);
      local.entering += w;
    }
  });
}

} // namespace

DirectLighting computeDirectLight(const Scene& scene,
                                  int channel,
                                  const QuadratureSettings& q,
                                  const ProgressRange& progress)
{
  const Grid& g = scene.grid;
  const std::vector<double> kt = scene.extinction(channel);
  RayTally tally(g, !scene.normals.empty());
  const std::size_t nd = scene.directionalLights.size(), lights = nd + scene.pointLights.size();
  auto part = [&](std::size_t i) {
    return progress.sub(double(i) / double(lights), double(i + 1) / double(lights));
  };
  for (std::size_t i = 0; i < nd; ++i) {
    addDirectional(scene, kt, scene.directionalLights[i], channel, q, tally, part(i));
  }
  for (std::size_t i = 0; i < scene.pointLights.size(); ++i) {
    addPoint(scene, kt, scene.pointLights[i], channel, q, i, tally, part(nd + i));
  }
  DirectLighting out;
  out.track = std::move(tally.track);
  out.trackFront = std::move(tally.trackFront);
  out.patchPower = std::move(tally.patchPower);
  out.entering = tally.entering;
  return out;
}

std::vector<std::string> lightsWallsKeepOut(const Scene& scene)
{
  std::vector<std::string> messages;
  const Grid& g = scene.grid;
  for (std::size_t i = 0; i < scene.directionalLights.size(); ++i) {
    const Vec3 d = scene.directionalLights[i].direction;
    bool enters = false;
    for (int fi = 0; fi < kFaceCount; ++fi) {
      const Face f = static_cast<Face>(fi);
      enters = enters || (d.dot(faceInwardNormal(f)) > 0.0 && faceIsOpen(scene, f));
    }
    if (!enters) {
      messages.push_back("directional light " + std::to_string(i) +
                         " meets only walls where it would enter: it lights nothing");
    }
  }
  const Vec3 lo = g.lower(), hi = g.upper();
  for (std::size_t i = 0; i < scene.pointLights.size(); ++i) {
    const Vec3 p = scene.pointLights[i].position;
    bool outside = false, seesOpenFace = false;
    for (int a = 0; a < 3; ++a) {
      // Faces 2a (min) and 2a + 1 (max) along axis a, seen from their outer side.
      for (int side = 0; side < 2; ++side) {
        const bool beyond = side == 0 ? p[a] < lo[a] : p[a] > hi[a];
        outside = outside || beyond;
        seesOpenFace =
          seesOpenFace || (beyond && faceIsOpen(scene, static_cast<Face>(2 * a + side)));
      }
    }
    if (outside && !seesOpenFace) {
      messages.push_back("point light " + std::to_string(i) + " at (" + std::to_string(p[0]) +
                         ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) +
                         ") is outside the volume behind walls: it lights nothing");
    }
  }
  return messages;
}

} // namespace volrad
