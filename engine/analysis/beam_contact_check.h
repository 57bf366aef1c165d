#pragma once
// Where the water's surface meets a beam between two of its nodes at the start of a run, in the
// formulation without beam riders (mesh/beam_riders.h: the incompressible one). A beam's nodes are the structure's and stay where they are, so there
// the free edge from the last surface particle ends at a beam node off the water's level, and
// still water next to the beam moves (0.11 m/s within 1 s with the level 0.6 of a 7.1 mm element
// above a node, h = 5 mm, μ = 1e-3; at rest with a node at the level). The run warns, naming the
// place, so that the beam can be given a node there.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

// One warning per beam node that ends a free edge from a surface particle (FluidMesh::
// contact_edges) whose level (square to gravity (gx, gy)) crosses the beam's element at that node
// more than h / 10 from the node.
// beam_segments: the node pairs of the beam elements.
std::vector<std::string> beam_contact_warnings(const mesh::FluidMesh& mesh, const NodeState& nodes,
                                               std::span<const std::array<std::int32_t, 2>> beam_segments,
                                               double gx, double gy, double h);

}  // namespace pfem
