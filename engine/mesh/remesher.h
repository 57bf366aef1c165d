#pragma once
// PFEM remeshing (theory §6, step 1): (constrained) Delaunay triangulation of all nodes at
// their current positions (CGAL, exact predicates), with wall and beam segments as
// constraints, the alpha-shape test per face, removal of triangles without a fluid particle,
// and free-surface detection. CGAL stays inside engine/mesh/'s .cpp files (its types in the
// internal delaunay_types.h, remesh()'s passes in remesh_passes.h).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pfem::mesh {

// Fluid particles carry the fluid; wall and structure nodes bound it and are never removed.
// Removed particles (taken out for mesh quality) keep their index but are not triangulated.
enum class NodeKind : std::uint8_t { Fluid = 0, Wall = 1, Structure = 2, Removed = 3 };

// A node on wall or beam lines has one pressure per side of them (FluidMesh::corner_side), at
// most this many (the sides past the last share its pressure).
inline constexpr int kMaxPressureSides = 4;

// A node placed on a wall or beam segment (a, b) of RemeshOptions::constraints, between its ends
// (a beam rider: where the free surface meets a beam between two of its nodes, beam_riders.h).
// The segment is then two, (a, node) and (node, b); around a and b the node stands for the far
// end (b, a) when their pressure sides are ranked, so that a side keeps its rank whether or not a
// rider splits the segment.
struct LineRider {
  std::int32_t node = -1, a = -1, b = -1;
};

struct RemeshOptions {
  double h = 0.0;      // particle spacing [m], > 0
  double alpha = 1.2;  // keep a triangle when its circumradius <= alpha * h
  // Gravity (any length; zero disables): triangles of two wall/structure nodes hanging above a
  // boundary particle are dropped (see hanging_faces.cpp).
  double gravity_x = 0.0, gravity_y = 0.0;
  // Constraint segments, each a pair of node indices: consecutive nodes of the wall
  // polylines, and beam elements. Each segment is forced into the triangulation (a
  // constrained Delaunay triangulation), so no triangle crosses it: fluid on its two sides is
  // meshed independently and cannot leak through it. A constraint edge is never a free edge
  // (it is a wall), whatever lies on its other side. Empty (the default): plain Delaunay.
  // - An index outside [0, size) or a segment with equal ends throws std::invalid_argument.
  // - A segment with a Removed end is skipped. An end that is a merged duplicate (see
  //   remesh()) stands for the point's representative node, which has the same coordinates;
  //   a segment whose two ends are coincident nodes is skipped.
  // - A node lying exactly on a segment splits it (both parts are constraints).
  // - Segments must not cross each other except at shared nodes (walls meeting at a corner
  //   node, a beam clamped at a wall node). A segment that crosses an already inserted one in
  //   the interior of both is left out (only parts ending at nodes lying on it before the
  //   crossing stay); no node is ever invented, and no error is raised.
  std::vector<std::array<std::int32_t, 2>> constraints{};
  // Nodes splitting constraint segments (LineRider), at most one a segment. A rider whose node
  // is out of range or Removed, or whose (a, b) is not a constraint (in either order), throws
  // std::invalid_argument.
  std::span<const LineRider> riders{};
  // Per node, 1 for a node on the boundary of the previous step's mesh: on its free surface
  // (FluidMesh::free_surface) or a particle in no triangle of it; nodes past its end count as
  // 0. Empty (the default): no previous mesh. A triangle whose three nodes are all flagged
  // spans a gap between free surfaces (spray, a jet against a wall or the pool, an air pocket):
  // it is kept only when its circumradius <= boundary_alpha * h, so that gaps close only where
  // the surfaces have really met and water is not created out of air. A triangle whose three
  // nodes were in the previous mesh (previous_triangles) and none on its boundary is kept up to
  // 1.25 * alpha * h: it is inside water that air cannot reach within a step.
  std::span<const std::uint8_t> previous_boundary{};
  double boundary_alpha = 0.0;  // 0: same as alpha; above alpha counts as alpha; < 0 throws
  // The triangles of the previous mesh, the nodes' velocities [m/s] and the coming step's dt [s]
  // (empty, empty, 0: not used). A triangle that was not in the previous mesh and whose three
  // nodes are particles flagged in previous_boundary spans a gap between free surfaces (a jet
  // meeting the pool, spray landing, an air pocket closing): it is kept only when its corners
  // move as water does, the divergence of their linear velocity field at most half the norm of
  // its rate of strain (water is incompressible; two surfaces closing head-on have a ratio of 1),
  // or when the gap would close within the step (div v * dt <= -1). Without it, the alpha test
  // closed every gap narrower than about alpha * h as soon as it formed, and the air in it became
  // water (the largest area drift of the dam break to 1 s, a block dropped into a pool and a dam
  // break over a step: 11.6, 8.0 and 21.5 %; 4.7, 2.8 and 7.1 % with it). vx and vy, when given,
  // have one entry per node; dt must then be finite and > 0.
  std::span<const std::array<std::int32_t, 3>> previous_triangles{};
  std::span<const double> vx{}, vy{};
  double dt = 0.0;
};

// The fluid mesh of one time step.
struct FluidMesh {
  std::vector<std::array<std::int32_t, 3>> triangles;  // node indices, counter-clockwise
  std::vector<std::uint8_t> in_mesh;       // per node: a corner of at least one kept triangle
  // per node: on a free edge of the kept region (a boundary edge with a fluid end that is not
  // a constraint); wall and structure nodes where the free surface meets them are included.
  std::vector<std::uint8_t> free_surface;
  // Free edges from a fluid particle to a wall or structure node (particle, node): where the free
  // surface meets a wall (see contact_line.h) or a beam, in the order of the triangulation's faces.
  std::vector<std::array<std::int32_t, 2>> contact_edges;
  // The riders it was made with (RemeshOptions::riders).
  std::vector<LineRider> riders;
  // The sides of the wall and beam lines (the constraints) at a node: its constrained edges cut
  // the plane around it into sectors, and the water in each sector has its own pressure there
  // (a plate with water on both sides carries the difference; one pressure for both would
  // cancel the pressure's load wherever both sides are wet). Per node, its number of sides (1:
  // one pressure; up to kMaxPressureSides); per triangle and corner, the side it lies on: the
  // rank, among the node's constrained neighbours sorted by index, of the neighbour where its
  // sector begins (counter-clockwise). Empty (no constraints): one side everywhere.
  std::vector<std::uint8_t> sides;
  std::vector<std::array<std::uint8_t, 3>> corner_side;

  bool multi_sided(std::size_t node) const { return node < sides.size() && sides[node] > 1; }
  int side(std::size_t triangle, int corner) const { return corner_side.empty() ? 0 : corner_side[triangle][corner]; }
};

// Triangulates the nodes (x[i], y[i]) of kinds kind[i], honouring options.constraints.
// Throws std::invalid_argument on mismatched spans, a non-positive (or non-finite) h or
// alpha, a negative or non-finite boundary_alpha, a non-finite coordinate, an invalid
// constraint, or velocities of the wrong size or without a dt > 0 (see RemeshOptions).
// Coincident nodes (equal coordinates) are merged: the lowest index among them
// represents the point, and the later duplicates get in_mesh = 0 and appear in no triangle.
// Thread-safe (no shared state).
FluidMesh remesh(std::span<const double> x, std::span<const double> y,
                 std::span<const NodeKind> kind, const RemeshOptions& options);

}  // namespace pfem::mesh
