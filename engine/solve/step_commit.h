#pragma once
// What a converged step writes to the nodes, the same for both formulations' steps (UnifiedStep,
// fluid_step.h; FractionalStep, fractional_step.h): its pressures, one per pressure unknown of
// step_numbering.h, as node values (a node's is the mean of its wet sides', and a node of several
// sides, at wall and beam lines (mesh::FluidMesh::sides), keeps each side's own too), and the
// sensitivities of its pressures and velocities. The structure's nodes: StepStructure.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_numbering.h"

namespace pfem {

// values per pressure unknown to mean (per node, 0 where there is no pressure) and sides (per
// node mesh::kMaxPressureSides entries: each side's value at a multi-sided node, NaN elsewhere);
// both are sized to `nodes` here.
void node_pressures(const StepNumbering& num, const mesh::FluidMesh& mesh,
                    const Eigen::Ref<const Eigen::VectorXd>& values, std::size_t nodes, std::vector<double>& mean,
                    std::vector<double>& sides);

// The pressure sensitivities dp (per pressure unknown, a column per parameter) to every node's
// kDp and kDpSide, as node_pressures gives the pressures.
void commit_pressure_sensitivities(const StepNumbering& num, const mesh::FluidMesh& mesh, const Eigen::MatrixXd& dp,
                                   NodeState& nodes);

// The velocity sensitivities dv (per velocity unknown, a column per parameter) to the nodes that
// have velocity unknowns, a prescribed wall's its own (wall_velocity_sensitivity, per node,
// parameter and direction; empty when none moves), and their position sensitivities advanced
// by dt of them. A particle that crossed a wall (hits_wall) is taken out where it was and keeps
// its own.
void commit_velocity_sensitivities(const StepNumbering& num, const Eigen::MatrixXd& dv,
                                   std::span<const std::uint8_t> hits_wall,
                                   std::span<const double> wall_velocity_sensitivity, double dt, NodeState& nodes);

}  // namespace pfem
