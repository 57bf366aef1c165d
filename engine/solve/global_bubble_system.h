#pragma once
// The paper's unified fractional step as the Newton system of a step (kGlobalBubble,
// engine/solve/fluid_step.h): bubbles stay global unknowns, the pressure is eliminated with the
// diagonal KTpp = Mp/dt,
//   dp* = KTpp^-1 rp, (KTvv + G dt Mp^-1 G^T) dv = rv + G dp*, dp = dp* - KTpp^-1 G^T dv,
// and the SPD condensed velocity matrix is factorised by supernodal Cholesky (CHOLMOD).
#include "engine/solve/linear_solvers.h"
#include "engine/solve/step_linear_system.h"

namespace pfem {

class GlobalBubbleSystem final : public StepLinearSystem {
 public:
  void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
             const StepStructure& structure) override;
  void factorize(const StepElements& elements, const Eigen::VectorXd& mp, bool analyze) override;
  // Always true: CHOLMOD's factor has no trailing block to refresh, the structure's block stays
  // that of the last factorisation until convergence stalls.
  bool refresh_structure() override { return true; }
  void solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const override;

 private:
  const mesh::FluidMesh* mesh_ = nullptr;
  const StepSettings* s_ = nullptr;
  const StepNumbering* num_ = nullptr;
  const StepStructure* structure_ = nullptr;
  SparseMatrix matrix_, g_;
  Eigen::VectorXd factor_mp_;  // Mp at the last factorisation
  SymmetricSolver solver_{SymmetricBackend::kCholmodLlt};
};

}  // namespace pfem
