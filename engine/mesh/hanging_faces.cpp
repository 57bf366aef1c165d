// The gravity rule of remesh(): kept triangles hanging above the waterline at a wall dropped.
#include "engine/mesh/remesh_passes.h"

#include <cmath>

namespace pfem::mesh {

// Drops "hanging" triangles above the waterline at a wall: a wall/structure node that is higher
// (against gravity) than every particle of its triangle by more than a tenth of h, in a triangle
// open to the air along an edge at that node: one particle on the free surface with two wall
// nodes wholly at or above it, or two particles with one wall node above both. They wet the wall
// above the water, add mass that nothing supports and make the contact line creep up the wall
// (still water then flows at the walls). A triangle whose wall edge reaches below its particle is
// kept: it is the water at the contact line, or a jet climbing the wall that must stay attached
// to it. Dropping one can open the next (the particle under it is now on the surface): repeated
// until none is left. A beam rider (RemeshOptions::riders) is placed level with its particle: in a
// triangle with one, the other wall node reaches below the particle when it lies below it by any
// amount (1e-6 h), and the rider never does. (With h/10, the triangle of a rider near a beam node,
// the water at the contact line, was dropped and the rider left out of the mesh.)
void drop_hanging_faces(Delaunay& tri, std::span<const double> x, std::span<const double> y,
                        std::span<const NodeKind> kind, const RemeshOptions& options) {
  const double g_norm = std::hypot(options.gravity_x, options.gravity_y);
  const auto height_over = [&](std::int32_t i, std::int32_t j) {  // of node i above node j
    return -((x[i] - x[j]) * options.gravity_x + (y[i] - y[j]) * options.gravity_y) / g_norm;
  };
  std::vector<std::uint8_t> rider(kind.size(), 0);
  for (const LineRider& r : options.riders) rider[r.node] = 1;
  std::vector<FaceHandle> drop;
  for (int round = 0; g_norm > 0.0 && (round == 0 || !drop.empty()); ++round) {
    drop.clear();
    for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
      if (!f->info()) continue;
      int fluid = 0;
      for (int k = 0; k < 3; ++k) fluid += kind[f->vertex(k)->info()] == NodeKind::Fluid;
      if (fluid == 0 || fluid == 3) continue;
      bool hanging = true, open = false;
      const bool has_rider = rider[f->vertex(0)->info()] || rider[f->vertex(1)->info()] || rider[f->vertex(2)->info()];
      const double below = (has_rider ? 1e-6 : 0.1) * options.h;
      for (int w = 0; w < 3 && hanging; ++w) {
        const std::int32_t wall = f->vertex(w)->info();
        if (kind[wall] == NodeKind::Fluid) continue;
        const bool reaches = !rider[wall];  // below a particle
        for (int k = 0; k < 3; ++k) {
          const std::int32_t i = f->vertex(k)->info();
          if (kind[i] != NodeKind::Fluid) continue;
          // One particle: both wall nodes at or above it; two: the wall node above both.
          if (fluid == 1 ? reaches && height_over(wall, i) < -below : height_over(wall, i) <= 0.1 * options.h)
            hanging = false;
        }
        // The edges at the wall node are those opposite the other two vertices.
        open = open || is_free_edge(tri, f, Delaunay::ccw(w), kind) || is_free_edge(tri, f, Delaunay::cw(w), kind);
      }
      if (hanging && open) drop.push_back(f);
    }
    for (auto f : drop) f->info() = 0;
  }
}

}  // namespace pfem::mesh
