#include "engine/solve/linear_solvers.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <stdexcept>

namespace pfem {

struct SpdSolver::Impl {
  SpdBackend backend;
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> cholmod;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
};

SpdSolver::SpdSolver(SpdBackend backend) : impl_(std::make_unique<Impl>()) {
  impl_->backend = backend;
  // Supernodal LL^T was no faster than simplicial below ~50k unknowns here (toolchain.md).
  impl_->cholmod.setMode(Eigen::CholmodSupernodalLLt);
}
SpdSolver::~SpdSolver() = default;

void SpdSolver::analyze(const SparseMatrix& a) {
  if (impl_->backend == SpdBackend::kCholmod) impl_->cholmod.analyzePattern(a);
  else impl_->ldlt.analyzePattern(a);
}

void SpdSolver::factorize(const SparseMatrix& a) {
  const bool ok = impl_->backend == SpdBackend::kCholmod
                      ? (impl_->cholmod.factorize(a), impl_->cholmod.info() == Eigen::Success)
                      : (impl_->ldlt.factorize(a), impl_->ldlt.info() == Eigen::Success);
  if (!ok) throw std::runtime_error("the condensed velocity matrix is not positive definite");
}

Eigen::VectorXd SpdSolver::solve(const Eigen::VectorXd& b) const {
  if (impl_->backend == SpdBackend::kCholmod) return impl_->cholmod.solve(b);
  return impl_->ldlt.solve(b);
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& b) const {
  if (impl_->backend == SpdBackend::kCholmod) return impl_->cholmod.solve(b);
  return impl_->ldlt.solve(b);
}

struct LuSolver::Impl {
  Eigen::UmfPackLU<SparseMatrix> lu;
};

LuSolver::LuSolver() : impl_(std::make_unique<Impl>()) {}
LuSolver::~LuSolver() = default;

void LuSolver::analyze(const SparseMatrix& a) { impl_->lu.analyzePattern(a); }

void LuSolver::factorize(const SparseMatrix& a) {
  impl_->lu.factorize(a);
  if (impl_->lu.info() != Eigen::Success) throw std::runtime_error("the sensitivity matrix is singular");
}

Eigen::MatrixXd LuSolver::solve(const Eigen::MatrixXd& b) const { return impl_->lu.solve(b); }

}  // namespace pfem
