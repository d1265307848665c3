// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/ZonalSystem.h"

#include "volrad/Sampling.h"

namespace volrad {

ZonalSystem buildZonalSystem(const Scene& scene,
                             int ch,
                             const ExchangeElements& el,
                             const DirectLighting& dl)
{
  const Grid& g = scene.grid;
  const Index n = el.size();
  const double V = g.voxelVolume();
  ZonalSystem sys{ Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n) };
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const Index i = el.full[v];
    if (i < 0) {
      continue;
    }
    const double kt = scene.kappaTAt(v, ch), ka = scene.kappaAAt(v, ch);
    sys.e[i] = ka * scene.emissionIAt(v, ch) / kt;
    sys.c[i] = scene.sigmaIAt(v, ch) / (4.0 * kt * kt * V);
    sys.D[i] = kt * dl.track[v];
    const Index f = el.front[v];
    if (f >= 0) {
      sys.e[f] = ka * scene.emissionDAt(v, ch) / kt;
      sys.c[f] = scene.sigmaDAt(v, ch) / (2.0 * kt * kt * V);
      sys.D[f] = kt * dl.trackFront[v];
    }
  }
  for (Index p = 0; p < el.patchCount; ++p) {
    const Index k = el.patchElement(p);
    const Face face = g.patchLocation(p).face;
    const BoundaryCondition& bc = scene.boundary[static_cast<int>(face)];
    sys.D[k] = dl.patchPower[p];
    if (bc.type == BoundaryCondition::Type::Wall) {
      sys.e[k] = bc.emission[ch];
      sys.c[k] = bc.reflectance[ch] / g.patchArea(face);
    } else {
      sys.e[k] = kPi * bc.radiance[ch];
    }
  }
  return sys;
}

void allocateFields(const Scene& scene, Solution& sol)
{
  const Index nv = scene.grid.voxelCount(), np = scene.grid.patchCount();
  const int C = sol.channels;
  for (auto* a : { &sol.G, &sol.Gplus, &sol.QI, &sol.QD, &sol.absorbed }) {
    a->assign(std::size_t(nv) * C, 0.0);
  }
  sol.B.assign(std::size_t(np) * C, 0.0);
  sol.H.assign(std::size_t(np) * C, 0.0);
}

Solution emptySolution(const Scene& scene, const char* method, bool withFields)
{
  const int C = scene.channels;
  Solution sol;
  sol.channels = C;
  if (withFields) {
    allocateFields(scene, sol);
  }
  sol.energy.resize(C);
  sol.stats.method = method;
  sol.stats.converged = true;
  return sol;
}

void storeChannelFields(const Scene& scene,
                        int ch,
                        const ExchangeElements& el,
                        const Eigen::VectorXd& x,
                        const Eigen::VectorXd& collided,
                        const std::function<double(Index)>& otherG,
                        const std::function<double(Index)>& otherGplus,
                        Solution& sol)
{
  const Grid& g = scene.grid;
  const int C = sol.channels;
  const double V = g.voxelVolume();
  for (Index v = 0; v < g.voxelCount(); ++v) {
    const std::size_t o = std::size_t(v) * C + ch;
    const double kt = scene.kappaTAt(v, ch);
    if (el.full[v] >= 0) {
      sol.G[o] = collided[el.full[v]] / (kt * V);
      sol.QI[o] = x[el.full[v]];
    } else {
      sol.G[o] = otherG(v);
    }
    if (el.front[v] >= 0) {
      sol.Gplus[o] = collided[el.front[v]] / (kt * V);
      sol.QD[o] = x[el.front[v]];
    } else if (scene.hasNormal(v)) {
      sol.Gplus[o] = otherGplus(v);
    }
    sol.absorbed[o] =
      scene.kappaAAt(v, ch) * sol.G[o] + scene.sigmaDAt(v, ch) * (sol.G[o] - sol.Gplus[o]);
  }
  for (Index p = 0; p < g.patchCount(); ++p) {
    const std::size_t o = std::size_t(p) * C + ch;
    sol.B[o] = x[el.patchElement(p)];
    sol.H[o] = collided[el.patchElement(p)] / g.patchArea(g.patchLocation(p).face);
  }
}

} // namespace volrad
