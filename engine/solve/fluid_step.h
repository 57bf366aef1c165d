#pragma once
// One PFEM time step on a fixed mesh: the Newton solve of theory §4. Its parts: the numbering
// of the unknowns (step_numbering.h), the structure's rows and block (step_structure.h), the
// loop's tests (newton_monitor.h), the bubble history (bubble_history.h), the wall guard
// (wall_guard.h) and the DDM (step_sensitivity.cpp).
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
//  - kGlobalBubble, the paper's unified fractional step: bubbles stay global unknowns, the
//    pressure is eliminated with the diagonal KTpp,
//      dp* = KTpp^-1 rp, (KTvv + G dt Mp^-1 G^T) dv = rv + G dp*, dp = dp* - KTpp^-1 G^T dv,
//    and the SPD condensed velocity matrix is factorised by supernodal Cholesky (CHOLMOD).
//    Bubbles couple through shared pressures, so this matrix holds ~50 entries a row.
//  - kCondensedBubble (default): each bubble row involves only its own triangle's unknowns, so
//    the bubble is eliminated inside the element first (exactly, with its 2x2 M/dt + K block);
//    what remains is [A -G'; -G'^T -C] in nodal velocities and pressures (pressure rows
//    negated), symmetric quasi-definite with A = condensed M/dt + K and C = Mp/dt + the
//    bubble's pressure coupling, factorised by LDL^T. Same solution, a third of the unknowns
//    and a P1 stencil: an order of magnitude faster.
// The tangent omits the geometric terms H, T (a modified Newton); one factorisation per step
// serves all iterations unless convergence stalls, and the residual is driven to a tight
// relative tolerance because the DDM is exact only at the converged state. The structure's
// unknowns are eliminated last, so that its tangent (which jumps as fibers yield or unload) is
// refreshed at every iterate where it changed by refactorising only the trailing dense block.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/bubble_history.h"
#include "engine/solve/linear_solvers.h"
#include "engine/solve/newton_monitor.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_solver.h"
#include "engine/solve/step_structure.h"
#include "engine/solve/supernodal_ldlt.h"
#include "engine/solve/supernodal_lu.h"
#include "engine/solve/volume_correction.h"
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
  // mesh/contact_line.h), keeping its velocity.
  std::span<const std::uint8_t> slip;
  // Walls with a prescribed motion (empty: none): per node, x and y (2 entries), the velocity
  // over the step of a moving wall's node, 0 elsewhere; it takes the place of v = 0 where the
  // node has no unknown. For the DDM, per node and parameter (2 entries each), its sensitivity.
  std::span<const double> wall_velocity;
  std::span<const double> wall_velocity_sensitivity;
  StructureCoupling structure;  // no structure when model is null
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
// Thrown when the cancellation flag is seen.
class StepCancelled : public std::runtime_error {
 public:
  StepCancelled() : std::runtime_error("cancelled") {}
};

class UnifiedStep : public StepSolver {
 public:
  UnifiedStep() = default;

  // nodes hold x, v, p at t_n on entry and at t_{n+1} on return. Particles outside the mesh
  // fall freely; a particle that would cross a wall or beam is removed (kind Removed). Throws
  // StepFailure or StepCancelled (nodes are then left unchanged).
  StepReport advance(const mesh::FluidMesh& mesh, const StepSettings& settings, NodeState& nodes,
                     const std::atomic<bool>* cancel = nullptr) override;
  // The report of the last call, also when it threw (the work of a failed attempt).
  const StepReport& last_report() const override { return report_; }
  // Saves or restores what one step hands to the next (the bubble velocities and their
  // sensitivities by triangle) for a checkpoint; between steps only.
  void archive(StateArchive& a) override;

 private:
  // Per element, from a condensed factorisation: the bubble block inverse and
  // its couplings to the corner velocities (bubble row a_bc, corner rows a_cb) and pressures.
  struct BubbleCondensation {
    Eigen::Matrix2d inv_bb;
    Eigen::Matrix<double, 2, 6> a_bc;
    Eigen::Matrix<double, 6, 2> a_cb;
    Eigen::Matrix<double, 2, 3> g_b;   // bubble rows of G (momentum)
    Eigen::Matrix<double, 2, 3> gc_b;  // ... of the mass balance's Gc (G in the Newton matrix)
  };

