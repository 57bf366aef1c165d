#include "engine/solve/linear_solvers.h"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <stdexcept>

namespace pfem {

struct SymmetricSolver::Impl {
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholmod;
};

SymmetricSolver::SymmetricSolver(SymmetricBackend backend) : impl_(std::make_unique<Impl>()) {
  impl_->cholmod.setMode(backend == SymmetricBackend::kCholmodLlt ? Eigen::CholmodSupernodalLLt
                                                                  : Eigen::CholmodLDLt);
}
SymmetricSolver::~SymmetricSolver() = default;

void SymmetricSolver::analyze(const SparseMatrix& a) { impl_->cholmod.analyzePattern(a); }

void SymmetricSolver::factorize(const SparseMatrix& a) {
  impl_->cholmod.factorize(a);
  if (impl_->cholmod.info() != Eigen::Success) throw std::runtime_error("the Newton matrix could not be factorised (zero or wrong-signed pivot)");
}

Eigen::VectorXd SymmetricSolver::solve(const Eigen::VectorXd& b) const {
  return solve(Eigen::MatrixXd(b)).col(0);
}

Eigen::MatrixXd SymmetricSolver::solve(const Eigen::MatrixXd& b) const { return impl_->cholmod.solve(b); }

struct LuSolver::Impl {
  Eigen::UmfPackLU<SparseMatrix> lu;
};

LuSolver::LuSolver() : impl_(std::make_unique<Impl>()) {
  // The fluid's matrices have a symmetric pattern and a strong diagonal: UMFPACK's symmetric
  // strategy (AMD on A + A^T, diagonal pivots preferred). No iterative refinement in solve():
  // it doubled the back-solve time and changed the DDM's sensitivities by 2e-12 relative.
  impl_->lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  impl_->lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
}
LuSolver::~LuSolver() = default;

void LuSolver::analyze(const SparseMatrix& a) { impl_->lu.analyzePattern(a); }

void LuSolver::factorize(const SparseMatrix& a) {
  impl_->lu.factorize(a);
  if (impl_->lu.info() != Eigen::Success) throw std::runtime_error("the sensitivity matrix is singular");
}

Eigen::MatrixXd LuSolver::solve(const Eigen::MatrixXd& b) const { return impl_->lu.solve(b); }

}  // namespace pfem
