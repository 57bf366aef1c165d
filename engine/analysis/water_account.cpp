#include "engine/analysis/water_account.h"

namespace pfem {

void WaterAccount::update(const mesh::FluidMesh& mesh, const NodeState& nodes) {
  const int P = num_params_ = nodes.num_params;
  share_.resize(nodes.size(), 0.0);
  share_sensitivity_.resize(nodes.size() * P, 0.0);
  left_sensitivity_.resize(P, 0.0);
  for (std::size_t i = 0; i < nodes.size() && i < mesh.in_mesh.size(); ++i) {
    if (!mesh.in_mesh[i]) continue;
    share_[i] = 0.0;
    for (int k = 0; k < P; ++k) share_sensitivity_[i * P + k] = 0.0;
  }
  for (const auto& t : mesh.triangles) {
    const double third = nodes.triangle_area(t) / 3.0;
    for (const int i : t) share_[i] += third;
    for (int k = 0; k < P; ++k) {
      const double d = nodes.triangle_area_sensitivity(t, k) / 3.0;
      for (const int i : t) share_sensitivity_[static_cast<std::size_t>(i) * P + k] += d;
    }
  }
}

void WaterAccount::leave(int i) {
  if (static_cast<std::size_t>(i) >= share_.size()) return;  // born after the last update: holds none
  left_ += share_[i];
  for (int k = 0; k < num_params_; ++k) left_sensitivity_[k] += share_sensitivity_[static_cast<std::size_t>(i) * num_params_ + k];
}

double WaterAccount::target(double initial, const mesh::FluidMesh& mesh, const NodeState& nodes,
                            std::vector<double>& sensitivity) const {
  double target = initial - left_;
  sensitivity.assign(num_params_, 0.0);
  for (int k = 0; k < num_params_; ++k) sensitivity[k] = -left_sensitivity_[k];
  for (std::size_t i = 0; i < share_.size() && i < mesh.in_mesh.size(); ++i) {
    if (nodes.kind[i] != mesh::NodeKind::Fluid || mesh.in_mesh[i]) continue;
    target -= share_[i];
    for (int k = 0; k < num_params_; ++k) sensitivity[k] -= share_sensitivity_[i * num_params_ + k];
  }
  return target;
}

void WaterAccount::archive(StateArchive& a) {
  a(num_params_), a(share_), a(share_sensitivity_), a(left_), a(left_sensitivity_);
}

}  // namespace pfem
