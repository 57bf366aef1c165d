#include "engine/analysis/beam_contact_check.h"

#include <cmath>
#include <cstdio>
#include <set>

#include "engine/mesh/contact_line.h"

namespace pfem {

std::vector<std::string> beam_contact_warnings(const mesh::FluidMesh& mesh, const NodeState& nodes,
                                               std::span<const std::array<std::int32_t, 2>> beam_segments,
                                               double gx, double gy, double h) {
  std::vector<std::string> warnings;
  const std::array<double, 2> level = mesh::level_direction(gx, gy);
  std::set<std::int32_t> warned;
  for (const auto& [p, s] : mesh.contact_edges) {
    if (nodes.kind[s] != mesh::NodeKind::Structure || warned.count(s)) continue;
    // The point of each beam element at s that is level with the particle, if it lies on it.
    for (const auto& [a, b] : beam_segments) {
      if (a != s && b != s) continue;
      const std::int32_t o = a == s ? b : a;
      const double length = std::hypot(nodes.x[o] - nodes.x[s], nodes.y[o] - nodes.y[s]);
      const mesh::SlidingWallNode line{s, nodes.x[s], nodes.y[s], (nodes.x[o] - nodes.x[s]) / length,
                                       (nodes.y[o] - nodes.y[s]) / length};
      double off = 0.0;
      if (!line.level_offset(nodes.x[p], nodes.y[p], level, off) || off <= 0.1 * h || off >= length) continue;
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
