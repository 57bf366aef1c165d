#pragma once
// One PFEM time step on a fixed mesh: the Newton solve of theory §4, then the DDM of the
// converged step and the commit. Its parts: the numbering of the unknowns (step_numbering.h),
// the fluid's element terms and residual (step_elements.h), the Newton matrix of either
// formulation behind one interface (step_linear_system.h), the structure's rows and block
// (step_structure.h), the loop's tests (newton_monitor.h), the bubble history
// (bubble_history.h), the wall guard (wall_guard.h) and the DDM, which reads a view of the
// converged step (step_sensitivity.h, converged_step.h).
//
// Unknowns: a velocity at every free node in the mesh (wall nodes are fixed at v = 0), a
// bubble velocity per triangle, and a pressure at every mesh node, free-surface nodes
// included: the free surface is traction free in the weak form (its natural condition), and
// the mass balance is tested at every node, so that sum_q of the rows is the whole water's
// area change (exact with the midpoint mass balance, fluid::continuity_at_midpoint). With
// p = 0 imposed at surface nodes their rows were missing: the surface layer could lose area
// unchecked, and still water under gravity did so unstably (growing at ~5 /s at mu = 1e-3). The bubble is a hierarchical enrichment (v = sum L_a v_a +
// 27 L1 L2 L3 v_b) whose mass couples to the corners (M_a4 != 0), so its momentum must be
// carried from step to step: a triangle that survives remeshing (same three nodes) keeps its
// bubble velocity; a new triangle starts with none. Resetting it every step instead acts as a
// drag that grows as dt shrinks (-10 % on start-up Poiseuille flow at dt = 0.1 ms). The DDM
// carries the bubble's sensitivity the same way.
//
// Each Newton iteration solves [KTvv KTvp; KTpv KTpp][dv; dp] = [rv; rp] with KTvv = M/dt + K,
// KTvp = -G, KTpv = G^T, KTpp = Mp/dt exactly, by one of two block eliminations:
//  - kGlobalBubble, the paper's unified fractional step (global_bubble_system.h): bubbles stay
//    global unknowns, the pressure is eliminated with the diagonal KTpp, and the SPD condensed
//    velocity matrix is factorised by supernodal Cholesky (CHOLMOD). Bubbles couple through
//    shared pressures, so this matrix holds ~50 entries a row.
//  - kCondensedBubble (default; condensed_bubble_system.h): each bubble row involves only its
//    own triangle's unknowns, so the bubble is eliminated inside the element first (exactly,
//    with its 2x2 M/dt + K block; bubble_condensation.h), and what remains in nodal velocities
//    and pressures is factorised by LDL^T. Same solution, a third of the unknowns and a P1
//    stencil: an order of magnitude faster.
// The tangent omits the geometric terms H, T (a modified Newton); one factorisation per step
// serves all iterations unless convergence stalls, and the residual is driven to a tight
// relative tolerance because the DDM is exact only at the converged state. The structure's
// unknowns are eliminated last, so that its tangent (which jumps as fibers yield or unload) is
// refreshed at every iterate where it changed by refactorising only the trailing dense block.
#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/bubble_history.h"
#include "engine/solve/condensed_bubble_system.h"
#include "engine/solve/global_bubble_system.h"
#include "engine/solve/newton_monitor.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_elements.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_sensitivity.h"
#include "engine/solve/step_solver.h"
#include "engine/solve/step_structure.h"
#include "engine/solve/wall_guard.h"
#include "engine/structure/structure_model.h"

