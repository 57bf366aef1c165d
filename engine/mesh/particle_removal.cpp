#include "engine/mesh/particle_removal.h"

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
  return removed;
}

}  // namespace pfem::mesh
