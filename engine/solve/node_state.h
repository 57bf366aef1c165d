#pragma once
// The nodal state every part of a step reads and writes: fluid particles, wall nodes and
// (later) structure nodes in one set of arrays. Everything lives on nodes so that it survives
// remeshing (theory §6, step 4).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
  std::vector<double> p;       // pressures [Pa]; at a node of several sides, the mean of its wet ones
  // Per node, mesh::kMaxPressureSides entries: the pressure on each side of a node of wall or
  // beam lines (mesh::FluidMesh::sides), NaN on a side that had no water (or a node of one
  // side). A side that gets water starts from the node's p.
  std::vector<double> side_p;
  std::vector<double> rz, wz;  // rotation [rad] and its rate [rad/s] (structure nodes only)
  std::vector<mesh::NodeKind> kind;
  // DDM: per node and parameter, the sensitivities of the fields below (empty without DDM).
  // kDpSide + s: the sensitivity of side_p's side s (NaN as it is).
  enum Sensitivity { kDx, kDy, kDvx, kDvy, kDp, kDrz, kDwz, kDpSide, kSensitivityFields = kDpSide + mesh::kMaxPressureSides };
  int num_params = 0;
  std::vector<double> sens;  // sens[(node * num_params + k) * kSensitivityFields + field]

  std::size_t size() const { return x.size(); }
  int add(double px, double py, mesh::NodeKind k, double pvx = 0.0, double pvy = 0.0) {
    x0.push_back(px), y0.push_back(py), x.push_back(px), y.push_back(py);
    vx.push_back(pvx), vy.push_back(pvy), p.push_back(0.0), kind.push_back(k);
    rz.push_back(0.0), wz.push_back(0.0);
    side_p.resize(side_p.size() + mesh::kMaxPressureSides, kNoSide);
    const std::size_t begin = sens.size();
    sens.resize(begin + num_params * kSensitivityFields, 0.0);
    for (std::size_t f = begin; f < sens.size(); f += kSensitivityFields)
      std::fill_n(&sens[f + kDpSide], mesh::kMaxPressureSides, kNoSide);
    return static_cast<int>(x.size()) - 1;
  }
  void set_num_params(int count) {
    num_params = count;
    sens.assign(size() * count * kSensitivityFields, 0.0);
    for (std::size_t f = 0; f < sens.size(); f += kSensitivityFields)
      std::fill_n(&sens[f + kDpSide], mesh::kMaxPressureSides, kNoSide);
  }
  static constexpr double kNoSide = std::numeric_limits<double>::quiet_NaN();
  // The pressure at t_n of side `side` of node i, in a mesh where it has several sides or not
  // (a side without water yet starts from the node's p), and its sensitivity to parameter k.
  double pressure(std::size_t i, bool multi_sided, int side) const {
    const double v = multi_sided ? side_p[i * mesh::kMaxPressureSides + side] : kNoSide;
    return std::isnan(v) ? p[i] : v;
  }
  double pressure_sensitivity(std::size_t i, bool multi_sided, int side, int k) const {
    const double* d = sensitivity(i, k);
    return multi_sided && !std::isnan(d[kDpSide + side]) ? d[kDpSide + side] : d[kDp];
  }
  double* sensitivity(std::size_t node, int k) { return &sens[(node * num_params + k) * kSensitivityFields]; }
  const double* sensitivity(std::size_t node, int k) const {
    return &sens[(node * num_params + k) * kSensitivityFields];
  }
  // A triangle's area at the current positions, and its derivative w.r.t. parameter k from
  // its corners' position sensitivities.
  double triangle_area(const std::array<std::int32_t, 3>& t) const {
    return 0.5 * ((x[t[1]] - x[t[0]]) * (y[t[2]] - y[t[0]]) - (x[t[2]] - x[t[0]]) * (y[t[1]] - y[t[0]]));
  }
  double triangle_area_sensitivity(const std::array<std::int32_t, 3>& t, int k) const {
    const double* d0 = sensitivity(t[0], k);
    const double* d1 = sensitivity(t[1], k);
    const double* d2 = sensitivity(t[2], k);
    const double x1 = x[t[1]] - x[t[0]], y1 = y[t[1]] - y[t[0]];
    const double x2 = x[t[2]] - x[t[0]], y2 = y[t[2]] - y[t[0]];
    const double dx1 = d1[kDx] - d0[kDx], dy1 = d1[kDy] - d0[kDy];
    const double dx2 = d2[kDx] - d0[kDx], dy2 = d2[kDy] - d0[kDy];
    return 0.5 * (dx1 * y2 + x1 * dy2 - dx2 * y1 - x2 * dy1);
  }
  // Walls and removed particles have no velocity unknowns (a wavemaker's wall moves as it is
  // told, engine/motion).
  bool is_fixed(std::size_t i) const {
    return kind[i] == mesh::NodeKind::Wall || kind[i] == mesh::NodeKind::Removed;
  }
};

}  // namespace pfem