  // The first iterate: the unknowns at t_n (bubbles by triangle), and the structure's state there.
  void initial_iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  // The residual's size at the iterate, relative to what the tolerance compares it with.
  double relative_residual(const StepSettings& s) const;
  // A Newton correction of the iterate, with the matrix refactorised at the first iterate and
  // where convergence stalled (else the last factorisation, its structure block updated).
  void newton_correction(const mesh::FluidMesh& mesh, const StepSettings& s, bool first, bool stalled);
  // The converged step to the nodes, the structure and the bubble history.
  void commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes);
  // The condensed factorisation with the structure's part at the current iterate (the fluid's
  // part stays that of the last factorisation), unless that part barely changed; false when it
  // cannot be updated so.
  bool update_structure_tangent();
  // Every element's geometry and residual at the current iterate (in parallel).
  void element_terms(const mesh::FluidMesh& mesh, const StepSettings& s);
  // Every element's matrices at the geometry of the last element_terms (once per iterate).
  void element_matrices(const StepSettings& s);
  fluid::ElementState element_state(const mesh::FluidMesh& mesh, int e) const;
  // Residuals rv, rp (and the assembled Mp) at the current iterate, from element_terms.
  void residuals(const mesh::FluidMesh& mesh);
  // Assemble and factorise the Newton matrix of the chosen formulation at the current iterate.
  void factorize_global_bubble(const mesh::FluidMesh& mesh, const StepSettings& s, bool analyze);
  void factorize_condensed_bubble(const mesh::FluidMesh& mesh, const StepSettings& s, bool analyze);
  // An element's bubble-condensed matrix in its corner unknowns (velocities x0 y0 x1 y1 x2 y2,
  // then pressures 0 1 2; pressure rows negated) and its condensation; with the geometric
  // derivatives (the DDM) the exact Jacobian, dt H and dt T included, otherwise symmetric.
  using CondensedElement = Eigen::Matrix<double, 9, 9>;
  void condense_element(int e, const StepSettings& s, const fluid::GeometricDerivatives* geometric,
                        BubbleCondensation& b, CondensedElement& k) const;
  // An element's Jacobian -d(rv, rp)/d(v, p) in its velocity columns: the velocity rows a
  // (corners, then bubble) and the pressure rows q of the corner columns (see condense_element).
  void element_jacobian(int e, const StepSettings& s, const fluid::GeometricDerivatives* geometric, fluid::Mat8& a,
                        Eigen::Matrix<double, 3, 6>& q) const;
  // Node i's x or y velocity at the iterate: its unknown's, else a moving wall's or 0.
  double velocity_x(int i) const;
  double velocity_y(int i) const;
  // The prescribed velocity of component c (0: x, 1: y) of node i (0 unless a moving wall's).
  double wall_velocity(int i, int c) const;
  // The condensed matrix's symbolic analysis on the graph of the mesh nodes, and where each
  // triangle's blocks go in the factor.
  void analyze_condensed(const mesh::FluidMesh& mesh, const StepSettings& s);
  // Solves the condensed system held by `solve` for right-hand sides in the full unknowns
  // (velocity rows rv, bubbles included, and pressure rows rp; one column each), returning the
  // solutions dv (bubbles recovered) and dp.
  using CondensedSolve = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;
  void solve_condensed(const mesh::FluidMesh& mesh, const std::vector<BubbleCondensation>& bubbles,
                       const CondensedSolve& solve, const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp,
                       Eigen::MatrixXd& dv, Eigen::MatrixXd& dp) const;
  // Whether a triangle is inverted (or flat) at the current iterate.
  bool any_inverted() const;
  // A converged state with an inverted triangle is no solution of the PFEM step: throws
  // StepFailure so that the step is retried shorter. A particle whose converged move crosses a
  // wall or beam is marked in hits_wall_ instead (its triangles may invert): it is removed. Sets
  // walls_ (engine/solve/wall_guard.h) for the particles outside the mesh.
  void check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  // The exact Jacobian at the current iterate, element by element: dt H and dt T (kept in
  // geometric_; zero without geometric terms) condensed like the Newton matrix.
  void jacobian_elements(const mesh::FluidMesh& mesh, const StepSettings& s, bool geometric_terms);
  // Those blocks and the structure's consistent tangent into the LU, on the LDL^T's analysis
  // (jacobian_layout, once a step), factorised.
  void jacobian_layout(const mesh::FluidMesh& mesh);
  void factorize_jacobian(const mesh::FluidMesh& mesh, const StepSettings& s);
  // The Jacobian's product with x (condensed unknowns), from jacobian_elements.
  Eigen::VectorXd jacobian_product(const mesh::FluidMesh& mesh, const StepSettings& s, const Eigen::VectorXd& x) const;
  // The DDM of the converged step: the Jacobian there, factorised once, and one right-hand side
  // per parameter; then the sensitivities committed to the nodes, the bubbles and the structure
  // (before the structure's own commit).
  void solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  void commit_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes);
  // Newton corrections from the current residuals with the last factorisation.
  void correct_global_bubble(const StepSettings& s);
  void correct_condensed_bubble(const mesh::FluidMesh& mesh);

  // Per step.
  StepReport report_;
  StepNumbering num_;
  StepStructure structure_;
  double s_force_scale_ = 0.0;  // magnitude of the structure's forces at the iterate
  std::vector<double> xn_, yn_, vxn_, vyn_;  // state at t_n (per node)
  Eigen::VectorXd pn_;                       // ... and the pressures there (per unknown)
  std::vector<std::uint8_t> hits_wall_;           // per node: hits a wall (check_admissible)
  std::vector<WallPiece> walls_;                  // the walls and beams at t_n and t_{n+1} (ditto)
  std::span<const double> wall_velocity_;         // StepSettings::wall_velocity of this step
  VolumeCorrection volume_;  // the dilatation [1/s], the mesh's area at t_n and each element's there
  std::vector<Eigen::Vector2d> vbn_;                // bubble velocities at t_n (per element)
  BubbleHistory bubble_history_;  // of the last converged step
  // Per iteration.
  Eigen::VectorXd v_, p_;           // current iterate of the unknowns
  Eigen::VectorXd rv_, rp_, mp_;    // residuals and assembled lumped pressure mass
  Eigen::VectorXd rp_abs_;          // per pressure row: sum of the magnitudes of its terms
  std::vector<fluid::MiniMatrices> mats_;
  std::vector<fluid::TriangleGeometry> geometries_;  // per element, at the current iterate
  std::vector<fluid::DirectResidual> element_residuals_;
  bool matrices_current_ = false;  // mats_ at the geometry of geometries_
  std::vector<BubbleCondensation> bubbles_;  // of the last factorisation (kCondensedBubble)
  SparseMatrix matrix_, g_;
  Eigen::VectorXd factor_mp_;  // Mp at the last factorisation
  SymmetricSolver global_solver_{SymmetricBackend::kCholmodLlt};
  SupernodalLdlt condensed_solver_;
  std::vector<int> first_of_node_;  // per node: its first condensed unknown (-1: none)
  std::vector<int> slot_;  // per condensed unknown: its rank among its node's unknowns
  std::vector<std::array<SupernodalLdlt::Block, 6>> element_blocks_;  // per triangle and corner pair
  std::vector<long> pressure_diagonal_;  // per pressure unknown: its diagonal in the factor
  std::vector<Eigen::Triplet<double>> factor_structure_;  // the structure's entries last factorised
  std::vector<Eigen::Triplet<double>> structure_in_factor_;  // ... and those the factor holds now
  // DDM: bubble sensitivities (2 x P) at t_n per element; the solved sensitivities of the
  // unknowns (one column per parameter).
  std::vector<BubbleHistory::Sensitivity> dvbn_;
  Eigen::MatrixXd dv_, dp_;
  // The exact Jacobian's pieces: per element its geometric derivatives, condensation and
  // condensed block; the LU and where each triangle's blocks go in it.
  std::vector<fluid::GeometricDerivatives> geometric_;
  std::vector<BubbleCondensation> jacobian_bubbles_;
  std::vector<CondensedElement> jacobian_elements_;
  SupernodalLu jacobian_lu_;
  std::vector<std::array<SupernodalLu::Block, 9>> lu_blocks_;
  bool analyzed_ = false;  // this step's mesh analysed (analyze_condensed)
  bool lu_layout_ready_ = false;
  // Steps left on which the DDM takes the LU without trying GMRES first: a flow where the
  // Newton factorisation preconditions the Jacobian poorly stays so for a while (kept in a
  // checkpoint: the two paths agree only to the solve's tolerance).
  int lu_steps_left_ = 0;
};

}  // namespace pfem
