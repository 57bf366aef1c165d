// The exact Jacobian of a PFEM step and the DDM of the converged step (theory §5, (38)-(46)).
//
// Differentiating the converged residual r(v, p; x = x_n + dt v, v_n, p_n, theta) = 0 gives
//   -(dr/dv + dt dr/dx) dv - dr/dp dp = dr/dx dx_n + dr/dv_n dv_n + dr/dp_n dp_n + dr/dtheta|
// (A moving wall's node has no unknown: its prescribed velocity sensitivity dv_w adds
// dr/dv_w dv_w to the right-hand side, with x = x_n + dt v there too.)
// The matrix is the exact Jacobian of the step (H and T through dr/dx, the structure's
// consistent tangent) and does not depend on the parameter: for one or two parameters GMRES
// preconditioned by the response's factorisation, for more one LU (supernodal_lu.h) on the
// analysis the Newton matrix already has and a back-substitution per parameter. The bubble is condensed per element exactly as in the
// response, and its sensitivity is carried from step to step by triangle like its velocity.
#include <algorithm>
#include <stdexcept>

#include "engine/solve/fluid_step.h"
#include "engine/solve/gmres.h"

namespace pfem {

namespace {
// The relative residual each sensitivity solve must reach (the response's Newton tolerance is
// 1e-10): at 1e-13 a directional parameter's run and the weighted sum of its parameters' runs,
// one solved by GMRES and the other by the LU, parted by 2e-11 over 0.1 s of the sloshing beam.
constexpr double kSensitivityTolerance = 1e-14;
constexpr int kGmresIterations = 15;
// Above this many parameters one LU of the Jacobian and its back-substitutions cost less than
// a GMRES solve per parameter preconditioned by the Newton factorisation (pfem-bench-ddm on the
// yielding obstacle to 0.3 s: the LU's fixed part 0.5 of the response and 6 % a parameter
// against 0.15 and 20 %).
constexpr int kGmresParameters = 2;
// After a column GMRES did not solve, the steps that take the LU at once (the wave flume's
// moving paddle: GMRES failed on most steps, and trying first cost 0.6 of a response).
constexpr int kLuSteps = 50;
}  // namespace

void UnifiedStep::solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  jacobian_elements(mesh, s, s.geometric_terms);
  const int num_params = static_cast<int>(s.sensitivity.size());
  const int ne = static_cast<int>(mesh.triangles.size());
  const double inv_dt = 1.0 / s.dt;
  Eigen::MatrixXd rv = Eigen::MatrixXd::Zero(num_.velocities, num_params);
  Eigen::MatrixXd rp = Eigen::MatrixXd::Zero(num_.pressures, num_params);
  Eigen::Matrix<double, 6, 1> dxn;
  fluid::Vec8 dvn;
  fluid::Vec3 dpn;
  // The volume correction's dilatation (target / A_n - 1) / relaxation depends on the parameter
  // through the mesh's area at t_n and through the target (the initial area less the water in
  // flight or gone, analysis/water_account.h); each corner's source dilatation * thickness *
  // A_e / 3 through it and A_e.
  // (At this point the nodes are still at t_n.)
  std::vector<double> darea_e;
  Eigen::VectorXd ddilatation = Eigen::VectorXd::Zero(num_params);
  if (dilatation_ != 0.0) {
    darea_e.assign(static_cast<std::size_t>(ne) * num_params, 0.0);
    for (int e = 0; e < ne; ++e)
      for (int k = 0; k < num_params; ++k) {
        darea_e[static_cast<std::size_t>(e) * num_params + k] = nodes.triangle_area_sensitivity(mesh.triangles[e], k);
        ddilatation(k) += darea_e[static_cast<std::size_t>(e) * num_params + k];
      }
    ddilatation *= -s.target_area / (area_n_ * area_n_ * s.volume_relaxation);
    for (int k = 0; k < num_params && !s.target_area_sensitivity.empty(); ++k)
      ddilatation(k) += s.target_area_sensitivity[k] / (area_n_ * s.volume_relaxation);
  }
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats_[e];
    const auto& tri = mesh.triangles[e];
    const fluid::ElementState st = element_state(mesh, e);
    const auto& gd = geometric_[e];
    const int bubble = num_.bubble(e);
    fluid::Mat8 a_e;
    Eigen::Matrix<double, 3, 6> q_e;
    bool have_jacobian = false;
    for (int k = 0; k < num_params; ++k) {
      for (int a = 0; a < 3; ++a) {
        const double* d = nodes.sensitivity(tri[a], k);
        dxn(2 * a) = d[NodeState::kDx], dxn(2 * a + 1) = d[NodeState::kDy];
        dvn(2 * a) = d[NodeState::kDvx], dvn(2 * a + 1) = d[NodeState::kDvy];
        dpn(a) = nodes.pressure_sensitivity(tri[a], mesh.multi_sided(tri[a]), mesh.side(e, a), k);
      }
      dvn.tail<2>() = dvbn_[e].col(k);
      fluid::Vec8 sv = gd.drv_dx * dxn + m.M * dvn * inv_dt;
      fluid::Vec3 sp = gd.drp_dx * dxn + m.Mp.cwiseProduct(dpn) * inv_dt;
      if (s.sensitivity[k].any()) {
        const fluid::ElementResidual c =
            fluid::conditional_derivative(geometries_[e], m, s.fluid, s.thickness, s.dt, st, s.sensitivity[k]);
        sv += c.rv;
        sp += c.rp;
      }
      // A moving wall's corner: its prescribed velocity sensitivity w enters as -J(:, corner) w.
      for (int c = 0; !s.wall_velocity_sensitivity.empty() && c < 6; ++c) {
        const int i = tri[c / 2];
        if ((c % 2 == 0 ? num_.vx[i] : num_.vy[i]) >= 0) continue;
        const double w = s.wall_velocity_sensitivity[(static_cast<std::size_t>(i) * num_params + k) * 2 + c % 2];
        if (w == 0.0) continue;
        if (!have_jacobian) element_jacobian(e, s, &gd, a_e, q_e), have_jacobian = true;
        sv -= a_e.col(c) * w;
        sp -= q_e.col(c) * w;
      }
      if (dilatation_ != 0.0) {
        const double da = darea_e[static_cast<std::size_t>(e) * num_params + k];
        sp.array() += s.sensitivity[k].thickness * dilatation_ * element_area_n_[e] / 3.0 +
                      s.thickness / 3.0 * (ddilatation(k) * element_area_n_[e] + dilatation_ * da);
      }
      for (int a = 0; a < 3; ++a) {
        const int i = tri[a], dx = num_.vx[i], dy = num_.vy[i];
        if (dx >= 0) rv(dx, k) += sv(2 * a);
        if (dy >= 0) rv(dy, k) += sv(2 * a + 1);
        rp(num_.corner_p[e][a], k) += sp(a);
      }
      rv(bubble, k) += sv(6), rv(bubble + 1, k) += sv(7);
    }
  }
  for (int k = 0; s.structure.model && k < num_params; ++k) {
    const Eigen::VectorXd r = structure_.sensitivity_rhs(nodes, k, v_);
    for (std::size_t j = 0; j < num_.structure.size(); ++j)
      if (num_.structure[j] >= 0) rv(num_.structure[j], k) += r[j];
  }
  // Up to kGmresParameters parameters: GMRES on the Jacobian (element by element) preconditioned
  // by the step's Newton factorisation. More, or a column GMRES does not solve in
  // kGmresIterations (then also on the next kLuSteps steps): one LU of the Jacobian for every parameter, a back-substitution each, its
  // residual against the Jacobian itself, and GMRES preconditioned by the LU on that residual
  // where it is above kSensitivityTolerance (the LU's pivots perturbed or grown): every solve is
  // exact to that tolerance either way. (The Newton factorisation is this step's only if the
  // step factorised: water at rest can converge at its first iterate.)
  const LinearOperator apply = [&](const Eigen::VectorXd& x) { return jacobian_product(mesh, s, x); };
  bool iterative = num_params <= kGmresParameters && lu_steps_left_ == 0 && analyzed_ &&
                   s.formulation == StepSettings::Formulation::kCondensedBubble;
  if (lu_steps_left_ > 0) --lu_steps_left_;
  if (iterative) {
    const LinearOperator precondition = [this](const Eigen::VectorXd& x) {
      Eigen::VectorXd y = x;
      condensed_solver_.solve(y);
      return y;
    };
    const CondensedSolve solve = [&](const Eigen::MatrixXd& b) {
      Eigen::MatrixXd x(b.rows(), b.cols());
      for (long c = 0; c < b.cols() && iterative; ++c) {
        Eigen::VectorXd xc;
        iterative = gmres(apply, precondition, b.col(c), xc, kSensitivityTolerance, kGmresIterations, kGmresIterations)
                        .converged;
        x.col(c) = xc;
      }
      return x;
    };
    solve_condensed(mesh, jacobian_bubbles_, solve, rv, rp, dv_, dp_);
    if (!iterative) lu_steps_left_ = kLuSteps;
  }
  if (!iterative) {
    if (!analyzed_) analyze_condensed(mesh, s);
    try {
      factorize_jacobian(mesh, s);
    } catch (const StepFailure& e) {
      throw StepFailure(std::string("sensitivity matrix: ") + e.what());
    }
    const LinearOperator precondition = [this](const Eigen::VectorXd& x) {
      Eigen::VectorXd y = x;
      jacobian_lu_.solve(y);
      return y;
    };
    const CondensedSolve solve = [&](const Eigen::MatrixXd& b) {
      Eigen::MatrixXd x = b;
      jacobian_lu_.solve(x);
      for (long c = 0; c < b.cols(); ++c) {
        const Eigen::VectorXd r = b.col(c) - apply(x.col(c));
        if (r.norm() <= kSensitivityTolerance * b.col(c).norm()) continue;
        Eigen::VectorXd correction;
        if (!gmres(apply, precondition, r, correction, kSensitivityTolerance * b.col(c).norm() / r.norm(),
                   kGmresIterations, kGmresIterations)
                 .converged)
          throw StepFailure("the sensitivity solve did not converge");
        x.col(c) += correction;
      }
      return x;
    };
    solve_condensed(mesh, jacobian_bubbles_, solve, rv, rp, dv_, dp_);
  }
  if (!dv_.allFinite() || !dp_.allFinite()) throw StepFailure("non-finite sensitivities");
}

