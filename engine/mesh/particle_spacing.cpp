#include "engine/mesh/particle_spacing.h"

#include <cmath>

namespace pfem::mesh {

int remove_close_particles(const FluidMesh& mesh, std::span<const double> x,
                           std::span<const double> y, std::span<NodeKind> kind, double min_distance) {
  const double d2 = min_distance * min_distance;
  int removed = 0;
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      std::int32_t a = t[e], b = t[(e + 1) % 3];
      if (kind[a] == NodeKind::Removed || kind[b] == NodeKind::Removed) continue;
      const double dx = x[a] - x[b], dy = y[a] - y[b];
      if (dx * dx + dy * dy >= d2) continue;
      const bool fa = kind[a] == NodeKind::Fluid, fb = kind[b] == NodeKind::Fluid;
      if (!fa && !fb) continue;
      const std::int32_t gone = (fa && fb) ? std::max(a, b) : (fa ? a : b);
      kind[gone] = NodeKind::Removed;
      ++removed;
    }
  }
  // A particle near the middle of a wall or structure edge is far from both its nodes but
  // makes the same sliver: measure its distance to the edge of its triangle.
  for (const auto& t : mesh.triangles) {
    int particle = -1, walls = 0;
    for (int k = 0; k < 3; ++k) {
      if (kind[t[k]] == NodeKind::Fluid) particle = k;
      else if (kind[t[k]] != NodeKind::Removed) ++walls;
    }
    if (walls != 2 || particle < 0) continue;
    const std::int32_t p = t[particle], a = t[(particle + 1) % 3], b = t[(particle + 2) % 3];
    const double ex = x[b] - x[a], ey = y[b] - y[a];
    const double twice_area = std::abs(ex * (y[p] - y[a]) - ey * (x[p] - x[a]));
    if (twice_area * twice_area < d2 * (ex * ex + ey * ey)) {  // height below min_distance
      kind[p] = NodeKind::Removed;
      ++removed;
    }
  }
  return removed;
}

std::vector<std::array<std::int32_t, 2>> edges_to_split(const FluidMesh& mesh, std::span<const double> x,
                                                        std::span<const double> y,
                                                        std::span<const NodeKind> kind, double surface_length,
                                                        double interior_length) {
  std::vector<std::array<std::int32_t, 2>> edges;
  std::vector<std::uint8_t> used(x.size(), 0);
  const double surface2 = surface_length * surface_length, interior2 = interior_length * interior_length;
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const std::int32_t a = t[e], b = t[(e + 1) % 3];
      if (used[a] || used[b] || kind[a] == NodeKind::Removed || kind[b] == NodeKind::Removed) continue;
      // Particle-particle edges only: an edge from a particle to a wall node can run along
      // the wall, and its middle would sit on the wall.
      if (kind[a] != NodeKind::Fluid || kind[b] != NodeKind::Fluid) continue;
      // Not along the free surface: a particle there would let the alpha test close gaps in
      // the surface and add water.
      if (mesh.free_surface[a] && mesh.free_surface[b]) continue;
      const double dx = x[a] - x[b], dy = y[a] - y[b];
      const bool interior = !mesh.free_surface[a] && !mesh.free_surface[b];
      if (dx * dx + dy * dy <= (interior ? interior2 : surface2)) continue;
      used[a] = used[b] = 1;
      edges.push_back({a, b});
    }
  }
  return edges;
}

}  // namespace pfem::mesh
