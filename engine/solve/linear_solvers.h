#pragma once
// SuiteSparse's factorisations behind one small interface: CHOLMOD for the SPD matrix of the
// paper's global-bubble formulation, and CHOLMOD and UMFPACK as the references the own
// supernodal factorisations (supernodal_ldlt.h for the Newton matrix, supernodal_lu.h for the
// sensitivity matrix) are tested against. Symbolic analysis once per step (connectivity is
// fixed within a step), numeric factorisation when the values change.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace pfem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// kCholmodLlt: supernodal Cholesky, positive definite matrices only.
// kCholmodLdlt: simplicial LDL^T without pivoting, which also factorises the symmetric
// quasi-definite [A B; B^T -C] systems (A, C positive definite) of the fluid.
enum class SymmetricBackend { kCholmodLlt, kCholmodLdlt };

// Factorises symmetric matrices (the lower triangle is read).
class SymmetricSolver {
 public:
  explicit SymmetricSolver(SymmetricBackend backend = SymmetricBackend::kCholmodLdlt);
  ~SymmetricSolver();
  SymmetricSolver(const SymmetricSolver&) = delete;
  SymmetricSolver& operator=(const SymmetricSolver&) = delete;

  void analyze(const SparseMatrix& a);    // fill-reducing ordering and symbolic factorisation
  void factorize(const SparseMatrix& a);  // same pattern as analyze(); throws std::runtime_error
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Factorises general square matrices with UMFPACK (the reference for SupernodalLu).
class LuSolver {
 public:
  LuSolver();
  ~LuSolver();
  LuSolver(const LuSolver&) = delete;
  LuSolver& operator=(const LuSolver&) = delete;

  void analyze(const SparseMatrix& a);
  void factorize(const SparseMatrix& a);  // throws std::runtime_error when singular
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pfem
