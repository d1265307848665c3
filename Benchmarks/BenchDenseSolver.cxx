// SPDX-License-Identifier: BSD-3-Clause
// Solve time and peak memory of the dense reference solver on a
// heterogeneous scattering medium with sigma_d surfaces, walls and a sun,
// at 8^3, 12^3 and 16^3 (or the sizes given on the command line). Each size
// runs in a child process so that its peak resident memory is its own.
#include "volrad/DenseSolver.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace volrad;

namespace {

Scene benchScene(int n)
{
  Scene s;
  s.grid.dims = { n, n, n };
  s.grid.spacing = Vec3::Constant(1.0 / n);
  s.grid.origin = Vec3::Constant(0.5 / n);
  s.allocate();
  s.normals.resize(s.grid.voxelCount());
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    const Vec3 x = s.grid.voxelCentre(v) - Vec3::Constant(0.5);
    const double r = x.norm();
    s.kappaA[v] = float(0.5 + 2.0 * (0.5 + 0.5 * std::sin(9 * x[0]) * std::cos(7 * x[1])));
    s.sigmaI[v] = float(4.0 * (0.5 + 0.5 * std::cos(5 * x[2])));
    s.sigmaD[v] = (r > 0.2 && r < 0.3) ? 8.0f : 0.0f;
    const Vec3 nrm = r > 1e-9 ? Vec3(x / r) : Vec3::UnitZ();
    s.normals[v] = { float(nrm[0]), float(nrm[1]), float(nrm[2]) };
  }
  s.boundary[static_cast<int>(Face::ZMin)].type = BoundaryCondition::Type::Wall;
  s.boundary[static_cast<int>(Face::ZMin)].reflectance = uniformChannels(0.5);
  s.directionalLights.push_back({ Vec3(0.3, 0.2, -1.0), uniformChannels(1.0) });
  return s;
}

} // namespace

int main(int argc, char* argv[])
{
  std::vector<int> sizes = { 8, 12, 16 };
  if (argc > 1) {
    sizes.clear();
    for (int i = 1; i < argc; ++i) {
      sizes.push_back(std::atoi(argv[i]));
    }
  }
  std::printf("%6s %9s %10s %12s %10s %12s %12s\n",
              "grid",
              "elements",
              "seconds",
              "peak MiB",
              "links",
              "residual",
              "quad. err");
  for (int n : sizes) {
    int pipefd[2];
    if (pipe(pipefd) != 0) {
      return 1;
    }
    const pid_t pid = fork();
    if (pid == 0) {
      close(pipefd[0]);
      const Scene s = benchScene(n);
      const Solution sol = solveDense(s);
      double buf[4] = { sol.stats.seconds,
                        double(sol.stats.links),
                        sol.energy[0].relativeResidual(),
                        sol.stats.quadratureError };
      if (write(pipefd[1], buf, sizeof(buf)) != sizeof(buf)) {
        _exit(1);
      }
      _exit(0);
    }
    close(pipefd[1]);
    double buf[4] = { 0, 0, 0, 0 };
    const bool got = read(pipefd[0], buf, sizeof(buf)) == sizeof(buf);
    close(pipefd[0]);
    int status = 0;
    struct rusage usage;
    wait4(pid, &status, 0, &usage);
    if (!got) {
      std::printf("%6d failed\n", n);
      continue;
    }
    const long long elements = (long long)(std::sqrt(2.0 * buf[1]));
    std::printf("%3d^3 %9lld %10.2f %12.1f %10.3g %12.2g %12.3g\n",
                n,
                elements,
                buf[0],
                usage.ru_maxrss / 1024.0,
                buf[1],
                buf[2],
                buf[3]);
  }
  return 0;
}
