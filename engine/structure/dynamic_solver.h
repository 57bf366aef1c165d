#pragma once
// Velocity-based backward Euler for the structure alone (theory §1, §4), Newton per step:
//   u = u_n + dt v
//   r(v) = lambda(t) F - M (v - v_n)/dt - C v - Fs_int(u)
//   KT   = M/dt + C + dt dFs/du
// The model holds the displacement state (committed at every converged step); the solver
// holds the velocity and the time, and a reference to the model (which must outlive it).
#include <Eigen/Core>
#include <functional>

#include "engine/structure/free_dofs.h"
#include "engine/structure/solver_options.h"
#include "engine/structure/structure_model.h"

namespace pfem::structure {

struct DynamicOptions {
  double dt = 0.0;  // > 0
  NewtonOptions newton;
  // Load factor applied to the model's nodal loads at time t (empty: 1 at every time).
  std::function<double(double t)> load_factor;
};

class DynamicSolver {
 public:
  // Starts at t = 0 from the model's committed displacement and the velocity v0
  // (empty: at rest). Throws std::invalid_argument for dt <= 0 ("dt").
  DynamicSolver(StructureModel& model, const DynamicOptions& options,
                const Eigen::VectorXd& v0 = {});

  // One step of size dt; on failure the model is reverted and the time does not advance.
  SolveSummary step();

  double time() const { return time_; }
  const Eigen::VectorXd& velocity() const { return v_; }
  const Eigen::VectorXd& displacement() const { return model_.committed_displacement(); }

 private:
  StructureModel& model_;
  DynamicOptions options_;
  FreeDofs dofs_;
  Eigen::VectorXd v_;  // committed velocity, global numbering
  double time_ = 0.0;
  int steps_ = 0;
};

}  // namespace pfem::structure
