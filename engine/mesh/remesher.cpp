// remesh(): its inputs checked, then its passes in turn (remesh_passes.h).
#include "engine/mesh/remesher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/mesh/remesh_passes.h"

namespace pfem::mesh {
namespace {

void validate(std::span<const double> x, std::span<const double> y,
              std::span<const NodeKind> kind, const RemeshOptions& options) {
  if (x.size() != y.size() || x.size() != kind.size()) {
    throw std::invalid_argument("remesh: x, y and kind must have the same size (got " +
                                std::to_string(x.size()) + ", " + std::to_string(y.size()) +
                                ", " + std::to_string(kind.size()) + ")");
  }
  if (x.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument("remesh: too many nodes for 32-bit node indices");
  }
  if (!(std::isfinite(options.h) && options.h > 0.0)) {
    throw std::invalid_argument("remesh: h must be finite and > 0 (got " +
                                std::to_string(options.h) + ")");
  }
  if (!(std::isfinite(options.alpha) && options.alpha > 0.0)) {
    throw std::invalid_argument("remesh: alpha must be finite and > 0 (got " +
                                std::to_string(options.alpha) + ")");
  }
  if (!(std::isfinite(options.boundary_alpha) && options.boundary_alpha >= 0.0)) {
    throw std::invalid_argument("remesh: boundary_alpha must be finite and >= 0 (got " +
                                std::to_string(options.boundary_alpha) + ")");
  }
  if (!options.vx.empty() || !options.vy.empty()) {
    if (options.vx.size() != x.size() || options.vy.size() != x.size())
      throw std::invalid_argument("remesh: vx and vy must have one entry per node (got " +
                                  std::to_string(options.vx.size()) + " and " + std::to_string(options.vy.size()) +
                                  " for " + std::to_string(x.size()) + " nodes)");
    if (!(std::isfinite(options.dt) && options.dt > 0.0))
      throw std::invalid_argument("remesh: dt must be finite and > 0 with velocities (got " +
                                  std::to_string(options.dt) + ")");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (kind[i] != NodeKind::Removed && (!std::isfinite(x[i]) || !std::isfinite(y[i]))) {
      throw std::invalid_argument("remesh: node " + std::to_string(i) +
                                  " has a non-finite coordinate");
    }
  }
  const auto n = static_cast<std::int64_t>(x.size());
  for (std::size_t c = 0; c < options.constraints.size(); ++c) {
    const auto [a, b] = options.constraints[c];
    if (a < 0 || a >= n || b < 0 || b >= n || a == b) {
      throw std::invalid_argument("remesh: constraint " + std::to_string(c) + " (" +
                                  std::to_string(a) + ", " + std::to_string(b) +
                                  ") needs two different node indices in [0, " +
                                  std::to_string(n) + ")");
    }
  }
  for (std::size_t r = 0; r < options.riders.size(); ++r) {
    const LineRider& rider = options.riders[r];
    if (rider.node < 0 || rider.node >= n || kind[rider.node] == NodeKind::Removed)
      throw std::invalid_argument("remesh: rider " + std::to_string(r) + " has no node (" + std::to_string(rider.node) + ")");
    const auto& c = options.constraints;
    const auto ends = std::minmax(rider.a, rider.b);
    if (std::none_of(c.begin(), c.end(), [&](const auto& s) { return std::minmax(s[0], s[1]) == ends; }))
      throw std::invalid_argument("remesh: rider " + std::to_string(r) + " is on (" + std::to_string(rider.a) + ", " +
                                  std::to_string(rider.b) + "), which is not a constraint");
  }
}

// The constraints with every rider's segment split at it.
std::vector<std::array<std::int32_t, 2>> split_at_riders(const RemeshOptions& options) {
  std::vector<std::array<std::int32_t, 2>> split;
  split.reserve(options.constraints.size() + options.riders.size());
  for (const auto& c : options.constraints) {
    const auto rider = std::find_if(options.riders.begin(), options.riders.end(), [&](const LineRider& r) {
      return std::minmax(r.a, r.b) == std::minmax(c[0], c[1]);
    });
    if (rider == options.riders.end()) {
      split.push_back(c);
    } else {
      split.push_back({c[0], rider->node});
      split.push_back({rider->node, c[1]});
    }
  }
  return split;
}

}  // namespace

FluidMesh remesh(std::span<const double> x, std::span<const double> y,
                 std::span<const NodeKind> kind, const RemeshOptions& options) {
  validate(x, y, kind, options);
  Delaunay tri;
  const bool constrained = options.riders.empty() ? triangulate_nodes(x, y, kind, options.constraints, tri)
                                                   : triangulate_nodes(x, y, kind, split_at_riders(options), tri);
  // The faces that are water: those the alpha test keeps, the pockets and voids it leaves
  // closed in, less those hanging above the waterline at a wall.
  const PreviousMesh previous(x.size(), options);
  keep_alpha_faces(tri, x, y, kind, options, previous);
  keep_wall_pockets(tri, kind, options);
  keep_voids_at_beams(tri, kind, options, previous);
  drop_hanging_faces(tri, x, y, kind, options);
  FluidMesh mesh = extract_fluid_mesh(tri, kind, constrained, options.riders);
  mesh.riders.assign(options.riders.begin(), options.riders.end());
  return mesh;
}

}  // namespace pfem::mesh
