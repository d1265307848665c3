// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Sampling.h"

namespace volrad {

namespace {
std::uint64_t splitMix64(std::uint64_t& x)
{
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t rotl(std::uint64_t x, int k)
{
  return (x << k) | (x >> (64 - k));
}
constexpr double kGoldenRatio = 1.61803398874989484820;
} // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream)
{
  std::uint64_t x = seed ^ (0xd1b54a32d192ed03ULL * (stream + 1));
  for (auto& s : s_) {
    s = splitMix64(x);
  }
}

std::uint64_t Rng::next()
{
  const std::uint64_t result = s_[0] + s_[3];
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

Vec3 sampleSphere(Rng& rng)
{
  const double z = 1.0 - 2.0 * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * rng.uniform();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Eigen::Matrix3d frameAround(const Vec3& n)
{
  // Duff et al. 2017, "Building an orthonormal basis, revisited".
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  Eigen::Matrix3d m;
  m.col(0) = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  m.col(1) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  m.col(2) = n;
  return m;
}

Vec3 sampleHemisphereUniform(const Vec3& n, Rng& rng)
{
  const double z = rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * rng.uniform();
  return frameAround(n) * Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec3 sampleHemisphereCosine(const Vec3& n, Rng& rng)
{
  const double u = rng.uniform();
  const double r = std::sqrt(u);
  const double phi = 2.0 * kPi * rng.uniform();
  return frameAround(n) *
         Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u)));
}

Eigen::Matrix3d sampleRotation(Rng& rng)
{
  // Uniform unit quaternion (Shoemake 1992).
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  Eigen::Quaterniond q(b * std::cos(2 * kPi * u3),
                       a * std::sin(2 * kPi * u2),
                       a * std::cos(2 * kPi * u2),
                       b * std::sin(2 * kPi * u3));
  return q.normalized().toRotationMatrix();
}

std::vector<Vec3> fibonacciSphere(int n)
{
  std::vector<Vec3> dirs(n);
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * kPi * std::fmod(i / kGoldenRatio, 1.0);
    dirs[i] = Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }
  return dirs;
}

void fibonacciCosineHemisphere(int n, double shiftU, double shiftPhi, std::vector<Vec3>& out)
{
  out.resize(n);
  for (int i = 0; i < n; ++i) {
    const double u = (i + shiftU) / n; // sin^2(theta): equal cos-weighted measure
    const double r = std::sqrt(u);
    const double phi = 2.0 * kPi * std::fmod(i / kGoldenRatio + shiftPhi, 1.0);
    out[i] = Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u)));
  }
}

std::vector<Vec3> stratifiedPoints(const Vec3& lower, const Vec3& size, int perAxis, Rng& rng)
{
  int counts[3];
  for (int a = 0; a < 3; ++a) {
    counts[a] = size[a] > 0.0 ? perAxis : 1;
  }
  std::vector<Vec3> pts;
  pts.reserve(std::size_t(counts[0]) * counts[1] * counts[2]);
  for (int k = 0; k < counts[2]; ++k) {
    for (int j = 0; j < counts[1]; ++j) {
      for (int i = 0; i < counts[0]; ++i) {
        const int c[3] = { i, j, k };
        Vec3 p;
        for (int a = 0; a < 3; ++a) {
          p[a] = lower[a] + size[a] * (c[a] + rng.uniform()) / counts[a];
        }
        pts.push_back(p);
      }
    }
  }
  return pts;
}

} // namespace volrad
