// remesh()'s result from the kept faces: the triangles and their nodes, the free surface (the
// free edges' ends) and where it meets a wall.
#include "engine/mesh/remesh_passes.h"

namespace pfem::mesh {

// Edge e of the kept face f (the edge opposite vertex e) is on the boundary of the kept region
// when the face across it is infinite or not kept. It is a free edge when it is on the
// boundary, is not a constraint (a wall or beam, whatever lies beyond it) and has a fluid end
// (an edge between two wall or structure nodes is a wall).
bool is_free_edge(const Delaunay& tri, FaceHandle f, int e, std::span<const NodeKind> kind) {
  const auto across = f->neighbor(e);
  if (!tri.is_infinite(across) && across->info()) return false;
  if (f->is_constrained(e)) return false;
  return kind[f->vertex(Delaunay::ccw(e))->info()] == NodeKind::Fluid ||
         kind[f->vertex(Delaunay::cw(e))->info()] == NodeKind::Fluid;
}

FluidMesh extract_fluid_mesh(const Delaunay& tri, std::span<const NodeKind> kind, bool constrained,
                             std::span<const LineRider> riders) {
  const std::size_t n = kind.size();
  FluidMesh mesh;
  mesh.in_mesh.assign(n, 0);
  mesh.free_surface.assign(n, 0);
  mesh.triangles.reserve(tri.number_of_faces());
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    mesh.triangles.push_back({i0, i1, i2});  // CGAL faces are counter-clockwise
    mesh.in_mesh[i0] = mesh.in_mesh[i1] = mesh.in_mesh[i2] = 1;
  }
  if (constrained) assign_pressure_sides(tri, kind, riders, mesh);

  // Both ends of a free edge (see is_free_edge) are on the free surface, wall nodes at the
  // contact line too. A constraint edge is never free: the triangle on its other side was
  // evaluated on its own (no triangle crosses a constraint).
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    for (int e = 0; e < 3; ++e) {
      if (!is_free_edge(tri, f, e, kind)) continue;
      // Edge e is opposite vertex e: its ends are vertices ccw(e) and cw(e).
      const std::int32_t a = f->vertex(Delaunay::ccw(e))->info(), b = f->vertex(Delaunay::cw(e))->info();
      mesh.free_surface[a] = mesh.free_surface[b] = 1;
      const auto on_line = [&](std::int32_t i) { return kind[i] == NodeKind::Wall || kind[i] == NodeKind::Structure; };
      if (kind[a] == NodeKind::Fluid && on_line(b)) mesh.contact_edges.push_back({a, b});
      if (kind[b] == NodeKind::Fluid && on_line(a)) mesh.contact_edges.push_back({b, a});
    }
  }
  return mesh;
}

}  // namespace pfem::mesh
