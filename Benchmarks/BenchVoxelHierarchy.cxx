// SPDX-License-Identifier: BSD-3-Clause
// The voxel hierarchy of the hierarchical solver, two ways (issue 4, item 1):
// VolRad's dense mip pyramid (mean/min/max extinction per 2x2x2 level) and
// an OpenVDB FloatGrid (sparse tree: empty space costs nothing, hierarchical
// DDA over its nodes). For each benchmark scene and size it prints the
// build time, the memory of the structure, and the time to integrate the
// exact optical depth along random rays through the volume.
#include "BenchmarkScenes.h"
#include "volrad/Sampling.h"
#include "volrad/VoxelPyramid.h"

#include <openvdb/math/DDA.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/RayIntersector.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace volrad;

namespace {

double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Ray
{
  Vec3 a, b;
};

std::vector<Ray> randomRays(int count)
{
  Rng rng(11);
  std::vector<Ray> rays(count);
  for (auto& r : rays) {
    // Face to opposite face of the unit cube, in a random axis.
    const int axis = int(rng.uniform() * 3) % 3;
    r.a = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    r.b = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    r.a[axis] = 0.0;
    r.b[axis] = 1.0;
  }
  return rays;
}

openvdb::FloatGrid::Ptr buildVdb(const Scene& s)
{
  auto grid = openvdb::FloatGrid::create(0.f);
  const double h = s.grid.spacing[0];
  // Index cell [i, i+1) is voxel i, so that the nodes' bounds in index space
  // are voxel bounds (VDB's own convention puts voxel centres on integers).
  auto xform = openvdb::math::Transform::createLinearTransform(h);
  const Vec3 lo = s.grid.lower();
  xform->postTranslate(openvdb::Vec3d(lo[0], lo[1], lo[2]));
  grid->setTransform(xform);
  auto acc = grid->getAccessor();
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const float k = float(s.kappaTAt(v, 0));
    if (k != 0.f) {
      const auto c = s.grid.ijk(v);
      acc.setValue(openvdb::Coord(c[0], c[1], c[2]), k);
    }
  }
  grid->pruneGrid(0.f); // uniform blocks become tiles
  return grid;
}

/// Exact optical depth through the VDB: the hierarchical DDA finds the
/// intervals of active nodes, a voxel DDA integrates inside them.
double vdbDepth(openvdb::tools::VolumeRayIntersector<openvdb::FloatGrid>& inter,
                const openvdb::FloatGrid& grid,
                const Ray& r)
{
  using RayT = openvdb::math::Ray<double>;
  const Vec3 d = (r.b - r.a);
  const double length = d.norm();
  // Ray times must be > 0.
  RayT wray(openvdb::Vec3d(r.a[0], r.a[1], r.a[2]),
            openvdb::Vec3d(d[0], d[1], d[2]) / length,
            1e-12,
            length);
  if (!inter.setWorldRay(wray)) {
    return 0.0;
  }
  auto acc = grid.getConstAccessor();
  const RayT iray = wray.worldToIndex(grid); // unit direction in index space: times in voxels
  const double h = grid.voxelSize()[0];
  double tau = 0.0, t0 = 0.0, t1 = 0.0;
  while (inter.march(t0, t1)) {
    openvdb::math::DDA<RayT, 0> dda(iray, t0, t1);
    do {
      const double tn = std::min(dda.next(), t1);
      tau += acc.getValue(dda.voxel()) * (tn - dda.time());
    } while (dda.step());
  }
  return tau * h;
}

} // namespace

int main(int argc, char* argv[])
{
  openvdb::initialize();
  std::vector<int> sizes = { 64, 128, 256 };
  if (argc > 1) {
    sizes.clear();
    for (int i = 1; i < argc; ++i) {
      sizes.push_back(std::atoi(argv[i]));
    }
  }
  const int rayCount = 20000;
  const auto rays = randomRays(rayCount);
  std::printf("%-8s %5s | %-28s | %-28s | %s\n",
              "scene",
              "n",
              "pyramid: build s, MiB, us/ray",
              "OpenVDB: build s, MiB, us/ray",
              "max |depth diff|");
  for (const char* name : { "phantom", "cloud", "cube" }) {
    for (int n : sizes) {
      const Scene s = bench::benchmarkScene(name, n);
      auto t = std::chrono::steady_clock::now();
      const VoxelPyramid pyramid(s, 0);
      const double pyramidBuild = seconds(t);
      double pyramidBytes = 0.0;
      for (int l = 0; l < pyramid.levels(); ++l) {
        pyramidBytes += 3.0 * sizeof(float) * double(pyramid.grid(l).voxelCount());
      }
      std::vector<double> depthP(rayCount), depthV(rayCount);
      t = std::chrono::steady_clock::now();
      for (int i = 0; i < rayCount; ++i) {
        depthP[i] = pyramid.opticalDepthAdaptive(rays[i].a, rays[i].b, 0.0).estimate;
      }
      const double pyramidRay = seconds(t) / rayCount * 1e6;

      t = std::chrono::steady_clock::now();
      auto grid = buildVdb(s);
      openvdb::tools::VolumeRayIntersector<openvdb::FloatGrid> inter(*grid);
      const double vdbBuild = seconds(t);
      const double vdbBytes = double(grid->memUsage());
      t = std::chrono::steady_clock::now();
      for (int i = 0; i < rayCount; ++i) {
        depthV[i] = vdbDepth(inter, *grid, rays[i]);
      }
      const double vdbRay = seconds(t) / rayCount * 1e6;
      double diff = 0.0;
      for (int i = 0; i < rayCount; ++i) {
        diff = std::max(diff, std::abs(depthP[i] - depthV[i]) / (1.0 + depthP[i]));
      }
      std::printf("%-8s %5d | %8.2f %9.1f %9.2f | %8.2f %9.1f %9.2f | %.2g\n",
                  name,
                  n,
                  pyramidBuild,
                  pyramidBytes / 1048576.0,
                  pyramidRay,
                  vdbBuild,
                  vdbBytes / 1048576.0,
                  vdbRay,
                  diff);
      std::fflush(stdout);
    }
  }
  return 0;
}
