#pragma once
// The velocity a slip wall's node takes home. Within a step a slip wall node moves along its wall
// with the water; before the next remeshing it goes back to its place (slide_walls, simulation.cpp).
// The velocity it carries is the water's where it is, not at its place: kept as it is, every step
// moved the wall's velocities against the flow by dt v (the convection along the wall left out),
// and a slip paddle's waves at kh = 1.8 came out 1.3 % lower (0.924 of Biesel's against 0.937).
// So each wet slip node takes, at its place, the wall's velocity there: linear along the wall
// between itself and its wet neighbour on that side, as they are after the step (their free
// components), and the sensitivities of that value. A node whose neighbour on that side is dry
// or absent keeps its velocity.
#include <array>
#include <cstdint>
#include <span>

#include "engine/mesh/contact_line.h"
#include "engine/solve/node_state.h"

namespace pfem {

// sliding: the sliding wall nodes with their places and tangents at this time; dwall: per sliding
// node and parameter, d(home_x, home_y, tx, ty); slip: per node, kSlipX or kSlipY for a slip
// wall's node (0 otherwise); wet: per node, whether it was in the last mesh (shorter: the rest dry).
// The nodes' positions are those after the step (not yet sent home).
void remap_slip_velocities(std::span<const mesh::SlidingWallNode> sliding, std::span<const std::array<double, 4>> dwall,
                           std::span<const std::uint8_t> slip, std::span<const std::uint8_t> wet, NodeState& nodes);

}  // namespace pfem
