#pragma once
// PFEM remeshing (theory §6, step 1): Delaunay triangulation of all nodes at their current
// positions (CGAL, exact predicates), the alpha-shape test per face, removal of triangles
// without a fluid particle, and free-surface detection. CGAL stays inside remesher.cpp.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pfem::mesh {

// Fluid particles carry the fluid; wall and structure nodes bound it. Only fluid particles
// can be free-surface nodes; wall and structure nodes are never removed.
enum class NodeKind : std::uint8_t { Fluid = 0, Wall = 1, Structure = 2 };

struct RemeshOptions {
  double h = 0.0;      // particle spacing [m], > 0
  double alpha = 1.2;  // keep a triangle when its circumradius <= alpha * h
};

// The fluid mesh of one time step.
struct FluidMesh {
  std::vector<std::array<std::int32_t, 3>> triangles;  // node indices, counter-clockwise
  std::vector<std::uint8_t> in_mesh;       // per node: a corner of at least one kept triangle
  std::vector<std::uint8_t> free_surface;  // per node: fluid particle on the kept region's boundary
};

// Triangulates the nodes (x[i], y[i]) of kinds kind[i]. Throws std::invalid_argument on
// mismatched spans or a non-positive h or alpha. Thread-safe (no shared state).
FluidMesh remesh(std::span<const double> x, std::span<const double> y,
                 std::span<const NodeKind> kind, const RemeshOptions& options);

}  // namespace pfem::mesh
