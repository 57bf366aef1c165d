#pragma once
// Samples the recorders of a problem into one row of values.
#include <vector>

#include "engine/io/problem.h"
#include "engine/mesh/remesher.h"

namespace pfem {

// Area of the fluid mesh at the nodes' current positions [m^2].
double fluid_area(const mesh::FluidMesh& mesh, const NodeState& nodes);

// One value per recorder, in the problem's order. mesh is the mesh of the step just taken;
// structure is the run's structure at its committed state (null without one).
std::vector<double> sample_recorders(const Problem& problem, const NodeState& nodes,
                                     const mesh::FluidMesh& mesh, const structure::StructureModel* structure);

// The DDM sensitivities of every recorder with respect to every differentiated parameter
// (nodes.num_params of them), recorder-major: row[r * P + k] = d recorder_r / d theta_k. The
// structure's must have its sensitivities set for the step (set_displacement_sensitivity).
std::vector<double> sample_recorder_sensitivities(const Problem& problem, const NodeState& nodes,
                                                  const mesh::FluidMesh& mesh,
                                                  const structure::StructureModel* structure);

}  // namespace pfem
