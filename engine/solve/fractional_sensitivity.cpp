// The approximate DDM of the incompressible step (fractional_step.h, theory §8).
//
// Differentiating the converged residual r(v, p; x = x_n + dt v, v_n, theta) = 0 gives, as for
// the quasi-incompressible step (step_sensitivity.cpp),
//   J [dv; dp] = dr/dx dx_n + dr/dv_n dv_n + dr/dtheta|,   J = -(dr/dv + dt dr/dx, dr/dp),
// whose velocity columns hold M_L/dt + K - dt drv/dx (dt H) in the momentum rows and
// Gc^T - dt/2 drp/dx (dt T) in the mass balance's. The approximation of Zhu & Scott's DDM of the
// incompressible PFEM, which the 2017 paper shows drifting from finite differences:
//  - the geometric part of J, L = -dt drv/dx and Gc^T - G^T - dt/2 drp/dx on the corner
//    velocities, acts on the previous step's velocity sensitivities on the right-hand side;
//  - what remains is solved by one pass of the response's fractional step at the converged
//    state (fractional_operators.h): its predictor holds M_L/dt + K and the structure's
//    consistent tangent, its pressure Poisson equation and correction the lumped mass and the
//    structure alone, so K is left out of the pressure's left-hand side,
//   [dv; dp] = FSM(dr/dx dx_n + dr/dv_n dv_n + dr/dtheta| - L dv_n).
// (K taken from the previous step too, the paper's words, made the sensitivities grow without
// bound: explicit in K, a step amplifies them where K exceeds M_L/dt, as on the small triangles
// the remeshing makes; on the sloshing beam dbase_p/drho_f was 1e7 times its finite difference at
// 0.3 s, and 0.12 times with K in the predictor. With every part of J in the solve (GMRES
// preconditioned by this pass) the same right-hand sides give the finite differences within
// 1e-5: the approximation is all in L and the one pass.) A moving wall's prescribed velocity
// sensitivity is known exactly and enters through J's full columns, and so do a beam rider's terms
// (its velocity moving with its level s, the shares of its rows: step_sensitivity.cpp).
#include <chrono>
#include <limits>
#include <string>

#include "engine/solve/fractional_step.h"
#include "engine/solve/rider_shares.h"
#include "engine/solve/step_commit.h"

