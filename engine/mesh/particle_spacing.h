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

// Mesh edges between two particles to be split at their middle: longer than surface_length when
// an end is on the free surface, longer than interior_length when both are inside the water (an
// edge along the free surface is never split). Near the surface a shorter edge keeps thin jets
// resolved, where the alpha test would otherwise lose water; inside, an edge of 2 h and more can
// take a particle without making the water denser than h, where a shorter one would add
// particles that nothing takes out again (the count would double in a violent flow). Each node
// is the end of at most one of them, so new particles are never crowded together.
std::vector<std::array<std::int32_t, 2>> edges_to_split(const FluidMesh& mesh, std::span<const double> x,
                                                        std::span<const double> y,
                                                        std::span<const NodeKind> kind, double surface_length,
                                                        double interior_length);

}  // namespace pfem::mesh
