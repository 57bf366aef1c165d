#include "engine/solve/wall_guard.h"

#include <algorithm>

namespace pfem {

bool segments_cross(Point2 p, Point2 q, Point2 a, Point2 b) {
  if (std::max(p.x, q.x) < std::min(a.x, b.x) || std::max(a.x, b.x) < std::min(p.x, q.x) ||
      std::max(p.y, q.y) < std::min(a.y, b.y) || std::max(a.y, b.y) < std::min(p.y, q.y))
    return false;
  // Twice the signed area of uvw: > 0 when w is left of u -> v.
  const auto orient = [](Point2 u, Point2 v, Point2 w) {
    return (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x);
  };
  const double d1 = orient(a, b, p), d2 = orient(a, b, q);
  const double d3 = orient(p, q, a), d4 = orient(p, q, b);
  return ((d1 > 0) != (d2 > 0) || d1 == 0 || d2 == 0) && ((d3 > 0) != (d4 > 0) || d3 == 0 || d4 == 0);
}

std::vector<WallPiece> wall_pieces(std::span<const std::array<std::int32_t, 2>> pieces, const StepEnds& ends) {
  std::vector<WallPiece> walls;
  walls.reserve(pieces.size());
  for (const auto& [a, b] : pieces) {
    walls.push_back(
        {{ends.x0[a], ends.y0[a]}, {ends.x0[b], ends.y0[b]}, {ends.x1[a], ends.y1[a]}, {ends.x1[b], ends.y1[b]}});
  }
  return walls;
}

bool crosses_wall(std::span<const WallPiece> walls, Point2 p, Point2 q) {
  for (const WallPiece& w : walls) {
    if (segments_cross(p, q, w.a0, w.b0)) return true;
    // A fixed piece ends where it was: one test.
    const bool moves = w.a1.x != w.a0.x || w.a1.y != w.a0.y || w.b1.x != w.b0.x || w.b1.y != w.b0.y;
    if (moves && segments_cross(p, q, w.a1, w.b1)) return true;
  }
  return false;
}

std::vector<std::uint8_t> particles_crossing_walls(std::span<const std::array<std::int32_t, 3>> triangles,
                                                   std::span<const mesh::NodeKind> kind, const StepEnds& ends,
                                                   std::span<const WallPiece> walls) {
  std::vector<std::uint8_t> crossing(kind.size(), 0);
  for (const auto& t : triangles) {
    const bool by_wall = kind[t[0]] != mesh::NodeKind::Fluid || kind[t[1]] != mesh::NodeKind::Fluid ||
                         kind[t[2]] != mesh::NodeKind::Fluid;
    for (int c = 0; by_wall && c < 3; ++c) {
      const int i = t[c];
      if (kind[i] != mesh::NodeKind::Fluid || crossing[i]) continue;
      crossing[i] = crosses_wall(walls, {ends.x0[i], ends.y0[i]}, {ends.x1[i], ends.y1[i]});
    }
  }
  return crossing;
}

FreeFall fall_freely(Point2 x0, Point2 v0, Point2 g, double dt, std::span<const WallPiece> walls) {
  const Point2 v{v0.x + dt * g.x, v0.y + dt * g.y};
  const Point2 x{x0.x + dt * v.x, x0.y + dt * v.y};
  if (crosses_wall(walls, x0, x)) return {x0, {0.0, 0.0}, true};
  return {x, v, false};
}

void move_free_particles(std::span<const std::uint8_t> in_mesh, std::span<const WallPiece> walls, Point2 g, double dt,
                         NodeState& nodes) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.kind[i] != mesh::NodeKind::Fluid || in_mesh[i]) continue;
    const FreeFall f = fall_freely({nodes.x[i], nodes.y[i]}, {nodes.vx[i], nodes.vy[i]}, g, dt, walls);
    nodes.x[i] = f.x.x, nodes.y[i] = f.x.y;
    nodes.vx[i] = f.v.x, nodes.vy[i] = f.v.y;
    for (int k = 0; k < nodes.num_params; ++k) {
      double* d = nodes.sensitivity(i, k);
      if (f.hit) d[NodeState::kDvx] = d[NodeState::kDvy] = 0.0;
      d[NodeState::kDx] += dt * d[NodeState::kDvx];
      d[NodeState::kDy] += dt * d[NodeState::kDvy];
    }
  }
}

}  // namespace pfem
