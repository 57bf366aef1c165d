#include "engine/solve/step_structure.h"

#include <cmath>

namespace pfem {

void StepStructure::begin(const StructureCoupling& coupling, const StepNumbering& num, double dt, double gx,
                          double gy, const NodeState& nodes, Eigen::VectorXd& v) {
  coupling_ = &coupling, num_ = &num, dt_ = dt, gx_ = gx, gy_ = gy;
  const auto& sn = coupling.node;
  un_.setZero(3 * sn.size());
  vn_.setZero(3 * sn.size());
  for (std::size_t k = 0; k < sn.size(); ++k) {
    const int i = sn[k];
    un_.segment<3>(3 * k) << nodes.x[i] - nodes.x0[i], nodes.y[i] - nodes.y0[i], nodes.rz[i];
    vn_.segment<3>(3 * k) << nodes.vx[i], nodes.vy[i], nodes.wz[i];
    if (const int d = num.structure[3 * k + 2]; d >= 0) v[d] = nodes.wz[i];
  }
}

Eigen::VectorXd StepStructure::velocities(const Eigen::VectorXd& v) const {
  Eigen::VectorXd vs = Eigen::VectorXd::Zero(num_->structure.size());
  for (std::size_t j = 0; j < num_->structure.size(); ++j)
    if (num_->structure[j] >= 0) vs[j] = v[num_->structure[j]];
  return vs;
}

Eigen::VectorXd StepStructure::acceleration(const Eigen::VectorXd& vs) const {
  Eigen::VectorXd a = (vs - vn_) / dt_;
  if (!coupling_->self_weight) return a;
  for (long j = 0; j < a.size(); j += 3) a[j] -= gx_, a[j + 1] -= gy_;
  return a;
}

double StepStructure::add_residual(const Eigen::VectorXd& v, Eigen::VectorXd& rv) {
  auto* model = coupling_->model;
  if (!model) return 0.0;
  const Eigen::VectorXd vs = velocities(v);
  model->set_trial_displacement(un_ + dt_ * vs);
  const Eigen::VectorXd load = model->external_load(), inertia = model->mass_times(acceleration(vs));
  const Eigen::VectorXd fs = model->resisting_force();
  const Eigen::VectorXd r = load - inertia - model->damping_times(vs) - fs;
  for (std::size_t j = 0; j < num_->structure.size(); ++j)
    if (num_->structure[j] >= 0) rv[num_->structure[j]] += r[j];
  return std::sqrt(load.squaredNorm() + inertia.squaredNorm() + fs.squaredNorm());
}

void StepStructure::add_tangent(const structure::AddEntry& put) const {
  const auto* model = coupling_->model;
  if (!model) return;
  const std::vector<int>& u = num_->structure;
  const structure::AddEntry add = [&](int row, int col, double value) {
    if (u[row] >= 0 && u[col] >= 0) put(u[row], u[col], value);
  };
  model->add_mass(add, 1.0 / dt_);
  model->add_damping(add, 1.0);
  model->add_tangent(add, dt_);  // at the trial state of the last residual
}

std::vector<Eigen::Triplet<double>> StepStructure::tangent_lower() const {
  std::vector<Eigen::Triplet<double>> t;
  add_tangent([&t](int row, int col, double value) {
    if (row >= col) t.emplace_back(row, col, value);
  });
  return t;
}

// The rows r = F_ext - M (v - v_n)/dt - C v - Fs(u_n + dt v) differentiated:
// -K_T du_n + M dv_n/dt - dM (v - v_n)/dt - dC v - dFs|u (loads hold no parameter).
Eigen::VectorXd StepStructure::sensitivity_rhs(const NodeState& nodes, int k, const Eigen::VectorXd& v) const {
  const auto* model = coupling_->model;
  const auto& sn = coupling_->node;
  const int n = model->num_dofs();
  Eigen::VectorXd dun(n), dvn(n);
  for (std::size_t j = 0; j < sn.size(); ++j) {
    const double* d = nodes.sensitivity(sn[j], k);
    dun.segment<3>(3 * j) << d[NodeState::kDx], d[NodeState::kDy], d[NodeState::kDrz];
    dvn.segment<3>(3 * j) << d[NodeState::kDvx], d[NodeState::kDvy], d[NodeState::kDwz];
  }
  const Eigen::VectorXd vs = velocities(v);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  model->add_tangent([&](int row, int col, double value) { r[row] -= value * dun[col]; });
  r += model->mass_times(dvn) / dt_ - model->mass_sensitivity_times(k, acceleration(vs)) -
       model->damping_sensitivity_times(k, vs) - model->resisting_force_sensitivity(k);
  return r;
}

void StepStructure::commit_sensitivities(const Eigen::MatrixXd& dv, NodeState& nodes) const {
  auto* model = coupling_->model;
  if (!model) return;
  Eigen::VectorXd du(model->num_dofs());
  for (int k = 0; k < static_cast<int>(dv.cols()); ++k) {
    for (std::size_t j = 0; j < coupling_->node.size(); ++j) {
      double* d = nodes.sensitivity(coupling_->node[j], k);
      const int rate = num_->structure[3 * j + 2];
      d[NodeState::kDwz] = rate < 0 ? 0.0 : dv(rate, k);
      d[NodeState::kDrz] += dt_ * d[NodeState::kDwz];
      du.segment<3>(3 * j) << d[NodeState::kDx], d[NodeState::kDy], d[NodeState::kDrz];
    }
    model->set_displacement_sensitivity(k, du);
  }
}

}  // namespace pfem
