#include "engine/solve/step_sensitivity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/solve/fluid_step.h"
#include "engine/solve/gmres.h"
#include "engine/solve/rider_shares.h"
#include "engine/solve/step_commit.h"

namespace pfem {

namespace {
// The relative residual each sensitivity solve must reach, above the round-off floor of these
// systems: on the yielding obstacle to 0.3 s (four parameters) the LU's back-solve alone leaves
// 1e-15 to 3e-13 (1e-14 to 1e-13 for most columns), and neither refinement by the LU (it
// stagnates there) nor GMRES on the Newton factorisation (2e-14 to 7e-14 after 15 iterations
// on 3 of 300 steps, then the LU for 50 steps) reaches 1e-14 cheaply: at 1e-14 the
// sensitivities cost 1.5 times as much at eight parameters. The sensitivity histories at
// 1e-10 to 1e-13 are within 8e-9 of their largest values of those at 1e-14, far inside the
// FDM's own error; GMRES and the LU agree to a few 1e-9 (DdmGradient tests).
constexpr double kSensitivityTolerance = 1e-13;
constexpr int kGmresIterations = 15;
// Above this many parameters one LU of the Jacobian and its back-substitutions cost less than
// a GMRES solve per parameter preconditioned by the Newton factorisation (pfem-bench-ddm on the
// yielding obstacle to 0.3 s: the LU's fixed part 0.51 of the response and 6.1 % a parameter
// against 0.17 and 13.2 %; measured directly, GMRES cost 0.70 of the response against 0.77 at
// three parameters and 0.85 against 0.77 at four).
constexpr int kGmresParameters = 2;
// After a column GMRES did not solve, the steps that take the LU at once (the wave flume's
// moving paddle: GMRES failed on most steps, and trying it first cost 0.7 of a response).
constexpr int kLuSteps = 50;

// x -> A^-1 x by a factorisation of A (a preconditioner for GMRES).
template <class Factorisation>
LinearOperator solve_by(const Factorisation& f) {
  return [&f](const Eigen::VectorXd& x) {
    Eigen::VectorXd y = x;
    f.solve(y);
    return y;
  };
}
}  // namespace

void StepSensitivity::right_hand_sides(const ConvergedStep& c, const NodeState& nodes, Eigen::MatrixXd& rv,
                                       Eigen::MatrixXd& rp) const {
  const mesh::FluidMesh& mesh = c.mesh;
  const StepSettings& s = c.settings;
  const StepNumbering& num = c.num;
  const auto& mats = c.elements.matrices();
  const auto& geometric = jacobian_.geometric();
  const int num_params = static_cast<int>(s.sensitivity.size());
  const int ne = static_cast<int>(mesh.triangles.size());
  const double inv_dt = 1.0 / s.dt;
  rv = Eigen::MatrixXd::Zero(num.velocities, num_params);
  rp = Eigen::MatrixXd::Zero(num.pressures, num_params);
  Eigen::Matrix<double, 6, 1> dxn;
  fluid::Vec8 dvn;
  fluid::Vec3 dpn;
  // The volume correction's corner sources depend on the parameter through the mesh's area at
  // t_n, each element's area and the target (the initial area less the water in flight or gone,
  // analysis/water_account.h). At this point the nodes are still at t_n.
  const VolumeCorrection& volume = c.elements.volume();
  const Eigen::MatrixXd dsource =
      corner_source_sensitivity(volume, mesh, nodes, s.sensitivity, s.target_area_sensitivity);
  fluid::FluidSeed moved;  // the fluid constants some parameter moves
  for (const fluid::FluidSeed& seed : s.sensitivity) {
    moved.rho += std::abs(seed.rho), moved.mu += std::abs(seed.mu);
    moved.kappa += std::abs(seed.kappa), moved.thickness += std::abs(seed.thickness);
  }
  // Each triangle's bubble sensitivities together (a column per triangle's bubble component).
  const Eigen::MatrixXd bubbles_n = c.bubbles_n.transpose();
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats[e];
    const auto& tri = mesh.triangles[e];
    const fluid::ElementState st = c.elements.state(e, c.v, c.p);
    const auto& gd = geometric[e];
    const int bubble = num.bubble(e);
    fluid::Mat8 a_e;
    Eigen::Matrix<double, 3, 6> q_e;
    bool have_jacobian = false;
    const fluid::ScaledTerms scaled =
        moved.any() ? fluid::scaled_terms(c.elements.geometries()[e], m, s.fluid, s.thickness, s.dt, st, moved)
                    : fluid::ScaledTerms{};
    const std::array<VelocityTerms, 9> rows = num.condensed_terms(tri, e);  // a rider's shared out
    std::array<bool, 3> multi_sided;
    for (int a = 0; a < 3; ++a) multi_sided[a] = mesh.multi_sided(tri[a]);
    for (int k = 0; k < num_params; ++k) {
      for (int a = 0; a < 3; ++a) {
        const double* d = nodes.sensitivity(tri[a], k);
        dxn(2 * a) = d[NodeState::kDx], dxn(2 * a + 1) = d[NodeState::kDy];
        dvn(2 * a) = d[NodeState::kDvx], dvn(2 * a + 1) = d[NodeState::kDvy];
        dpn(a) = nodes.pressure_sensitivity(tri[a], multi_sided[a], mesh.side(e, a), k);
      }
      dvn(6) = bubbles_n(k, 2 * e), dvn(7) = bubbles_n(k, 2 * e + 1);
      // Coefficient-based products: Eigen's matrix-vector kernel costs more than their arithmetic.
      fluid::Vec8 sv = gd.drv_dx.lazyProduct(dxn) + m.M.lazyProduct(dvn) * inv_dt;
      fluid::Vec3 sp = gd.drp_dx.lazyProduct(dxn) + m.Mp.cwiseProduct(dpn) * inv_dt;
      if (s.sensitivity[k].any()) {
        const fluid::ElementResidual cd = fluid::conditional_derivative(scaled, s.fluid, s.thickness, s.sensitivity[k]);
        sv += cd.rv;
        sp += cd.rp;
      }
      // A moving wall's corner: its prescribed velocity sensitivity w enters as -J(:, corner) w;
      // a rider's velocity moves with its s at fixed unknowns: w = ds (v_b - v_a).
      for (int col = 0; (!s.wall_velocity_sensitivity.empty() || !num.riders.empty()) && col < 6; ++col) {
        const int i = tri[col / 2];
        if ((col % 2 == 0 ? num.vx[i] : num.vy[i]) >= 0) continue;
        double w = 0.0;
        if (num.is_rider(i)) {
          const StepRider& r = num.riders[num.rider[i]];
          w = r.ds[k] * (c.elements.velocity(r.b, col % 2, c.v) - c.elements.velocity(r.a, col % 2, c.v));
        } else if (!s.wall_velocity_sensitivity.empty()) {
          w = s.wall_velocity_sensitivity[(static_cast<std::size_t>(i) * num_params + k) * 2 + col % 2];
        }
        if (w == 0.0) continue;
        if (!have_jacobian) element_jacobian(m, s.dt, &gd, a_e, q_e), have_jacobian = true;
        sv -= a_e.col(col) * w;
        sp -= q_e.col(col) * w;
      }
      if (volume.dilatation != 0.0) sp.array() += dsource(e, k);
      for (int r = 0; r < 6; ++r) StepNumbering::add_to_terms(rows[r], sv(r), rv.col(k));
      for (int a = 0; a < 3; ++a) rp(num.corner_p[e][a], k) += sp(a);
      rv(bubble, k) += sv(6), rv(bubble + 1, k) += sv(7);
    }
  }
  add_rider_shares(num, mesh, c.elements.residuals(), rv);
  for (int k = 0; s.structure.model && k < num_params; ++k) {
    const Eigen::VectorXd r = c.structure.sensitivity_rhs(nodes, k, c.v);
    for (std::size_t j = 0; j < num.structure.size(); ++j)
      if (num.structure[j] >= 0) rv(num.structure[j], k) += r[j];
  }
}