void UnifiedStep::commit_pressure_sensitivities(const mesh::FluidMesh& mesh, NodeState& nodes, int num_params) const {
  // As commit_pressures: a node's the mean of its wet sides', each side's its own.
  std::vector<int> wet(nodes.size(), 0);
  for (int q = 0; q < num_.pressures; ++q) ++wet[num_.pressure_node[q]];
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < num_params; ++k) {
      double* d = nodes.sensitivity(i, k);
      d[NodeState::kDp] = 0.0;
      std::fill_n(d + NodeState::kDpSide, mesh::kMaxPressureSides, NodeState::kNoSide);
    }
  std::vector<int> seen(nodes.size(), 0);
  for (int q = 0; q < num_.pressures; ++q) {
    const int i = num_.pressure_node[q];
    const bool first = seen[i]++ == 0;
    for (int k = 0; k < num_params; ++k) {
      double* d = nodes.sensitivity(i, k);
      d[NodeState::kDp] = first ? dp_(q, k) : d[NodeState::kDp] + dp_(q, k);
      if (seen[i] == wet[i] && wet[i] > 1) d[NodeState::kDp] /= wet[i];
      if (mesh.multi_sided(i)) d[NodeState::kDpSide + num_.pressure_side[q]] = dp_(q, k);
    }
  }
}

