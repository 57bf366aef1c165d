#pragma once
// The beam riders of a run (engine/mesh/beam_riders.h): one node for each beam segment, Removed
// while the water's surface does not meet the segment between its ends, placed before each
// remeshing with the state of the beam there.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/beam_riders.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_numbering.h"

namespace pfem {

class BeamRiderNodes {
 public:
  // Adds a rider node (Removed) for each of the beam segments (node pairs) to nodes.
  BeamRiderNodes(std::span<const std::array<std::int32_t, 2>> segments, NodeState& nodes);

  // Places the riders for the contact edges of previous at the nodes' current positions (level:
  // the unit level direction, h the particle spacing) and returns them for the remeshing; every
  // other rider is Removed. A placed rider takes its segment's state at its place, interpolated
  // between the ends, x = (1 - s) x_a + s x_b for position, velocity and pressure (its sides
  // start from that pressure), with the sensitivities of that, s's included (s follows its
  // particle's level, mesh::level_fraction_derivative).
  std::span<const mesh::LineRider> place(const mesh::FluidMesh& previous, NodeState& nodes,
                                         const std::array<double, 2>& level, double h);
  // The riders of mesh (those placed for it) for its step.
  std::vector<StepRider> step_riders(const mesh::FluidMesh& mesh) const;

 private:
  std::vector<std::array<std::int32_t, 2>> segments_;
  std::vector<std::vector<int>> segments_of_;  // per node: the segments it ends
  std::int32_t first_ = 0;                     // the rider of segment j is node first_ + j
  std::vector<mesh::LineRider> placed_;
  std::vector<double> s_;                  // per segment: its rider's place, when placed
  std::vector<std::vector<double>> ds_;    // ... and its sensitivities
};

}  // namespace pfem
