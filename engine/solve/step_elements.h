#pragma once
// The fluid's triangles in one PFEM step (engine/solve/fluid_step.h): the state at t_n they
// start from, each triangle's geometry, residual and matrices at an iterate of the unknowns
// (computed in parallel), and the residual assembled in the step's unknowns
// (engine/solve/step_numbering.h). The iterate itself (v, p) is the caller's.
#include <Eigen/Core>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/solve/step_numbering.h"
#include "engine/solve/volume_correction.h"

namespace pfem {

struct StepSettings;

// The fluid's residual assembled at an iterate.
struct StepResidual {
  Eigen::VectorXd rv, rp;  // velocity rows (bubbles included) and pressure rows
  Eigen::VectorXd mp;      // the assembled lumped pressure mass
  Eigen::VectorXd rp_abs;  // per pressure row: sum of the magnitudes of its terms
};

class StepElements {
 public:
  // The state at t_n: the nodes' positions and velocities, the pressures of the unknowns, the
  // bubble velocities per triangle, and the volume correction's dilatation. mesh, s and num must
  // outlive the step.
  void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num, const NodeState& nodes,
             Eigen::VectorXd bubbles_n);
  // Every element's geometry and residual at the iterate (v, p).
  void update(const Eigen::VectorXd& v, const Eigen::VectorXd& p);
  // Every element's matrices at the geometry of the last update (computed once per iterate).
  const std::vector<fluid::MiniMatrices>& matrices() const;
  // The residual at the iterate of the last update, assembled.
  void assemble(StepResidual& r) const;
  // Whether a triangle is inverted (or flat) at the iterate of the last update.
  bool any_inverted() const;

  fluid::ElementState state(int e, const Eigen::VectorXd& v, const Eigen::VectorXd& p) const;
  // Node i's velocity component c (0: x, 1: y) at the iterate v: its unknown's, a beam rider's
  // from its segment's ends, else a moving wall's or 0.
  double velocity(int i, int c, const Eigen::VectorXd& v) const;
  double velocity_x(int i, const Eigen::VectorXd& v) const { return velocity(i, 0, v); }
  double velocity_y(int i, const Eigen::VectorXd& v) const { return velocity(i, 1, v); }

  const std::vector<fluid::TriangleGeometry>& geometries() const { return geometries_; }
  const std::vector<fluid::DirectResidual>& residuals() const { return element_residuals_; }
  const std::vector<double>& x_n() const { return xn_; }
  const std::vector<double>& y_n() const { return yn_; }
  const Eigen::VectorXd& pressures_n() const { return pn_; }
  // The step's volume correction (its dilatation 0: none).
  const VolumeCorrection& volume() const { return volume_; }

 private:
  // The prescribed velocity of component c (0: x, 1: y) of node i (0 unless a moving wall's).
  double wall_velocity(int i, int c) const;

  const mesh::FluidMesh* mesh_ = nullptr;
  const StepSettings* s_ = nullptr;
  const StepNumbering* num_ = nullptr;
  std::vector<double> xn_, yn_, vxn_, vyn_;  // state at t_n (per node)
  Eigen::VectorXd pn_;                       // ... and the pressures there (per unknown)
  Eigen::VectorXd vbn_;                      // bubble velocities at t_n (2 rows a triangle)
  VolumeCorrection volume_;
  // At the current iterate.
  std::vector<fluid::TriangleGeometry> geometries_;
  std::vector<fluid::DirectResidual> element_residuals_;
  // Lazily at the geometry of geometries_ (matrices()).
  mutable std::vector<fluid::MiniMatrices> mats_;
  mutable bool matrices_current_ = false;
};

}  // namespace pfem