void StepSensitivity::solve(const ConvergedStep& c, const NodeState& nodes) {
  jacobian_.assemble(c);
  Eigen::MatrixXd rv, rp;
  right_hand_sides(c, nodes, rv, rp);
  const int num_params = static_cast<int>(c.settings.sensitivity.size());
  // Up to kGmresParameters parameters: GMRES on the Jacobian (element by element) preconditioned
  // by the step's Newton factorisation. More, or a column GMRES does not solve in
  // kGmresIterations (then also on the next kLuSteps steps): one LU of the Jacobian for every
  // parameter, a back-substitution each, its residual against the Jacobian itself, and where
  // that is above kSensitivityTolerance (the LU's pivots perturbed or grown) a refinement by the
  // LU and then GMRES preconditioned by it: every solve is exact to that tolerance either way.
  const LinearOperator apply = [&](const Eigen::VectorXd& x) { return jacobian_.product(c, x); };
  bool iterative = num_params <= kGmresParameters && lu_steps_left_ == 0 && c.newton_factorized;
  if (lu_steps_left_ > 0) --lu_steps_left_;
  if (iterative) {
    const LinearOperator precondition = solve_by(c.condensed.factor());
    const CondensedSolve solve = [&](const Eigen::MatrixXd& b) {
      Eigen::MatrixXd x(b.rows(), b.cols());
      for (long col = 0; col < b.cols() && iterative; ++col) {
        Eigen::VectorXd xc;
        iterative = gmres(apply, precondition, b.col(col), xc, kSensitivityTolerance, kGmresIterations,
                          kGmresIterations)
                        .converged;
        x.col(col) = xc;
      }
      return x;
    };
    solve_condensed(c.mesh, c.num, jacobian_.bubbles(), solve, rv, rp, dv_, dp_);
    if (!iterative) lu_steps_left_ = kLuSteps;
  }
  if (!iterative) {
    try {
      jacobian_.factorize(c);
    } catch (const StepFailure& e) {
      throw StepFailure(std::string("sensitivity matrix: ") + e.what());
    }
    const SupernodalLu& lu = jacobian_.lu();
    const LinearOperator precondition = solve_by(lu);
    const CondensedSolve solve = [&](const Eigen::MatrixXd& b) {
      Eigen::MatrixXd x = b;
      lu.solve(x);
      Eigen::MatrixXd residuals = b - jacobian_.product(c, x);
      // The columns above the tolerance refined once by the LU, together (one back-solve), and
      // GMRES for any still above it: on the two obstacles to 0.3 s at eight parameters 4 to 11 %
      // of the columns are above it after the back-solve and 0.7 to 1.0 % after the refinement
      // (each GMRES column costs back-solves of its own).
      std::vector<long> above;
      for (long col = 0; col < b.cols(); ++col)
        if (residuals.col(col).norm() > kSensitivityTolerance * b.col(col).norm()) above.push_back(col);
      if (!above.empty()) {
        Eigen::MatrixXd refined = x(Eigen::all, above), correction = residuals(Eigen::all, above);
        lu.solve(correction);
        refined += correction;
        const Eigen::MatrixXd r = b(Eigen::all, above) - jacobian_.product(c, refined);
        for (std::size_t i = 0; i < above.size(); ++i) {
          if (r.col(i).norm() >= residuals.col(above[i]).norm()) continue;  // an LU of perturbed pivots
          x.col(above[i]) = refined.col(i);
          residuals.col(above[i]) = r.col(i);
        }
      }
      for (const long col : above) {
        const Eigen::VectorXd r = residuals.col(col);
        if (r.norm() <= kSensitivityTolerance * b.col(col).norm()) continue;
        Eigen::VectorXd correction;
        if (!gmres(apply, precondition, r, correction, kSensitivityTolerance * b.col(col).norm() / r.norm(),
                   kGmresIterations, kGmresIterations)
                 .converged)
          throw StepFailure("the sensitivity solve did not converge");
        x.col(col) += correction;
      }
      return x;
    };
    solve_condensed(c.mesh, c.num, jacobian_.bubbles(), solve, rv, rp, dv_, dp_);
  }
  if (!dv_.allFinite() || !dp_.allFinite()) throw StepFailure("non-finite sensitivities");
}

void StepSensitivity::commit(const StepSettings& s, const StepNumbering& num, const mesh::FluidMesh& mesh,
                             const StepStructure& structure, std::span<const std::uint8_t> hits_wall,
                             NodeState& nodes) const {
  commit_pressure_sensitivities(num, mesh, dp_, nodes);
  commit_velocity_sensitivities(num, dv_, hits_wall, s.wall_velocity_sensitivity, s.dt, nodes);
  structure.commit_sensitivities(dv_, nodes);
}

}  // namespace pfem
