#pragma once
// PFEM remeshing (theory §6, step 1): Delaunay triangulation of all nodes at their current
// positions (CGAL, exact predicates), the alpha-shape test per face, removal of triangles
// without a fluid particle, and free-surface detection. CGAL stays inside remesher.cpp.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pfem::mesh {

// Fluid particles carry the fluid; wall and structure nodes bound it and are never removed.
// Removed particles (taken out for mesh quality) keep their index but are not triangulated.
enum class NodeKind : std::uint8_t { Fluid = 0, Wall = 1, Structure = 2, Removed = 3 };

struct RemeshOptions {
  double h = 0.0;      // particle spacing [m], > 0
  double alpha = 1.2;  // keep a triangle when its circumradius <= alpha * h
  // Gravity (any length; zero disables): triangles of two wall/structure nodes hanging above a
  // boundary particle are dropped (see remesher.cpp).
  double gravity_x = 0.0, gravity_y = 0.0;
};

// The fluid mesh of one time step.
struct FluidMesh {
  std::vector<std::array<std::int32_t, 3>> triangles;  // node indices, counter-clockwise
  std::vector<std::uint8_t> in_mesh;       // per node: a corner of at least one kept triangle
  // per node: on a free edge of the kept region (a boundary edge with a fluid end), p = 0;
  // wall and structure nodes where the free surface meets them are included.
  std::vector<std::uint8_t> free_surface;
};

// Triangulates the nodes (x[i], y[i]) of kinds kind[i]. Throws std::invalid_argument on
// mismatched spans, a non-positive (or non-finite) h or alpha, or a non-finite coordinate.
// Coincident nodes (equal coordinates) are merged: the lowest index among them
// represents the point, and the later duplicates get in_mesh = 0 and appear in no triangle.
// Thread-safe (no shared state).
FluidMesh remesh(std::span<const double> x, std::span<const double> y,
                 std::span<const NodeKind> kind, const RemeshOptions& options);

}  // namespace pfem::mesh
