#include "engine/analysis/beam_contact_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

namespace pfem {

std::vector<std::string> beam_contact_warnings(const mesh::FluidMesh& mesh, const NodeState& nodes,
                                               std::span<const std::array<std::int32_t, 2>> beam_segments,
                                               double gx, double gy, double h) {
  std::vector<std::string> warnings;
  const double g = std::hypot(gx, gy);
  if (beam_segments.empty() || g == 0.0) return warnings;
  const double lx = -gy / g, ly = gx / g;  // the level
  std::set<std::pair<std::int32_t, std::int32_t>> beam_edges;
  for (const auto& [a, b] : beam_segments) beam_edges.insert(std::minmax(a, b));
  // The free edges between a particle and a structure node: in one triangle, not a beam's.
  std::map<std::pair<std::int32_t, std::int32_t>, int> count;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  std::set<std::int32_t> warned;
  for (const auto& [edge, n] : count) {
    if (n != 1 || beam_edges.count(edge)) continue;
    auto [p, s] = edge;
    if (nodes.kind[p] == mesh::NodeKind::Structure) std::swap(p, s);
    if (nodes.kind[p] != mesh::NodeKind::Fluid || nodes.kind[s] != mesh::NodeKind::Structure || warned.count(s)) continue;
    // The point of each beam element at s that is level with the particle, if it lies on it.
    for (const auto& [a, b] : beam_segments) {
      if (a != s && b != s) continue;
      const std::int32_t o = a == s ? b : a;
      const double ux = nodes.x[o] - nodes.x[s], uy = nodes.y[o] - nodes.y[s];
      const double ul = ux * ly - uy * lx;
      if (std::abs(ul) < 1e-12 * std::hypot(ux, uy)) continue;  // a level element
      const double along = ((nodes.x[p] - nodes.x[s]) * ly - (nodes.y[p] - nodes.y[s]) * lx) / ul;  // of the element
      const double off = along * std::hypot(ux, uy);
      if (along <= 0.0 || along >= 1.0 || off <= 0.1 * h) continue;
      char msg[400];
      std::snprintf(msg, sizeof msg,
                    "the water's surface meets a beam %.2f mm from its node at (%.6g, %.6g) m at t = 0: a beam's "
                    "nodes stay where they are (a wall's slide to the water's level), so the surface ends off its "
                    "level there and water at rest next to the beam would move; give the beam a node at that level "
                    "(structure.beams[].elements)",
                    1e3 * off, nodes.x[s], nodes.y[s]);
      warnings.emplace_back(msg);
      warned.insert(s);
      break;
    }
  }
  return warnings;
}

}  // namespace pfem
