// SPDX-License-Identifier: BSD-3-Clause
// physics.md 5.4: a purely absorbing, emitting cube with cold black walls.
// The flux onto a wall has the closed form
//   q(x) = E/pi * integral over the hemisphere of (1 - exp(-kappa s(x,w))) cos(theta) dw,
// which we integrate here by product Gauss quadrature, independently of the
// solver's ray quadrature.
#include "TestScenes.h"
#include "volrad/DenseSolver.h"

#include <gtest/gtest.h>

using namespace volrad;
using namespace volrad::test;

namespace {

/// P_n(z) and the derivative P_n'(z) of the Legendre polynomial.
std::pair<double, double> legendre(int n, double z)
{
  double p0 = 1.0, p1 = 0.0;
  for (int j = 0; j < n; ++j) {
    const double p2 = p1;
    p1 = p0;
    p0 = ((2.0 * j + 1.0) * z * p1 - j * p2) / (j + 1.0);
  }
  return { p0, n * (z * p0 - p1) / (z * z - 1.0) };
}

/// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n's roots).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w)
{
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      const auto [p, dp] = legendre(n, z);
      z -= p / dp;
      if (std::abs(p / dp) < 1e-15) {
        break;
      }
    }
    const double dp = legendre(n, z).second;
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

/// q(x)/E at a point (u, v) of the face z = 0 of the unit cube, optical
/// thickness kappa per unit length. Cosine-weighted measure: u = sin^2(theta).
double wallFlux(double px, double py, double kappa, int n)
{
  std::vector<double> x, w;
  gaussLegendre(n, x, w);
  double sum = 0.0;
  const int nphi = 4 * n;
  for (int i = 0; i < n; ++i) {
    const double st = std::sqrt(x[i]), ct = std::sqrt(1.0 - x[i]);
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / nphi;
      const Vec3 d(st * std::cos(phi), st * std::sin(phi), ct);
      double s = 1.0 / d[2];
      s = std::min(s, d[0] > 0 ? (1.0 - px) / d[0] : (d[0] < 0 ? -px / d[0] : 1e300));
      s = std::min(s, d[1] > 0 ? (1.0 - py) / d[1] : (d[1] < 0 ? -py / d[1] : 1e300));
      sum += w[i] * (1.0 - std::exp(-kappa * s));
    }
  }
  // integral of f cos dw = (1/2) int du int dphi f; times 1/pi.
  return sum * 0.5 * (2.0 * kPi / nphi) / kPi;
}

/// Total power through one face / E: integral of q over the face.
double faceFlux(double kappa, int n)
{
  std::vector<double> x, w;
  gaussLegendre(n, x, w);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      sum += w[i] * w[j] * wallFlux(x[i], x[j], kappa, n);
    }
  }
  return sum;
}

struct CubeResult
{
  double centreFlux; ///< mean H of the patches touching the centre of face zmin, / E
  double escaped;    ///< total escaping power / E
};

CubeResult solveCube(int n, double kappa)
{
  Scene s = cubeScene(n);
  for (Index v = 0; v < s.grid.voxelCount(); ++v) {
    s.kappaA[v] = float(kappa);
    s.emissionI[v] = 1.0f;
  }
  BoundaryCondition wall;
  wall.type = BoundaryCondition::Type::Wall;
  setAllFaces(s, wall);
  const Solution sol = solveDense(s);
  // Patches of zmin around the face centre (one if n is odd, four if even).
  double sum = 0.0;
  int count = 0;
  for (int a = (n - 1) / 2; a <= n / 2; ++a) {
    for (int b = (n - 1) / 2; b <= n / 2; ++b) {
      sum += sol.H[s.grid.patchIndex(Face::ZMin, a, b)];
      ++count;
    }
  }
  return { sum / count, sol.energy[0].absorbedWalls };
}

} // namespace

TEST(AbsorbingCube, ClosedFormQuadratureConverges)
{
  // Our reference quadrature itself: doubling the order changes nothing.
  for (double kappa : { 0.1, 1.0, 10.0 }) {
    EXPECT_NEAR(wallFlux(0.5, 0.5, kappa, 64),
                wallFlux(0.5, 0.5, kappa, 128),
                1e-4 * wallFlux(0.5, 0.5, kappa, 128));
  }
  // Thick limit: a black body, q = E; thin limit: q = kappa E (mean of s cos / pi ...) -> 0.
  EXPECT_NEAR(wallFlux(0.5, 0.5, 200.0, 64), 1.0, 1e-4);
}

TEST(AbsorbingCube, WallFluxAndEscapingPowerMatchTheClosedForm)
{
  for (double kappa : { 0.1, 1.0, 10.0 }) {
    const double qRef = wallFlux(0.5, 0.5, kappa, 64);
    const double escRef = 6.0 * faceFlux(kappa, 24);
    const CubeResult coarse = solveCube(4, kappa);
    const CubeResult fine = solveCube(16, kappa);
    const double errCoarse = std::abs(coarse.centreFlux / qRef - 1.0);
    const double errFine = std::abs(fine.centreFlux / qRef - 1.0);
    const double escErr = std::abs(fine.escaped / escRef - 1.0);
    std::printf("[measured] cube kappa*a=%g: q_ref=%.6f  4^3 err=%.3g  16^3 err=%.3g  escaping err "
                "(16^3)=%.3g\n",
                kappa,
                qRef,
                errCoarse,
                errFine,
                escErr);
    EXPECT_LT(errFine, 0.01);
    EXPECT_LT(escErr, 0.01);
    EXPECT_LT(errFine, errCoarse);
  }
}
