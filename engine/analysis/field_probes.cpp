#include "engine/analysis/field_probes.h"

#include <algorithm>
#include <array>
#include <map>
#include <utility>

#include "engine/analysis/dual.h"

namespace pfem {
ProbeSite wave_gauge_site(const mesh::FluidMesh& mesh, const NodeState& nodes, double x) {
  // Boundary edges: those of one kept triangle only. An edge that crosses the line (see below)
  // lies only in triangles that span it, lo <= x < hi: the others are left out.
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  for (const auto& t : mesh.triangles) {
    const auto [lo, hi] = std::minmax({nodes.x[t[0]], nodes.x[t[1]], nodes.x[t[2]]});
    if (!(lo <= x && x < hi)) continue;
    for (int e = 0; e < 3; ++e) ++uses[std::minmax(t[e], t[(e + 1) % 3])];
  }
  ProbeSite best;
  double best_y = 0.0;
  for (const auto& [edge, count] : uses) {
    const auto [a, b] = edge;
    if (count != 1 || !mesh.free_surface[a] || !mesh.free_surface[b]) continue;
    if (nodes.kind[a] != mesh::NodeKind::Fluid && nodes.kind[b] != mesh::NodeKind::Fluid) continue;
    const double xa = nodes.x[a], xb = nodes.x[b];
    if (!((xa <= x && x < xb) || (xb <= x && x < xa))) continue;  // half-open: a node is crossed once
    const double y = nodes.y[a] + (x - xa) / (xb - xa) * (nodes.y[b] - nodes.y[a]);
    if (best.a < 0 || y > best_y) best.a = a, best.b = b, best_y = y;
  }
  return best;
}

double wave_gauge(const ProbeSite& site, const NodeState& nodes, double x, int k) {
  if (site.a < 0) return 0.0;
  const Dual xa = node_dual(nodes, site.a, NodeState::kDx, k), ya = node_dual(nodes, site.a, NodeState::kDy, k);
  const Dual xb = node_dual(nodes, site.b, NodeState::kDx, k), yb = node_dual(nodes, site.b, NodeState::kDy, k);
  const Dual y = ya + (Dual{x, 0.0} - xa) / (xb - xa) * (yb - ya);
  return k < 0 ? y.v : y.d;
}

namespace {
// Twice the signed areas of the triangle t and of its sub-triangles opposite each corner with
// the point (x, y); parameter k's derivatives in their dual parts.
struct Barycentric {
  Dual whole;
  std::array<Dual, 3> part;
};
Barycentric barycentric(const std::array<std::int32_t, 3>& t, const NodeState& nodes, double x, double y, int k) {
  std::array<Dual, 3> px, py;
  for (int a = 0; a < 3; ++a) px[a] = node_dual(nodes, t[a], NodeState::kDx, k), py[a] = node_dual(nodes, t[a], NodeState::kDy, k);
  const Dual X{x, 0.0}, Y{y, 0.0};
  const auto twice_area = [](Dual ax, Dual ay, Dual bx, Dual by, Dual cx, Dual cy) {
    return (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
  };
  return {twice_area(px[0], py[0], px[1], py[1], px[2], py[2]),
          {twice_area(X, Y, px[1], py[1], px[2], py[2]), twice_area(px[0], py[0], X, Y, px[2], py[2]),
           twice_area(px[0], py[0], px[1], py[1], X, Y)}};
}
}  // namespace

ProbeSite pressure_site(const mesh::FluidMesh& mesh, const NodeState& nodes, double x, double y) {
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    const Barycentric b = barycentric(mesh.triangles[e], nodes, x, y, -1);
    const double tolerance = -1e-12 * b.whole.v;
    if (b.whole.v > 0.0 && b.part[0].v >= tolerance && b.part[1].v >= tolerance && b.part[2].v >= tolerance)
      return {-1, -1, static_cast<int>(e)};
  }
  return {};
}

double pressure_at(const ProbeSite& site, const mesh::FluidMesh& mesh, const NodeState& nodes, double x, double y,
                   int k) {
  if (site.triangle < 0) return 0.0;
  const auto& t = mesh.triangles[site.triangle];
  const Barycentric b = barycentric(t, nodes, x, y, k);
  Dual p;
  for (int a = 0; a < 3; ++a) p = p + b.part[a] / b.whole * corner_pressure_dual(nodes, mesh, site.triangle, a, k);
  return k < 0 ? p.v : p.d;
}

}  // namespace pfem
