#pragma once
// The DDM of a converged PFEM step (theory §5, (38)-(46)), a consumer of the step's converged
// view (converged_step.h).
//
// Differentiating the converged residual r(v, p; x = x_n + dt v, v_n, p_n, theta) = 0 gives
//   -(dr/dv + dt dr/dx) dv - dr/dp dp = dr/dx dx_n + dr/dv_n dv_n + dr/dp_n dp_n + dr/dtheta|
// (A moving wall's node has no unknown: its prescribed velocity sensitivity dv_w adds
// dr/dv_w dv_w to the right-hand side, with x = x_n + dt v there too.)
// The matrix is the exact Jacobian of the step (H and T through dr/dx, the structure's
// consistent tangent; step_jacobian.h) and does not depend on the parameter: for one or two
// parameters GMRES preconditioned by the response's factorisation, for more one LU
// (supernodal_lu.h) on the analysis the Newton matrix already has and a back-substitution per
// parameter. The bubble is condensed per element exactly as in the response, and its
// sensitivity is carried from step to step by triangle like its velocity.
#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "engine/solve/converged_step.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_jacobian.h"
#include "engine/state/state_archive.h"

namespace pfem {

class StepSensitivity {
 public:
  // The sensitivities of the unknowns, one column per parameter: the Jacobian at the converged
  // step, factorised at most once, and one right-hand side per parameter (nodes still at t_n
  // with their sensitivities). Throws StepFailure.
  void solve(const ConvergedStep& c, const NodeState& nodes);
  // The solved sensitivities to the nodes and the structure (before the structure's own
  // commit); a particle that hits a wall (hits_wall, per node) keeps its own.
  void commit(const StepSettings& s, const StepNumbering& num, const mesh::FluidMesh& mesh,
              const StepStructure& structure, std::span<const std::uint8_t> hits_wall, NodeState& nodes) const;
  // The velocity unknowns' sensitivities (bubbles included), one column per parameter.
  const Eigen::MatrixXd& velocities() const { return dv_; }
  // Saves or restores what it hands to the next step (lu_steps_left_), for a checkpoint.
  void archive(StateArchive& a) { a(lu_steps_left_); }

 private:
  // The right-hand sides in the full unknowns: velocity rows rv and pressure rows rp.
  void right_hand_sides(const ConvergedStep& c, const NodeState& nodes, Eigen::MatrixXd& rv,
                        Eigen::MatrixXd& rp) const;

  StepJacobian jacobian_;
  Eigen::MatrixXd dv_, dp_;
  // Steps left on which the LU is taken without trying GMRES first: a flow where the Newton
  // factorisation preconditions the Jacobian poorly stays so for a while (kept in a checkpoint:
  // the two paths agree only to the solve's tolerance).
  int lu_steps_left_ = 0;
};

}  // namespace pfem
