#pragma once
// The nodal state every part of a step reads and writes: fluid particles, wall nodes and
// (later) structure nodes in one set of arrays. Everything lives on nodes so that it survives
// remeshing (theory §6, step 4).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/mesh/remesher.h"

namespace pfem {

// The free velocity component of a slip wall's node (StepSettings::slip).
inline constexpr std::uint8_t kSlipX = 1, kSlipY = 2;

struct NodeState {
  std::vector<double> x0, y0;  // positions at t = 0 [m]
  std::vector<double> x, y;    // current positions [m]
  std::vector<double> vx, vy;  // velocities [m/s]
  std::vector<double> p;       // pressures [Pa]
  std::vector<double> rz, wz;  // rotation [rad] and its rate [rad/s] (structure nodes only)
  std::vector<mesh::NodeKind> kind;
  // DDM: per node and parameter, the sensitivities of the fields below (empty without DDM).
  enum Sensitivity { kDx, kDy, kDvx, kDvy, kDp, kDrz, kDwz, kSensitivityFields };
  int num_params = 0;
  std::vector<double> sens;  // sens[(node * num_params + k) * kSensitivityFields + field]

  std::size_t size() const { return x.size(); }
  int add(double px, double py, mesh::NodeKind k, double pvx = 0.0, double pvy = 0.0) {
    x0.push_back(px), y0.push_back(py), x.push_back(px), y.push_back(py);
    vx.push_back(pvx), vy.push_back(pvy), p.push_back(0.0), kind.push_back(k);
    rz.push_back(0.0), wz.push_back(0.0);
    sens.resize(sens.size() + num_params * kSensitivityFields, 0.0);
    return static_cast<int>(x.size()) - 1;
  }
  void set_num_params(int count) {
    num_params = count;
    sens.assign(size() * count * kSensitivityFields, 0.0);
  }
  double* sensitivity(std::size_t node, int k) { return &sens[(node * num_params + k) * kSensitivityFields]; }
  const double* sensitivity(std::size_t node, int k) const {
    return &sens[(node * num_params + k) * kSensitivityFields];
  }
  // Walls and removed particles have no velocity unknowns (a wavemaker's wall moves as it is
  // told, engine/motion).
  bool is_fixed(std::size_t i) const {
    return kind[i] == mesh::NodeKind::Wall || kind[i] == mesh::NodeKind::Removed;
  }
};

}  // namespace pfem
