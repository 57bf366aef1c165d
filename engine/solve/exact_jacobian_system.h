#pragma once
// The exact Jacobian of a step as its Newton matrix (engine/solve/fluid_step.h): the condensed
// Newton matrix with dt H and dt T and the mass balance's own Gc (step_jacobian.h), factorised by
// the supernodal LU on the condensed system's analysis, which must have been made in this step.
// Newton's iterates then converge quadratically where the modified Newton of the condensed
// system (which leaves those terms out) contracts slowly: water at mu = 1e-3, whose hydrostatic
// geometric terms are large.
#include "engine/solve/step_jacobian.h"
#include "engine/solve/step_linear_system.h"

namespace pfem {

class ExactJacobianSystem final : public StepLinearSystem {
 public:
  void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
             const StepStructure& structure) override;
  // At the iterate, on the condensed system's analysis (analyze is ignored).
  void factorize(const StepIterate& at, bool analyze) override;
  // Always true: the structure's block stays that of the last factorisation (the Newton loop
  // refactorises where the iterates contract slowly).
  bool refresh_structure() override { return true; }
  void solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const override;

 private:
  const mesh::FluidMesh* mesh_ = nullptr;
  const StepNumbering* num_ = nullptr;
  StepJacobian jacobian_;
};

}  // namespace pfem
