#pragma once
// The resultant of the fluid's traction on a wall or a beam (recorders force_x, force_y, moment)
// and its DDM sensitivity: the traction t = (p I - s) n, with n the water's outward normal and
// s = 2 mu (eps - tr(eps)/3 I) the viscous stress of the engine's fluid (P1 velocity gradient of
// the triangle), integrated exactly along every edge of the mesh that lies on one of the wall's
// pieces or the beam's elements, from each side that has water (a submerged beam gets both).
// Times the model's thickness: forces in N, moments in N m.
#include <array>
#include <cstdint>
#include <span>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

struct BoundaryLoad {
  double fx = 0.0, fy = 0.0;  // force on the boundary [N]
  double moment = 0.0;        // about the point (ax, ay), counter-clockwise positive [N m]
};

// segments: the node pairs of the boundary's pieces (either order). seed: how parameter k moves
// the fluid constants and the thickness; k < 0 (and seed null): the load itself, k >= 0: its
// sensitivity to parameter k, from the nodes' sensitivities.
BoundaryLoad boundary_load(std::span<const std::array<std::int32_t, 2>> segments, const mesh::FluidMesh& mesh,
                           const NodeState& nodes, const fluid::FluidConstants& fluid, double thickness, double ax,
                           double ay, const fluid::FluidSeed* seed = nullptr, int k = -1);

}  // namespace pfem
