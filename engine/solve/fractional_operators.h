#pragma once
// The linear solver of the incompressible fractional step (theory §8; FractionalStep), after
// Zhu & Scott, "Improved fractional step method for simulating fluid-structure interaction
// using the PFEM" (IJNME 99, 2014), as OpenSees's PFEMSolver carries it out. For a step's
// system in the unknowns of step_numbering.h,
//     [A + Kv   -G] [dv]   [rv]
//     [G^T       0] [dp] = [rp],
// A the lumped fluid mass / dt on the node velocities (diagonal), each bubble's M_44/dt + K_44
// (2 x 2) and the structure's M/dt + C + dt K_T with its nodes' lumped fluid mass, and Kv the
// viscous matrix between corner velocities:
//  1. velocity predictor dv* = (A + Kv)^-1 rv, fluid and structure in one sparse SPD system
//     (supernodal LDL^T);
//  2. pressure Poisson equation (G^T A^-1 G) dp = rp - G^T dv* (SPD, supernodal LDL^T). A^-1
//     is diagonal but on the
//     structure's unknowns, where it is exact (a dense block on their few unknowns): the
//     improved method's exact added mass, whatever the structure's tangent;
//  3. velocity correction dv = dv* + A^-1 G dp.
// Without Kv this is the exact block elimination of the system. With Kv the correction keeps A
// alone (what makes the Poisson matrix sparse), so the three steps solve the system only
// approximately: they contract its error by about K / (M/dt + K) per application (0.45 in the
// start-up Poiseuille test, mu dt / (rho h^2) = 0.16), and solve_accelerated() takes them as the
// preconditioner of GMRES on the system instead. (Without Kv in the predictor, as OpenSees's
// PFEMSolver has it with K in the residual only, the iterations diverge once mu dt / (rho h^2)
// exceeds about 1/7 on an element.)
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <span>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/linear_solvers.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_structure.h"
#include "engine/solve/supernodal_ldlt.h"

namespace pfem {

class FractionalOperators {
 public:
  // Assembles and factorises the operators at one iterate: mats and lumped (fluid::lumped_mass)
  // per triangle at its geometry, the structure's tangent at its last residual. The sparse
  // matrices' symbolic analysis is redone when `analyze` (a new mesh or numbering: their
  // patterns depend on nothing else). Throws std::runtime_error when the predictor, the
  // structure's block or the Poisson matrix cannot be factorised.
  void build(const mesh::FluidMesh& mesh, const StepNumbering& num, std::span<const fluid::MiniMatrices> mats,
             std::span<const fluid::Vec8> lumped, const StepStructure& structure, double dt, bool analyze);
  // The three steps for each column of (rv, rp): velocity rows of every unknown (bubbles
  // included), pressure rows.
  void solve(const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp, Eigen::MatrixXd& dv, Eigen::MatrixXd& dp) const;
  // The system itself solved for one right-hand side to a relative residual of `tolerance`
  // (its pressure rows scaled to the velocity rows' size) by GMRES preconditioned with the
  // three steps (a few applications of them, at most 60).
  void solve_accelerated(const Eigen::VectorXd& rv, const Eigen::VectorXd& rp, double tolerance, Eigen::VectorXd& dv,
                         Eigen::VectorXd& dp) const;

 private:
  // node_mass_ (with the structure block) and bubble_inverse_.
  void assemble_mass(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats,
                     std::span<const fluid::Vec8> lumped, const StepStructure& structure);
  // g_, z_ = A^-1 G and the Poisson matrix's factorisation.
  void assemble_poisson(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats, bool analyze);
  void assemble_predictor(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats, bool analyze);
  // The system's matrix times x = [velocities; pressures], its pressure rows times row_scale_.
  Eigen::VectorXd scaled_product(const Eigen::VectorXd& x) const;

  const StepNumbering* num_ = nullptr;
  double dt_ = 0.0;
  int first_structure_ = 0;    // the structure's unknowns are the node unknowns from here on
  Eigen::VectorXd node_mass_;  // per node unknown before first_structure_: lumped mass / dt
  std::vector<Eigen::Matrix2d> bubble_block_, bubble_inverse_;  // per triangle: M_44/dt + K_44, its inverse
  Eigen::MatrixXd structure_matrix_;                            // the structure's block of A ...
  Eigen::LDLT<Eigen::MatrixXd> structure_block_;                // ... factorised
  SparseMatrix g_, z_;                                          // G and A^-1 G (all velocity unknowns x pressures)
  SparseMatrix predictor_matrix_;                               // A + Kv on the node unknowns
  double row_scale_ = 1.0;           // mass / dt over |G| on the fluid's node rows: the pressure rows' scale
  bool predictor_analyzed_ = false;  // for the numbering of the last `analyze`
  SupernodalLdlt predictor_, poisson_;
};

}  // namespace pfem
