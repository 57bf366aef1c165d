#pragma once
// Particle spacing control between steps (the Lagrangian flow squeezes particles together in
// one direction and pulls them apart in another). A fluid particle that has come closer than
// a fraction of h to another node makes slivers that invert within a step, so it is taken out
// (kind -> Removed; its index stays valid, it is no longer triangulated); an edge that has
// grown much longer than h gets a new particle at its middle, or the alpha test would open
// holes in the water.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// For each edge of mesh shorter than min_distance: the particle goes when the other end is a
// wall or structure node; of two particles, the one with the higher index goes. A particle
// closer than min_distance to the wall/structure edge of its triangle goes too. Returns the
// number removed. Deterministic for a given mesh and positions.
int remove_close_particles(const FluidMesh& mesh, std::span<const double> x,
                           std::span<const double> y, std::span<NodeKind> kind, double min_distance);

// An edge to be split at its middle: a is a particle; b a particle or a wall or structure node,
// on side side_b of its lines (FluidMesh::corner_side; 0 for a particle). on_surface: an edge
// of the free surface (in one triangle only, both ends particles), so its middle is on it too.
struct SplitEdge {
  std::int32_t a = 0, b = 0;
  int side_b = 0;
  bool on_surface = false;
};

// The wall and beam lines (constraint segments, RemeshOptions::constraints) and the least
// distance from them at which a new particle may be put on an edge from a particle to one of
// their nodes.
struct WallClearance {
  std::span<const std::array<std::int32_t, 2>> segments{};
  double distance = 0.0;
};

// Mesh edges to be split at their middle: longer than surface_length when one end is on the free
// surface, longer than interior_length when both are inside the water or both on the surface.
// Near the surface a shorter edge keeps thin jets resolved, where the alpha test would otherwise
// lose water. An edge of the surface itself left whole stretched a crest running up a plate into
// a triangle the alpha test dropped (a 0.5 N step in the force on a plate at h = 10 mm, and a
// peak deflection that jumped by 0.2 mm between neighbouring parameter values); its new particle
// is on the surface (SplitEdge::on_surface), and the next remeshing's gap rules count it so (see
// RemeshOptions::previous_boundary). Inside, an edge of 2 h and more can take a particle
// without making the water denser than h, where a shorter one would add particles that nothing
// takes out again (the count would double in a violent flow). Each node is the end of at most
// one of them, so new particles are never crowded together.
// An edge from a particle to a wall or structure node is split only inside the water and when
// its middle lies at least walls.distance from every segment of walls at that node (one running
// along the wall would put the particle on it). Without them the water next to a wall thinned
// out where particles were taken out (at a paddle's foot), until the alpha test opened a void
// there whose zero pressure sucked at the paddle (a 236 N spike in its 50 N force). At the
// surface they stay whole: a particle between the front's last particle and a floor node ahead
// of it would move the front on (the dam break's front ran 10.6 % ahead of Martin & Moyce).
std::vector<SplitEdge> edges_to_split(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                                      std::span<const NodeKind> kind, double surface_length, double interior_length,
                                      const WallClearance& walls);

}  // namespace pfem::mesh
