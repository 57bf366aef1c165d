#include "engine/solve/exact_jacobian_system.h"

namespace pfem {

void ExactJacobianSystem::begin(const mesh::FluidMesh& mesh, const StepSettings&, const StepNumbering& num,
                                const StepStructure&) {
  mesh_ = &mesh, num_ = &num;
}

void ExactJacobianSystem::factorize(const StepIterate& at, bool) {
  jacobian_.assemble(at);
  jacobian_.factorize(at);
}

void ExactJacobianSystem::solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const {
  const SupernodalLu& lu = jacobian_.lu();
  const auto solve = [&lu](const Eigen::MatrixXd& b) {
    Eigen::MatrixXd x = b;
    lu.solve(x);
    return x;
  };
  Eigen::MatrixXd dvs, dps;
  solve_condensed(*mesh_, *num_, jacobian_.bubbles(), solve, r.rv, r.rp, dvs, dps);
  dv = dvs.col(0);
  dp = dps.col(0);
}

}  // namespace pfem
