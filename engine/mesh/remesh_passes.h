#pragma once
// The passes of remesh() (remesher.cpp), in the files named below (internal to engine/mesh/).
// Between passes a finite face's info is 1 when it is kept (water) and 0 when it is dropped; a
// pass that marks faces otherwise sets them back to 0 or 1 before it returns.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/delaunay_types.h"
#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// The previous step's mesh as the face rules see it (RemeshOptions::previous_boundary,
// previous_triangles).
class PreviousMesh {
 public:
  PreviousMesh(std::size_t n, const RemeshOptions& options) : boundary_(options.previous_boundary), in_(n, 0) {
    for (const auto& t : options.previous_triangles)
      for (const std::int32_t i : t)
        if (static_cast<std::size_t>(i) < n) in_[i] = 1;
  }
  // On its boundary: on its free surface, or a particle in no triangle of it.
  bool was_boundary(std::int32_t i) const {
    return static_cast<std::size_t>(i) < boundary_.size() && boundary_[i] != 0;
  }
  // In one of its triangles and not on its boundary: inside the water.
  bool was_inside(std::int32_t i) const { return in_[i] && !was_boundary(i); }

 private:
  std::span<const std::uint8_t> boundary_;
  std::vector<std::uint8_t> in_;
};

// constrained_delaunay.cpp: the triangulation of the nodes that are not Removed into tri (empty),
// coincident ones merged, with the constraints inserted when it has faces. Returns whether they
// were (some given and tri of dimension 2).
bool triangulate_nodes(std::span<const double> x, std::span<const double> y, std::span<const NodeKind> kind,
                       std::span<const std::array<std::int32_t, 2>> constraints, Delaunay& tri);

// alpha_test.cpp: the alpha test of one face, and the faces kept by it and the gap rule.
bool passes_alpha_test(const Point& p0, const Point& p1, const Point& p2, double max_radius);
void keep_alpha_faces(Delaunay& tri, std::span<const double> x, std::span<const double> y,
                      std::span<const NodeKind> kind, const RemeshOptions& options, const PreviousMesh& previous);

// water_pockets.cpp: dropped faces that are water all the same, closed in by walls, beams and
// kept faces.
void keep_wall_pockets(Delaunay& tri, std::span<const NodeKind> kind, const RemeshOptions& options);
void keep_voids_at_beams(Delaunay& tri, std::span<const NodeKind> kind, const RemeshOptions& options,
                         const PreviousMesh& previous);

// hanging_faces.cpp: the gravity rule, kept faces above the waterline at a wall dropped.
void drop_hanging_faces(Delaunay& tri, std::span<const double> x, std::span<const double> y,
                        std::span<const NodeKind> kind, const RemeshOptions& options);

// fluid_mesh.cpp: the kept faces' FluidMesh (triangles, in_mesh, free surface, contact edges,
// and the pressure sides when constrained), and the free edges that bound them.
bool is_free_edge(const Delaunay& tri, FaceHandle f, int e, std::span<const NodeKind> kind);
FluidMesh extract_fluid_mesh(const Delaunay& tri, std::span<const NodeKind> kind, bool constrained,
                             std::span<const LineRider> riders);

// pressure_sides.cpp: FluidMesh::sides and corner_side of the kept faces (a rider ranked as the
// far end of its segment, LineRider).
void assign_pressure_sides(const Delaunay& tri, std::span<const NodeKind> kind, std::span<const LineRider> riders,
                           FluidMesh& mesh);

}  // namespace pfem::mesh
