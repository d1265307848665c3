// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/EnergyBalance.h"

#include "volrad/Sampling.h"

#include <cmath>

namespace volrad {

double EnergyTerms::relativeResidual() const
{
  const double in = emitted();
  return in > 0.0 ? std::abs(in - removed()) / in : std::abs(removed());
}

EnergyTerms computeEnergyTerms(const Scene& scene,
                               int ch,
                               const Solution& sol,
                               double lightsEntering)
{
  const Grid& g = scene.grid;
  const int C = sol.channels;
  const double V = g.voxelVolume();
  EnergyTerms t;
  t.enteringLights = lightsEntering;
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const double ka = scene.kappaAAt(v, ch);
    t.emittedVoxels += V * ka * (4.0 * scene.emissionIAt(v, ch) + 2.0 * scene.emissionDAt(v, ch));
    t.absorbedVoxels += V * sol.absorbed[std::size_t(v) * C + ch];
  }
  for (Index p = 0; p < g.patchCount(); ++p) {
    const Face f = g.patchLocation(p).face;
    const BoundaryCondition& bc = scene.boundary[static_cast<int>(f)];
    const double A = g.patchArea(f);
    const double H = sol.H[std::size_t(p) * C + ch];
    if (bc.type == BoundaryCondition::Type::Wall) {
      t.emittedWalls += A * bc.emission[ch];
      t.absorbedWalls += A * (1.0 - bc.reflectance[ch]) * H;
    } else {
      t.enteringEnvironment += A * kPi * bc.radiance[ch];
      t.escaped += A * H;
    }
  }
  return t;
}

} // namespace volrad
