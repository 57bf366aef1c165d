#pragma once
// What area the fluid mesh should hold: the volume correction's target (StepSettings::
// target_area). The mesh holds the water that is in it; a particle in free flight (a jet or a
// splash that the alpha shape leaves out of the mesh) carries its share of the water outside the
// mesh until it comes back, and one that leaves the domain takes it away for good. The target
// is the initial area less both, so that the correction does not give the water in flight or
// gone back to the water that stays (a 0.12 m column pouring off a ledge otherwise kept its
// initial area in the domain while 65 % of its particles left). A particle's share is a third of
// each triangle it is a corner of, as of the last mesh that held it; with its DDM sensitivity.
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/state/state_archive.h"

namespace pfem {

class WaterAccount {
 public:
  // The shares of the particles in `mesh`, at the nodes' positions and sensitivities now (the
  // start of a step); particles out of the mesh keep theirs.
  void update(const mesh::FluidMesh& mesh, const NodeState& nodes);
  // Particle i leaves the domain with its share.
  void leave(int i);
  // initial - (in flight) - (left), and its sensitivity per parameter (in `sensitivity`).
  double target(double initial, const mesh::FluidMesh& mesh, const NodeState& nodes,
                std::vector<double>& sensitivity) const;
  double left() const { return left_; }
  void archive(StateArchive& a);

 private:
  int num_params_ = 0;
  std::vector<double> share_;              // per node [m^2]
  std::vector<double> share_sensitivity_;  // per node and parameter
  double left_ = 0.0;
  std::vector<double> left_sensitivity_;   // per parameter
};

}  // namespace pfem
