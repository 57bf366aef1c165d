#pragma once
// Supernodal LDL^T without pivoting, for the symmetric quasi-definite [A B; B^T -C] Newton
// matrix of the fluid (A, C positive definite: any symmetric permutation has an LDL^T).
// CHOLMOD's supernodal factorisation is LL^T only, which stops at the first negative pivot, and
// its simplicial LDL^T works a column at a time; this class takes CHOLMOD's supernodal symbolic
// analysis (fill-reducing permutation, supernodes and their row patterns) and does the numeric
// LDL^T itself with dense blocks (BLAS dgemm for the updates between supernodes, dtrsm for the
// off-diagonal rows of wide ones). Any pivot that is zero or not finite fails the factorisation.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace pfem {

class SupernodalLdlt {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  // Ordering and supernodal symbolic factorisation of the lower triangle of a (which must be
  // compressed). Throws std::runtime_error if CHOLMOD fails.
  void analyze(const SparseMatrix& a);
  // Numeric factorisation of a (compressed). A pattern other than the analysed one (the
  // structure's tangent leaves out exact zeros, so it can change within a step) is analysed
  // first. Returns false on a zero or non-finite pivot (the factor is then unusable).
  bool factorize(const SparseMatrix& a);
  // Solves in place for each column of b (n rows).
  void solve(Eigen::Ref<Eigen::MatrixXd> b) const;

 private:
  int n_ = 0;
  int nsuper_ = 0;
  std::vector<int> outer_, inner_;  // the analysed pattern
  std::vector<int> perm_;           // row k of the factor is row perm_[k] of a
  std::vector<int> super_;          // supernode s holds columns super_[s] .. super_[s+1]-1
  std::vector<int> super_of_col_;   // the supernode of each column
  std::vector<long> pi_, px_;       // starts of each supernode's row indices (in ls_) and values (in lx_)
  std::vector<int> ls_;             // row indices of each supernode, its own columns first
  std::vector<int> entry_src_;      // a's lower entries (indices into its values), grouped by supernode ...
  std::vector<long> entry_dst_;     // ... and where each goes in lx_
  std::vector<long> entry_start_;   // supernode s owns entries entry_start_[s] .. entry_start_[s+1]-1
  long max_update_ = 0;             // largest update block (rows x columns) between two supernodes
  int max_rows_ = 0, max_cols_ = 0;
  std::vector<double> lx_;          // supernodal L (unit diagonal implied), column-major blocks
  std::vector<double> d_;           // the diagonal D
};

}  // namespace pfem
