#pragma once
// The wall guard of a PFEM step: no particle passes through a wall or beam within a step.
// Pure geometry on the nodes' positions at both ends of the step: a particle in the mesh whose
// converged move crosses a wall or beam is to be removed (UnifiedStep takes it out); a particle
// outside the mesh falls freely and stops where it was if its path would cross one.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

struct Point2 {
  double x = 0.0, y = 0.0;
};

// Whether segments pq and ab cross or touch (their boxes overlap and each straddles the other's
// line; the box test also keeps collinear segments apart on their common line from counting).
bool segments_cross(Point2 p, Point2 q, Point2 a, Point2 b);

// Every node's position at t_n (x0, y0) and where the step takes it (x1, y1).
struct StepEnds {
  std::span<const double> x0, y0, x1, y1;
};

// A wall or beam piece at t_n (a0 b0) and at t_{n+1} (a1 b1: the same points for a fixed wall).
struct WallPiece {
  Point2 a0, b0, a1, b1;
};

// The pieces (node pairs) at both ends of the step.
std::vector<WallPiece> wall_pieces(std::span<const std::array<std::int32_t, 2>> pieces, const StepEnds& ends);

// Whether the move p -> q crosses or touches a piece where it was at t_n or where it is at
// t_{n+1}. The area a moving piece sweeps in between is not tested: a beam that passes over a
// particle within the step, crossing its move at neither end, is not seen.
bool crosses_wall(std::span<const WallPiece> walls, Point2 p, Point2 q);

// Per node, 1 for a fluid particle whose move crosses a wall or beam (to be removed), else 0.
// Only particles sharing a triangle with a wall or structure node are near enough to cross, and
// only they are tested.
std::vector<std::uint8_t> particles_crossing_walls(std::span<const std::array<std::int32_t, 3>> triangles,
                                                   std::span<const mesh::NodeKind> kind, const StepEnds& ends,
                                                   std::span<const WallPiece> walls);

// A free particle's step: v = v0 + dt g, x = x0 + dt v (semi-implicit Euler: x = x0 + dt v0 +
// dt^2 g). One whose path crosses a wall or beam hits it and sticks, as water does at a no-slip
// wall: it stays at x0 with v = 0.
struct FreeFall {
  Point2 x, v;
  bool hit = false;
};
FreeFall fall_freely(Point2 x0, Point2 v0, Point2 g, double dt, std::span<const WallPiece> walls);

// Moves every fluid particle outside the mesh by fall_freely, and its position and velocity
// sensitivities by the same rule (gravity is no parameter).
void move_free_particles(std::span<const std::uint8_t> in_mesh, std::span<const WallPiece> walls, Point2 g, double dt,
                         NodeState& nodes);

}  // namespace pfem
