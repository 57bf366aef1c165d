#pragma once
// One PFEM time step of the incompressible formulation (analysis.formulation "incompressible",
// theory §8): the fluid is incompressible (div v = 0, no bulk modulus), its MINI triangles carry
// a lumped mass (fluid/mini_lumped.h), and each step is solved by Zhu & Scott's improved
// fractional step (fractional_operators.h: velocity predictor with the structure in the same
// system, pressure Poisson equation, velocity correction), repeated on the updated geometry
// until the residual of the step's equations
//     rv = F - M_L (v - v_n)/dt - K v + G p - Fs(u_n + dt v) = 0,   rp = -Gc^T v (+ the volume
//     correction's source) = 0
// is below analysis.newton_tolerance, as the quasi-incompressible step's Newton loop does (the
// same tests, newton_monitor.h). Everything around the step is the other formulation's: the
// numbering of the unknowns (a pressure at every mesh node, free surface included: it is
// traction free weakly; a beam rider's velocity its segment's, step_numbering.h), the
// structure's rows and tangent, the wall guard, the remeshing.
//
// Its DDM is the approximation the paper compares against (Zhu & Scott 2017, §3-§5; their
// earlier DDM of the incompressible PFEM): the sensitivity equations are solved by one pass of
// the same fractional step, whose left-hand side holds the lumped mass, the structure and (in
// the velocity predictor only) the viscous K, but not the geometric terms dt H, dt T (nor
// Gc - G): those parts of the exact Jacobian act on the previous step's velocity sensitivities
// on the right-hand side instead of this step's (fractional_sensitivity.cpp). The runs label it
// "ddm-approximate"; the quasi-incompressible DDM is exact.
#include <atomic>
#include <cstdint>
#include <vector>

#include "engine/fluid/mini_lumped.h"
#include "engine/solve/fluid_step.h"
#include "engine/solve/fractional_operators.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/step_solver.h"
#include "engine/solve/step_structure.h"
#include "engine/solve/volume_correction.h"
#include "engine/solve/wall_guard.h"

namespace pfem {

class FractionalStep final : public StepSolver {
 public:
  void solve(const mesh::FluidMesh& mesh, const StepSettings& settings, const NodeState& nodes,
             const std::atomic<bool>* cancel) override;
  // fractional_sensitivity.cpp: the approximate DDM of the converged step (timed in the report).
  void solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) override;
  void commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) override;
  const StepReport& last_report() const override { return report_; }
  void archive(StateArchive& a) override;  // a tag: the step hands nothing on (bubbles start from rest)

 private:
  // fractional_step.cpp: the step's numbering and first iterate (the state at t_n), its
  // iterations to convergence, the residual and its size, the converged step's checks.
  void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  void iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const std::atomic<bool>* cancel);
  void element_terms(const mesh::FluidMesh& mesh, const StepSettings& s);
  fluid::ElementState element_state(const mesh::FluidMesh& mesh, int e) const;
  void residuals(const mesh::FluidMesh& mesh);
  double relative_residual(const StepSettings& s) const;
  double velocity(int i, int c) const;  // node i's x (c = 0) or y velocity at the iterate
  void check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes);
  // fractional_sensitivity.cpp: the sensitivities' part of commit().
  void commit_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) const;

  StepReport report_;
  // Per step.
  StepNumbering num_;
  StepStructure structure_;
  VolumeCorrection volume_;
  std::vector<double> xn_, yn_, vxn_, vyn_;  // per node, at t_n
  Eigen::VectorXd pn_;                       // per pressure unknown, at t_n
  std::span<const double> wall_velocity_;    // StepSettings::wall_velocity
  std::vector<std::uint8_t> hits_wall_;      // per node (check_admissible)
  std::vector<WallPiece> walls_;             // the walls and beams at both ends of the step
  FractionalOperators operators_;
  // Per iterate.
  Eigen::VectorXd v_, p_, rv_, rp_;
  // Per pressure row: the sum of its terms' magnitudes, and of |Gc| over its velocities (what a
  // velocity error of 1 m/s would make of it).
  Eigen::VectorXd rp_terms_, rp_reach_;
  double force_squared_ = 0.0, structure_force_ = 0.0;  // the scale of rv
  std::vector<fluid::TriangleGeometry> geometries_;
  std::vector<fluid::MiniMatrices> mats_;
  std::vector<fluid::Vec8> lumped_;
  std::vector<fluid::ElementResidual> element_residuals_;
  // DDM: the velocity (all unknowns) and pressure sensitivities, a column per parameter.
  Eigen::MatrixXd dv_, dp_;
};

}  // namespace pfem
