#pragma once
// A step's pressures (or one parameter's pressure sensitivities), one per pressure unknown of
// step_numbering.h, on the nodes: a node's is the mean of its wet sides', and a node of several
// sides (wall and beam lines, mesh::FluidMesh::sides) keeps each side's own too.
#include <Eigen/Core>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/step_numbering.h"

namespace pfem {

// mean: per node (0 where no pressure); sides: per node mesh::kMaxPressureSides entries, each
// side's value at a multi-sided node and NaN elsewhere. Both are sized to `nodes` here.
void node_pressures(const StepNumbering& num, const mesh::FluidMesh& mesh,
                    const Eigen::Ref<const Eigen::VectorXd>& values, std::size_t nodes, std::vector<double>& mean,
                    std::vector<double>& sides);

}  // namespace pfem
