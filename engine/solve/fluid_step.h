#pragma once
// One PFEM time step on a fixed mesh: the unified fractional step Newton solve of theory §4.
//
// Unknowns: a velocity at every free node in the mesh (wall nodes are fixed at v = 0), a
// bubble velocity per triangle, and a pressure at every mesh node that is not on the free
// surface (p = 0 there). The bubble stays a global unknown, as in the paper: condensing it
// inside the element would couple the pressures of each triangle and make KTpp non-diagonal,
// which the exact block elimination below needs to be diagonal (lumped Mp). The bubble is a
// hierarchical enrichment (v = sum L_a v_a + 27 L1 L2 L3 v_b), so its value at t_n is taken as
// zero: the previous step's field is carried by the nodes alone. The DDM makes the same choice.
//
// Each Newton iteration solves [KTvv KTvp; KTpv KTpp][dv; dp] = [rv; rp] by
//   dp* = KTpp^-1 rp,  (KTvv - KTvp KTpp^-1 KTpv) dv = rv - KTvp dp*,  dp = dp* - KTpp^-1 KTpv dv
// with KTvv = M/dt + K, KTvp = -G, KTpv = G^T, KTpp = Mp/dt: the condensed matrix
// M/dt + K + G (dt Mp^-1) G^T is SPD and factorised by sparse Cholesky. The tangent omits the
// geometric terms H, T (a modified Newton), so the residual is driven to a tight tolerance.
#include <atomic>
#include <stdexcept>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/linear_solvers.h"
#include "engine/solve/node_state.h"

namespace pfem {

struct StepSettings {
  double dt = 0.0;
  double tolerance = 1e-10;  // relative residual
  int max_iterations = 20;
  fluid::FluidConstants fluid;
  double thickness = 1.0;
  double gx = 0.0, gy = -9.81;
  SpdBackend backend = SpdBackend::kCholmod;
  int threads = 1;  // for the element loops
};

struct StepReport {
  int iterations = 0;
  int factorizations = 0;
  double residual = 0.0;  // final relative residual
  int velocity_unknowns = 0;
  int pressure_unknowns = 0;
  double assemble_seconds = 0.0;
  double factorize_seconds = 0.0;
  double solve_seconds = 0.0;
};

// Thrown when Newton does not converge or produces non-finite values.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// Thrown when the cancellation flag is seen.
class StepCancelled : public std::runtime_error {
 public:
  StepCancelled() : std::runtime_error("cancelled") {}
};

class UnifiedStep {
 public:
  explicit UnifiedStep(SpdBackend backend = SpdBackend::kCholmod) : solver_(backend) {}

  // nodes hold x, v, p at t_n on entry and at t_{n+1} on return. Particles outside the mesh
  // fall freely. Throws StepFailure or StepCancelled (nodes are then left unchanged).
  StepReport advance(const mesh::FluidMesh& mesh, const StepSettings& settings, NodeState& nodes,
                     const std::atomic<bool>* cancel = nullptr);

 private:
  void number_unknowns(const mesh::FluidMesh& mesh, const NodeState& nodes);
  void element_matrices(const mesh::FluidMesh& mesh, const StepSettings& s);
  // Residuals rv, rp at the current iterate; returns the force scale for the convergence test.
  void residuals(const mesh::FluidMesh& mesh, const StepSettings& s);
  void assemble_condensed(const mesh::FluidMesh& mesh, const StepSettings& s);

  // Per step.
  std::vector<int> vdof_;           // per node: first velocity unknown or -1
  std::vector<int> pdof_;           // per node: pressure unknown or -1
  int n_node_v_ = 0, n_v_ = 0, n_p_ = 0;
  std::vector<double> xn_, yn_, vxn_, vyn_, pn_;  // state at t_n (per node)
  // Per iteration.
  Eigen::VectorXd v_, p_;           // current iterate of the unknowns
  Eigen::VectorXd rv_, rp_, mp_;    // residuals and assembled lumped pressure mass
  std::vector<fluid::MiniMatrices> mats_;
  SparseMatrix condensed_, g_;
  SpdSolver solver_;
};

}  // namespace pfem
