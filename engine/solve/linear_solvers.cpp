#include "engine/solve/linear_solvers.h"

#include "engine/solve/supernodal_ldlt.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <stdexcept>

namespace pfem {

struct SymmetricSolver::Impl {
  SymmetricBackend backend;
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholmod;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  SupernodalLdlt supernodal;
};

SymmetricSolver::SymmetricSolver(SymmetricBackend backend) : impl_(std::make_unique<Impl>()) {
  impl_->backend = backend;
  impl_->cholmod.setMode(backend == SymmetricBackend::kCholmodLlt ? Eigen::CholmodSupernodalLLt
                                                                  : Eigen::CholmodLDLt);
}
SymmetricSolver::~SymmetricSolver() = default;

void SymmetricSolver::analyze(const SparseMatrix& a) {
  switch (impl_->backend) {
    case SymmetricBackend::kEigenLdlt: impl_->ldlt.analyzePattern(a); break;
    case SymmetricBackend::kSupernodalLdlt: impl_->supernodal.analyze(a); break;
    default: impl_->cholmod.analyzePattern(a);
  }
}

void SymmetricSolver::factorize(const SparseMatrix& a) {
  bool ok;
  switch (impl_->backend) {
    case SymmetricBackend::kEigenLdlt: ok = (impl_->ldlt.factorize(a), impl_->ldlt.info() == Eigen::Success); break;
    case SymmetricBackend::kSupernodalLdlt: ok = impl_->supernodal.factorize(a); break;
    default: ok = (impl_->cholmod.factorize(a), impl_->cholmod.info() == Eigen::Success);
  }
  if (!ok) throw std::runtime_error("the Newton matrix could not be factorised (zero or wrong-signed pivot)");
}

Eigen::VectorXd SymmetricSolver::solve(const Eigen::VectorXd& b) const {
  return solve(Eigen::MatrixXd(b)).col(0);
}

Eigen::MatrixXd SymmetricSolver::solve(const Eigen::MatrixXd& b) const {
  switch (impl_->backend) {
    case SymmetricBackend::kEigenLdlt: return impl_->ldlt.solve(b);
    case SymmetricBackend::kSupernodalLdlt: {
      Eigen::MatrixXd x = b;
      impl_->supernodal.solve(x);
      return x;
    }
    default: return impl_->cholmod.solve(b);
  }
}

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
