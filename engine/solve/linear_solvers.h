#pragma once
// The sparse factorisations behind one small interface, so backends can be measured side by
// side (toolchain.md): CHOLMOD or Eigen's SimplicialLDLT for the SPD condensed response matrix,
// UMFPACK for the non-symmetric sensitivity matrix. Symbolic analysis once per step
// (connectivity is fixed within a step), numeric factorisation when the values change.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace pfem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// kCholmodLlt: supernodal Cholesky, positive definite matrices only.
// kCholmodLdlt, kEigenLdlt: simplicial LDL^T without pivoting, which also factorises the
// symmetric quasi-definite [A B; B^T -C] systems (A, C positive definite) of the fluid.
// kSupernodalLdlt: the same LDL^T with dense supernodal blocks (supernodal_ldlt.h).
enum class SymmetricBackend { kCholmodLlt, kCholmodLdlt, kEigenLdlt, kSupernodalLdlt };

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

// Factorises general square matrices with UMFPACK.
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
