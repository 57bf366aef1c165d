#include "engine/solve/node_pressures.h"

#include <limits>

namespace pfem {

void node_pressures(const StepNumbering& num, const mesh::FluidMesh& mesh,
                    const Eigen::Ref<const Eigen::VectorXd>& values, std::size_t nodes, std::vector<double>& mean,
                    std::vector<double>& sides) {
  mean.assign(nodes, 0.0);
  sides.assign(nodes * mesh::kMaxPressureSides, std::numeric_limits<double>::quiet_NaN());
  std::vector<int> wet(nodes, 0);
  for (int q = 0; q < num.pressures; ++q) {
    const auto i = static_cast<std::size_t>(num.pressure_node[q]);
    mean[i] += values[q];
    ++wet[i];
    if (mesh.multi_sided(i)) sides[i * mesh::kMaxPressureSides + num.pressure_side[q]] = values[q];
  }
  for (std::size_t i = 0; i < nodes; ++i)
    if (wet[i] > 1) mean[i] /= wet[i];
}

}  // namespace pfem