namespace pfem {

struct StepSettings {
  double dt = 0.0;
  double tolerance = 1e-10;  // relative residual
  int max_iterations = 50;
  // Whether an inverted, stagnating Newton iterate gives the step up (newton_monitor.h): not on
  // the last retry a step has.
  bool give_up_inverted = false;
  fluid::FluidConstants fluid;
  double thickness = 1.0;
  double gx = 0.0, gy = -9.81;
  enum class Formulation { kCondensedBubble, kGlobalBubble };
  Formulation formulation = Formulation::kCondensedBubble;
  int threads = 1;  // for the element loops
  // Wall and beam pieces (node pairs): no particle may pass through them within a step.
  std::span<const std::array<std::int32_t, 2>> walls;
  // Per node (empty: none): kSlipX or kSlipY for a node of a slip wall whose x or y velocity is
  // free (a horizontal or a vertical wall: no normal velocity). Within a step it moves along
  // its wall with the water; it returns to its place before the next remeshing (see
  // mesh/contact_line.h), keeping its velocity, or slides to a contact particle's foot and takes
  // that particle's velocity along the wall. On a moving wall (a piston) the other component is
  // the wall's (wall_velocity).
  std::span<const std::uint8_t> slip;
  // Walls with a prescribed motion (empty: none): per node, x and y (2 entries), the velocity
  // over the step of a moving wall's node, 0 elsewhere; it takes the place of v = 0 where the
  // node has no unknown. For the DDM, per node and parameter (2 entries each), its sensitivity.
  std::span<const double> wall_velocity;
  std::span<const double> wall_velocity_sensitivity;
  StructureCoupling structure;  // no structure when model is null
  // Beam riders (engine/mesh/beam_riders.h), of nodes the
  // structure does not list.
  std::vector<StepRider> riders;
  // DDM (theory §5): one seed per parameter (how it moves the fluid constants; the structure's
  // seeds live in its model); empty for no sensitivities. Without geometric terms H and T are
  // dropped, the approximation of the paper's baseline, kept only to show what it costs.
  std::span<const fluid::FluidSeed> sensitivity;
  bool geometric_terms = true;
  // Volume correction (0, 0: none): the mass balance of every element gains the uniform
  // dilatation (target_area / A_n - 1) / volume_relaxation [1/s], A_n the mesh's area at t_n, so
  // that area a remeshing made or lost is returned to the water over about volume_relaxation.
  double target_area = 0.0;        // [m^2]
  double volume_relaxation = 0.0;  // [s]
  std::span<const double> target_area_sensitivity;  // per parameter (empty: none moves it)
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
  double sensitivity_seconds = 0.0;
  int removed_particles = 0;  // that would have crossed a wall or beam
};

// Thrown when Newton does not converge or produces non-finite values.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// Runs factorize(); its runtime_error (a zero or tiny pivot) becomes a StepFailure, so that the
// step is retried shorter.
template <class Factorize>
void factorize_or_fail(Factorize&& factorize) {
  try {
    factorize();
  } catch (const std::runtime_error& e) {
    throw StepFailure(e.what());
  }
}
// Thrown when the cancellation flag is seen.
class StepCancelled : public std::runtime_error {
 public:
  StepCancelled() : std::runtime_error("cancelled") {}
};

class UnifiedStep : public StepSolver {
 public:
  UnifiedStep() = default;

  // Newton from the state at t_n to the converged step. A particle whose move would cross a
  // wall or beam is marked to be removed (kind Removed) by commit(); particles outside the
  // mesh fall freely there.
  void solve(const mesh::FluidMesh& mesh, const StepSettings& settings, const NodeState& nodes,
             const std::atomic<bool>* cancel) override;
  // The DDM of the converged step (the condensed system analysed for it if Newton did not).
  void solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) override;
  // The converged step to the nodes, the structure and the bubble history.
  void commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) override;
  // The report of the last call, also when it threw (the work of a failed attempt).
  const StepReport& last_report() const override { return report_; }
  // Saves or restores what one step hands to the next (the bubble velocities and their
  // sensitivities by triangle, the DDM's steps left on its LU) for a checkpoint; between steps
  // only.
  void archive(StateArchive& a) override;

 private:
  // The first iterate: the unknowns at t_n (bubbles by triangle), and the structure's state
  // there; the elements and the linear systems begin the step.
  void initial_iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  // The residual at the iterate: the elements' terms, assembled, and the structure's rows.
  void assemble();
  // The residual's size at the iterate, relative to what the tolerance compares it with.
  double relative_residual(const StepSettings& s) const;
  // A Newton correction of the iterate, with the matrix refactorised at the first iterate and
  // where convergence stalled (else the last factorisation, its structure block refreshed).
  void newton_correction(const StepSettings& s, bool first, bool stalled);
  // A converged state with an inverted triangle is no solution of the PFEM step: throws
  // StepFailure so that the step is retried shorter. A particle whose converged move crosses a
  // wall or beam is marked in hits_wall_ instead (its triangles may invert): it is removed. Sets
  // walls_ (engine/solve/wall_guard.h) for the particles outside the mesh.
  void check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);

  // Per step.
  StepReport report_;
  StepNumbering num_;
  StepElements elements_;
  StepStructure structure_;
  double s_force_scale_ = 0.0;  // magnitude of the structure's forces at the iterate
  std::vector<std::uint8_t> hits_wall_;  // per node: hits a wall (check_admissible)
  std::vector<WallPiece> walls_;         // the walls and beams at t_n and t_{n+1} (ditto)
  BubbleHistory bubble_history_;         // of the last converged step
  Eigen::MatrixXd dvbn_;                 // DDM: the bubbles' sensitivities at t_n (2 rows a triangle)
  // Per iteration.
  Eigen::VectorXd v_, p_;  // current iterate of the unknowns
  StepResidual residual_;
  CondensedBubbleSystem condensed_;  // also the DDM's analysis with either formulation
  GlobalBubbleSystem global_;
  StepSensitivity sensitivity_;
};

}  // namespace pfem
