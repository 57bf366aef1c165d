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
#include "engine/solve/step_commit.h"

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
  // The volume correction's corner source through A_n, A_e and the target (the initial area less
  // the water in flight or gone, analysis/water_account.h); the nodes are still at t_n.
  const Eigen::MatrixXd source =
      corner_source_sensitivity(volume_, mesh, nodes, s.sensitivity, s.target_area_sensitivity);
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
      if (volume_.dilatation != 0.0) sp.array() += source(e, k);
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

void UnifiedStep::commit_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) {
  commit_pressure_sensitivities(num_, mesh, dp_, nodes);
  commit_velocity_sensitivities(num_, dv_, hits_wall_, s.wall_velocity_sensitivity, s.dt, nodes);
  structure_.commit_sensitivities(dv_, nodes);
}

}  // namespace pfem
