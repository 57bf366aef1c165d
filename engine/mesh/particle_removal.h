#pragma once
// Mesh-quality control between steps: a fluid particle that has come closer than a fraction
// of h to another node it shares a mesh edge with makes slivers that invert within a step, so
// it is taken out (kind -> Removed; its index stays valid, it is no longer triangulated).
#include <span>

#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// For each edge of mesh shorter than min_distance: the particle goes when the other end is a
// wall or structure node; of two particles, the one with the higher index goes. Returns the
// number removed. Deterministic for a given mesh and positions.
int remove_close_particles(const FluidMesh& mesh, std::span<const double> x,
                           std::span<const double> y, std::span<NodeKind> kind, double min_distance);

}  // namespace pfem::mesh
