#include "engine/analysis/slip_wall_remap.h"

#include <vector>

namespace pfem {

void remap_slip_velocities(std::span<const mesh::SlidingWallNode> sliding, std::span<const std::array<double, 4>> dwall,
                           std::span<const std::uint8_t> slip, std::span<const std::uint8_t> wet, NodeState& nodes) {
  const int P = nodes.num_params;
  const auto is_wet = [&](std::int32_t i) { return i >= 0 && static_cast<std::size_t>(i) < wet.size() && wet[i]; };
  struct Remap {
    std::int32_t node;
    int field;  // kDvx or kDvy: the free component
    double v;
    std::vector<double> dv;
  };
  std::vector<Remap> remaps;  // all from the values after the step, then written
  for (std::size_t j = 0; j < sliding.size(); ++j) {
    const mesh::SlidingWallNode& s = sliding[j];
    const std::int32_t n = s.node;
    if (static_cast<std::size_t>(n) >= slip.size() || slip[n] == 0 || !is_wet(n)) continue;
    // Offsets along the wall from n's place: n's own (o) and its neighbour's on the side of home (om).
    const double o = s.offset(nodes.x[n], nodes.y[n]);
    if (o == 0.0) continue;
    const std::int32_t m = s.neighbours[o > 0.0 ? 0 : 1];
    if (!is_wet(m)) continue;
    const double om = s.offset(nodes.x[m], nodes.y[m]), w = -o / (om - o);  // home = n + w (m - n)
    if (!(w >= 0.0 && w <= 1.0)) continue;
    const bool along_x = slip[n] == kSlipX;
    const std::vector<double>& v = along_x ? nodes.vx : nodes.vy;
    const int field = along_x ? NodeState::kDvx : NodeState::kDvy;
    Remap r{n, field, v[n] + w * (v[m] - v[n]), std::vector<double>(P)};
    for (int k = 0; k < P; ++k) {
      const auto d_offset = [&](std::int32_t i) {
        const double* d = nodes.sensitivity(i, k);
        return s.offset_derivative(nodes.x[i], nodes.y[i], d[NodeState::kDx], d[NodeState::kDy], dwall[j * P + k]);
      };
      const double dn = d_offset(n), dm = d_offset(m);
      const double dw = (-dn * (om - o) + o * (dm - dn)) / ((om - o) * (om - o));
      const double dvn = nodes.sensitivity(n, k)[field], dvm = nodes.sensitivity(m, k)[field];
      r.dv[k] = dvn + dw * (v[m] - v[n]) + w * (dvm - dvn);
    }
    remaps.push_back(std::move(r));
  }
  for (const Remap& r : remaps) {
    (r.field == NodeState::kDvx ? nodes.vx : nodes.vy)[r.node] = r.v;
    for (int k = 0; k < P; ++k) nodes.sensitivity(r.node, k)[r.field] = r.dv[k];
  }
}

}  // namespace pfem
