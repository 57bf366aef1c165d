#pragma once
// Forward-mode dual number for the recorders' DDM sensitivities: a value and its derivative
// along one parameter. A recorder evaluated on duals whose derivative parts are the nodes'
// sensitivities gives its own sensitivity by the same formula (and the same discrete choices).
#include "engine/solve/node_state.h"

namespace pfem {

struct Dual {
  double v = 0.0, d = 0.0;
};
inline Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d + b.d}; }
inline Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d - b.d}; }
inline Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d * b.v + a.v * b.d}; }
inline Dual operator/(Dual a, Dual b) { return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)}; }

// Node i's coordinate, velocity or pressure (which: NodeState::kDx, kDy, kDvx, kDvy or kDp) with
// its sensitivity to parameter k (none for k < 0).
inline Dual node_dual(const NodeState& nodes, int i, int which, int k) {
  const double value = which == NodeState::kDx    ? nodes.x[i]
                       : which == NodeState::kDy  ? nodes.y[i]
                       : which == NodeState::kDvx ? nodes.vx[i]
                       : which == NodeState::kDvy ? nodes.vy[i]
                                                  : nodes.p[i];
  return {value, k >= 0 ? nodes.sensitivity(i, k)[which] : 0.0};
}

// The pressure at corner a of triangle e (its side's, at a node of wall or beam lines) with its
// sensitivity to parameter k (none for k < 0).
inline Dual corner_pressure_dual(const NodeState& nodes, const mesh::FluidMesh& mesh, std::size_t e, int a, int k) {
  const int i = mesh.triangles[e][a], side = mesh.side(e, a);
  const bool multi = mesh.multi_sided(i);
  return {nodes.pressure(i, multi, side), k >= 0 ? nodes.pressure_sensitivity(i, multi, side, k) : 0.0};
}

}  // namespace pfem
