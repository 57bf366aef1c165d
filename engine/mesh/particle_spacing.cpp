#include "engine/mesh/particle_spacing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

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

namespace {
// The distance from (px, py) to the segment from (ax, ay) to (bx, by).
double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double ex = bx - ax, ey = by - ay, e2 = ex * ex + ey * ey;
  const double s = e2 > 0.0 ? std::clamp(((px - ax) * ex + (py - ay) * ey) / e2, 0.0, 1.0) : 0.0;
  return std::hypot(px - ax - s * ex, py - ay - s * ey);
}
}  // namespace

std::vector<SplitEdge> edges_to_split(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                                      std::span<const NodeKind> kind, double surface_length, double interior_length,
                                      const WallClearance& walls) {
  std::vector<std::vector<std::int32_t>> along(x.size());  // per wall node: the other ends of its segments
  for (const auto& [a, b] : walls.segments) along[a].push_back(b), along[b].push_back(a);
  // Whether the middle of particle p's edge to wall node w keeps clear of w's segments.
  const auto clear_of_walls = [&](std::int32_t p, std::int32_t w) {
    const double mx = 0.5 * (x[p] + x[w]), my = 0.5 * (y[p] + y[w]);
    for (const std::int32_t u : along[w])
      if (distance_to_segment(mx, my, x[w], y[w], x[u], y[u]) < walls.distance) return false;
    return !along[w].empty();
  };
  // The edges between two surface particles that lie in one triangle only: the free surface's own.
  std::map<std::pair<std::int32_t, std::int32_t>, int> surface_pairs;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const std::int32_t a = t[e], b = t[(e + 1) % 3];
      if (kind[a] == NodeKind::Fluid && kind[b] == NodeKind::Fluid && mesh.free_surface[a] && mesh.free_surface[b])
        ++surface_pairs[std::minmax(a, b)];
    }
  std::vector<SplitEdge> edges;
  std::vector<std::uint8_t> used(x.size(), 0);
  const double surface2 = surface_length * surface_length, interior2 = interior_length * interior_length;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const int ca = (kind[mesh.triangles[t][e]] == NodeKind::Fluid) ? e : (e + 1) % 3;  // the particle's corner
      const int cb = ca == e ? (e + 1) % 3 : e;
      const std::int32_t a = mesh.triangles[t][ca], b = mesh.triangles[t][cb];
      if (used[a] || used[b] || kind[a] != NodeKind::Fluid || kind[b] == NodeKind::Removed) continue;
      const bool wall = kind[b] != NodeKind::Fluid;
      const bool interior = !mesh.free_surface[a] && !mesh.free_surface[b];
      // Both ends on the surface: an edge of the surface itself, or a chord through the water.
      const bool both = !wall && mesh.free_surface[a] && mesh.free_surface[b];
      const double dx = x[a] - x[b], dy = y[a] - y[b];
      if (dx * dx + dy * dy <= (interior || both ? interior2 : surface2)) continue;
      if (wall && (!interior || !clear_of_walls(a, b))) continue;
      used[a] = used[b] = 1;
      edges.push_back({a, b, wall ? mesh.side(t, cb) : 0, both && surface_pairs[std::minmax(a, b)] == 1});
    }
  }
  return edges;
}

}  // namespace pfem::mesh