namespace pfem {

void FractionalStep::solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  if (s.sensitivity.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  try {
    // The response's last build had the same mesh and numbering (a state converged at its first
    // iterate, as water at rest can be, built nothing this step).
    operators_.build(mesh, num_, mats_, lumped_, structure_, s.dt, report_.factorizations == 0);
  } catch (const std::runtime_error& e) {
    throw StepFailure(std::string("sensitivity: ") + e.what());
  }
  const int num_params = static_cast<int>(s.sensitivity.size());
  const fluid::FluidConstants incompressible{s.fluid.rho, s.fluid.mu, std::numeric_limits<double>::infinity()};
  const Eigen::MatrixXd source =
      corner_source_sensitivity(volume_, mesh, nodes, s.sensitivity, s.target_area_sensitivity);
  Eigen::MatrixXd rv = Eigen::MatrixXd::Zero(num_.velocities, num_params);
  Eigen::MatrixXd rp = Eigen::MatrixXd::Zero(num_.pressures, num_params);
  for (int e = 0; e < static_cast<int>(mesh.triangles.size()); ++e) {
    const auto& tri = mesh.triangles[e];
    const auto& m = mats_[e];
    const fluid::Vec8& ml = lumped_[e];
    const fluid::ElementState st = element_state(mesh, e);
    fluid::GeometricDerivatives gd;
    if (s.geometric_terms) {
      fluid::lumped_geometric_derivatives(geometries_[e], m, ml, s.fluid.mu, s.thickness, s.dt, st, gd);
    } else {
      gd.drv_dx.setZero(), gd.drp_dx.setZero();
    }
    // J's corner columns, and their geometric part L.
    const fluid::Mat86 lag_v = -s.dt * gd.drv_dx;
    fluid::Mat86 jv = m.K.leftCols<6>() + lag_v;
    for (int c = 0; c < 6; ++c) jv(c, c) += ml(c) / s.dt;
    const fluid::Mat36 jp = m.Gc.topRows<6>().transpose() - 0.5 * s.dt * gd.drp_dx;
    const fluid::Mat36 lag_p = jp - m.G.topRows<6>().transpose();
    const auto dof = num_.element_velocities(tri, e);
    for (int k = 0; k < num_params; ++k) {
      Eigen::Matrix<double, 6, 1> dxn;
      fluid::Vec8 dvn = fluid::Vec8::Zero();  // the bubbles start from rest
      for (int a = 0; a < 3; ++a) {
        const double* d = nodes.sensitivity(tri[a], k);
        dxn(2 * a) = d[NodeState::kDx], dxn(2 * a + 1) = d[NodeState::kDy];
        dvn(2 * a) = d[NodeState::kDvx], dvn(2 * a + 1) = d[NodeState::kDvy];
      }
      fluid::Vec8 sv = gd.drv_dx * dxn + ml.cwiseProduct(dvn) / s.dt;
      fluid::Vec3 sp = gd.drp_dx * dxn;
      if (s.sensitivity[k].any()) {
        const fluid::ElementResidual c = fluid::lumped_conditional_derivative(geometries_[e], m, ml, incompressible,
                                                                              s.thickness, s.dt, st, s.sensitivity[k]);
        sv += c.rv, sp += c.rp;
      }
      for (int c = 0; c < 6; ++c) {
        const std::size_t i = tri[c / 2];
        const bool rider = num_.is_rider(static_cast<int>(i));
        if (dof[c] >= 0 || rider)  // L on the previous step's sensitivity
          sv -= lag_v.col(c) * dvn(c), sp -= lag_p.col(c) * dvn(c);
        // A moving wall's prescribed velocity sensitivity w, or a rider's velocity moving with its
        // s at fixed unknowns, w = ds (v_b - v_a), through J's full column.
        double w = 0.0;
        if (rider) {
          const StepRider& r = num_.riders[num_.rider[i]];
          w = r.ds[k] * (velocity(r.b, c % 2) - velocity(r.a, c % 2));
        } else if (dof[c] < 0 && !s.wall_velocity_sensitivity.empty()) {
          w = s.wall_velocity_sensitivity[(i * num_params + k) * 2 + c % 2];
        }
        sv -= jv.col(c) * w, sp -= jp.col(c) * w;
      }
      sp.array() += source(e, k);
      for (int r = 0; r < 6; ++r) num_.add_to_velocity(tri[r / 2], r % 2, sv(r), rv.col(k));
      rv.block<2, 1>(num_.bubble(e), k) += sv.tail<2>();
      for (int a = 0; a < 3; ++a) rp(num_.corner_p[e][a], k) += sp(a);
    }
  }
  add_rider_shares(num_, mesh, element_residuals_, rv);
  for (int k = 0; s.structure.model && k < num_params; ++k) {
    const Eigen::VectorXd r = structure_.sensitivity_rhs(nodes, k, v_);
    for (std::size_t j = 0; j < num_.structure.size(); ++j)
      if (num_.structure[j] >= 0) rv(num_.structure[j], k) += r[j];
  }
  operators_.solve(rv, rp, dv_, dp_);
  if (!dv_.allFinite() || !dp_.allFinite()) throw StepFailure("non-finite sensitivities");
  report_.sensitivity_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void FractionalStep::commit_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) const {
  commit_pressure_sensitivities(num_, mesh, dp_, nodes);
  commit_velocity_sensitivities(num_, dv_, hits_wall_, s.wall_velocity_sensitivity, s.dt, nodes);
  structure_.commit_sensitivities(dv_, nodes);
}

}  // namespace pfem
