#include "engine/solve/step_commit.h"

#include <algorithm>

namespace pfem {

void node_pressures(const StepNumbering& num, const mesh::FluidMesh& mesh,
                    const Eigen::Ref<const Eigen::VectorXd>& values, std::size_t nodes, std::vector<double>& mean,
                    std::vector<double>& sides) {
  mean.assign(nodes, 0.0);
  sides.assign(nodes * mesh::kMaxPressureSides, NodeState::kNoSide);
  std::vector<int> wet(nodes, 0);
  for (int q = 0; q < num.pressures; ++q) {
    const auto i = static_cast<std::size_t>(num.pressure_node[q]);
    mean[i] = wet[i]++ ? mean[i] + values[q] : values[q];
    if (mesh.multi_sided(i)) sides[i * mesh::kMaxPressureSides + num.pressure_side[q]] = values[q];
  }
  for (std::size_t i = 0; i < nodes; ++i)
    if (wet[i] > 1) mean[i] /= wet[i];
}

void commit_pressure_sensitivities(const StepNumbering& num, const mesh::FluidMesh& mesh, const Eigen::MatrixXd& dp,
                                   NodeState& nodes) {
  std::vector<double> mean, sides;
  for (int k = 0; k < static_cast<int>(dp.cols()); ++k) {
    node_pressures(num, mesh, dp.col(k), nodes.size(), mean, sides);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      double* d = nodes.sensitivity(i, k);
      d[NodeState::kDp] = mean[i];
      std::copy_n(&sides[i * mesh::kMaxPressureSides], mesh::kMaxPressureSides, d + NodeState::kDpSide);
    }
  }
}

void commit_velocity_sensitivities(const StepNumbering& num, const Eigen::MatrixXd& dv,
                                   std::span<const std::uint8_t> hits_wall,
                                   std::span<const double> wall_velocity_sensitivity, double dt, NodeState& nodes) {
  const auto num_params = static_cast<std::size_t>(dv.cols());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int unknown[2] = {num.vx[i], num.vy[i]};
    const bool rider = num.is_rider(static_cast<int>(i));
    if ((unknown[0] < 0 && unknown[1] < 0 && !rider) || hits_wall[i]) continue;
    for (std::size_t k = 0; k < num_params; ++k) {
      double* d = nodes.sensitivity(i, static_cast<int>(k));
      for (int c = 0; c < 2; ++c) {
        if (rider) {
          // (1 - s) dv_a + s dv_b + ds (v_b - v_a), the ends' velocities committed
          const StepRider& r = num.riders[num.rider[i]];
          const std::vector<double>& v = c == 0 ? nodes.vx : nodes.vy;
          d[NodeState::kDvx + c] = r.ds[k] * (v[r.b] - v[r.a]) +
                                   num.velocity_in(static_cast<int>(i), c, dv.col(static_cast<Eigen::Index>(k)));
        } else {
          const double wall =
              wall_velocity_sensitivity.empty() ? 0.0 : wall_velocity_sensitivity[(i * num_params + k) * 2 + c];
          d[NodeState::kDvx + c] = unknown[c] >= 0 ? dv(unknown[c], static_cast<Eigen::Index>(k)) : wall;
        }
        d[NodeState::kDx + c] += dt * d[NodeState::kDvx + c];
      }
    }
  }
}

}  // namespace pfem
