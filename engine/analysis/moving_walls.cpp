#include "engine/analysis/moving_walls.h"

#include <cmath>
#include <map>

namespace pfem {

namespace {
motion::Sensitive signal_at(const motion::WallMotion& m, double t, int k) {
  return m.signal.displacement(t, k >= 0 ? m.seeds[k] : motion::SignalSeed{});
}
}  // namespace

WallKinematics wall_kinematics(const Problem& problem, const NodeState& nodes, double t0, double t1) {
  WallKinematics out;
  if (problem.moving_walls.empty()) return out;
  const int P = nodes.num_params;
  out.velocity.assign(2 * nodes.size(), 0.0);
  out.sensitivity.assign(2 * nodes.size() * P, 0.0);
  const double inv_dt = 1.0 / (t1 - t0);
  for (const auto& m : problem.moving_walls) {
    for (int k = -1; k < P; ++k) {
      const motion::Sensitive s0 = signal_at(m, t0, k), s1 = signal_at(m, t1, k);
      for (const int i : m.nodes) {
        const motion::Placement a = motion::place(m, s0, nodes.x0[i], nodes.y0[i]);
        const motion::Placement b = motion::place(m, s1, nodes.x0[i], nodes.y0[i]);
        if (k < 0) {
          out.velocity[2 * i] = (b.x - a.x) * inv_dt, out.velocity[2 * i + 1] = (b.y - a.y) * inv_dt;
        } else {
          const std::size_t at = (static_cast<std::size_t>(i) * P + k) * 2;
          out.sensitivity[at] = (b.dx - a.dx) * inv_dt, out.sensitivity[at + 1] = (b.dy - a.dy) * inv_dt;
        }
      }
    }
  }
  return out;
}

void place_moving_walls(const Problem& problem, double t, const WallKinematics& step, NodeState& nodes) {
  const int P = nodes.num_params;
  for (const auto& m : problem.moving_walls) {
    for (int k = -1; k < P; ++k) {
      const motion::Sensitive s = signal_at(m, t, k);
      for (const int i : m.nodes) {
        const motion::Placement q = motion::place(m, s, nodes.x0[i], nodes.y0[i]);
        const std::uint8_t free = problem.slip_of(i);
        const bool set_x = free != kSlipX, set_y = free != kSlipY;
        if (k < 0) {
          if (set_x) nodes.x[i] = q.x, nodes.vx[i] = step.velocity.empty() ? 0.0 : step.velocity[2 * i];
          if (set_y) nodes.y[i] = q.y, nodes.vy[i] = step.velocity.empty() ? 0.0 : step.velocity[2 * i + 1];
          continue;
        }
        double* d = nodes.sensitivity(i, k);
        const std::size_t at = (static_cast<std::size_t>(i) * P + k) * 2;
        if (set_x) d[NodeState::kDx] = q.dx, d[NodeState::kDvx] = step.sensitivity.empty() ? 0.0 : step.sensitivity[at];
        if (set_y) d[NodeState::kDy] = q.dy, d[NodeState::kDvy] = step.sensitivity.empty() ? 0.0 : step.sensitivity[at + 1];
      }
    }
  }
}

void clear_under_moving_walls(const Problem& problem, const NodeState& nodes, std::vector<mesh::NodeKind>& kind,
                              std::vector<std::array<std::int32_t, 2>>& constraints) {
  std::map<std::int32_t, std::vector<std::int32_t>> links;  // per left-out node: its constraint neighbours
  for (std::size_t j = 0; j < problem.sliding_walls.size(); ++j) {
    if (problem.sliding_motion[j] >= 0) continue;
    const int i = problem.sliding_walls[j].node;
    for (const auto& m : problem.moving_walls)
      for (const int w : m.nodes)
        if (std::hypot(nodes.x[w] - nodes.x[i], nodes.y[w] - nodes.y[i]) < 0.5 * problem.h) links[i];
  }
  if (links.empty()) return;
  for (const auto& [a, b] : constraints) {
    if (auto it = links.find(a); it != links.end()) it->second.push_back(b);
    if (auto it = links.find(b); it != links.end()) it->second.push_back(a);
  }
  std::erase_if(links, [](const auto& l) { return l.second.size() != 2; });  // a corner, a beam's foot: kept
  std::vector<std::array<std::int32_t, 2>> out;
  for (const auto& [a, b] : constraints) {
    const bool left_a = links.count(a) != 0, left_b = links.count(b) != 0;
    if (!left_a && !left_b) out.push_back({a, b});
    if (left_a == left_b) continue;
    // Walk from the kept end across the left-out nodes to the next kept node.
    std::int32_t from = left_a ? b : a, previous = from, at = left_a ? a : b;
    while (links.count(at) != 0) {
      const auto& l = links.at(at);
      const std::int32_t next = l[0] == previous ? l[1] : l[0];
      previous = at, at = next;
    }
    if (from < at) out.push_back({from, at});  // each joined piece is reached from both ends
  }
  constraints = std::move(out);
  for (const auto& l : links) kind[l.first] = mesh::NodeKind::Removed;
}

std::vector<mesh::SlidingWallNode> sliding_walls_at(const Problem& problem, int num_params, double t,
                                                    std::vector<std::array<double, 4>>& sensitivities) {
  std::vector<mesh::SlidingWallNode> out = problem.sliding_walls;
  sensitivities.assign(out.size() * num_params, {0.0, 0.0, 0.0, 0.0});
  if (problem.moving_walls.empty()) return out;
  for (std::size_t j = 0; j < out.size(); ++j) {
    const int w = problem.sliding_motion[j];
    if (w < 0) continue;
    const auto& m = problem.moving_walls[w];
    const auto& rest = problem.sliding_walls[j];
    for (int k = -1; k < num_params; ++k) {
      const motion::Placement q = motion::place(m, signal_at(m, t, k), rest.home_x, rest.home_y, rest.tx, rest.ty);
      if (k < 0) out[j].home_x = q.x, out[j].home_y = q.y, out[j].tx = q.tx, out[j].ty = q.ty;
      else sensitivities[j * num_params + k] = {q.dx, q.dy, q.dtx, q.dty};
    }
  }
  return out;
}

}  // namespace pfem