void UnifiedStep::commit_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) {
  const int num_params = static_cast<int>(s.sensitivity.size());
  commit_pressure_sensitivities(mesh, nodes, num_params);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int dx = num_.vx[i], dy = num_.vy[i];
    for (int k = 0; k < num_params; ++k) {
      double* d = nodes.sensitivity(i, k);
      // A particle that hit a wall is taken out where it was (advance()): it keeps its state.
      if ((dx < 0 && dy < 0) || hits_wall_[i]) continue;
      const auto wall = [&](int c) {
        return s.wall_velocity_sensitivity.empty() ? 0.0 : s.wall_velocity_sensitivity[(i * num_params + k) * 2 + c];
      };
      d[NodeState::kDvx] = dx >= 0 ? dv_(dx, k) : wall(0);
      d[NodeState::kDvy] = dy >= 0 ? dv_(dy, k) : wall(1);
      d[NodeState::kDx] += s.dt * d[NodeState::kDvx];
      d[NodeState::kDy] += s.dt * d[NodeState::kDvy];
    }
  }
  auto* model = s.structure.model;
  if (!model) return;
  const auto& sn = s.structure.node;
  Eigen::VectorXd du(model->num_dofs());
  for (int k = 0; k < num_params; ++k) {
    for (std::size_t j = 0; j < sn.size(); ++j) {
      double* d = nodes.sensitivity(sn[j], k);
      const int w = num_.structure[3 * j + 2];
      d[NodeState::kDwz] = w >= 0 ? dv_(w, k) : 0.0;
      d[NodeState::kDrz] += s.dt * d[NodeState::kDwz];
      du.segment<3>(3 * j) << d[NodeState::kDx], d[NodeState::kDy], d[NodeState::kDrz];
    }
    model->set_displacement_sensitivity(k, du);
  }
}

}  // namespace pfem
