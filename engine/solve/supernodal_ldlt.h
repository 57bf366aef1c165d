#pragma once
// Supernodal LDL^T without pivoting, for the symmetric quasi-definite [A B; B^T -C] Newton
// matrix of the fluid (A, C positive definite: any symmetric permutation has an LDL^T).
// CHOLMOD's supernodal factorisation is LL^T only, which stops at the first negative pivot, and
// its simplicial LDL^T works a column at a time; this class does the numeric LDL^T with dense
// blocks (BLAS dgemm for the updates between supernodes, dtrsm for the off-diagonal rows of wide
// ones) on the symbolic analysis of supernodal_symbolic.h, which orders the mesh's nodes rather
// than its unknowns. Any pivot that is zero or not finite fails the factorisation.
//
// Unknowns named at analysis are ordered last (CAMD): a change of the matrix confined to them
// (the structure's tangent, between Newton iterations) then touches only the trailing supernodes,
// which update_last refactorises from the kept updates of the others at the cost of a small
// dense block.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <span>
#include <utility>
#include <vector>

#include "engine/solve/supernodal_factor.h"

namespace pfem {

class SupernodalLdlt : public SupernodalFactor {
 public:
  // analyze() (supernodal_factor.h) reads the lower triangle of a matrix.
  // Numeric factorisation of a (compressed). A pattern other than the analysed one (the
  // structure's tangent leaves out exact zeros, so it can change within a step) is analysed
  // first, with the same groups and `last`. Returns false on a zero or non-finite pivot (the
  // factor is then unusable).
  bool factorize(const SparseMatrix& a);

  // Where the entries between the unknowns of two groups go in values(): entry (row0 + i,
  // col0 + j), with row0 and col0 the first unknowns of their groups and i, j counted among the
  // group's unknowns in increasing order, lies at base + i row_step + j col_step, in the lower
  // triangle of the permuted matrix whichever group comes first (add each pair of groups once;
  // in a group's own block the entries above the diagonal land in ignored scratch).
  struct Block {
    long base;
    long row_step, col_step;
  };
  Block block(int row0, int col0) const;  // throws std::logic_error if the groups do not couple
  void zero_values();
  double* values() { return lx_.data(); }
  bool factorize_values();  // as factorize, from the values added in place
  // Factorises the last factorised matrix plus delta, whose entries (lower triangle, repeated
  // ones summed) all lie between unknowns named `last`: only the trailing supernodes are redone.
  // Returns false on a zero or non-finite pivot, or when an entry of delta has no place in the
  // factor (then factorise the whole matrix).
  bool update_last(std::span<const Eigen::Triplet<double>> delta);
  // Solves in place for each column of b (n rows).
  void solve(Eigen::Ref<Eigen::MatrixXd> b) const;

 private:
  // Subtracts from supernode s the update L_d D_d L_d^T of the factorised supernode d.
  void update(int d, int s, const UpdateRows& rows) override;
  bool factor(int s) override;
  void allocate() override;
  long entry_destination(int row, int col) const override;
  // The trailing supernodes from their kept sums (a's entries and the leading supernodes'
  // updates) plus the (position, value) additions.
  bool factorize_trailing(std::span<const std::pair<long, double>> additions);

  std::vector<double> lx_;          // supernodal L (unit diagonal implied), column-major blocks
  std::vector<double> d_;           // the diagonal D
  std::vector<double> trailing_sums_;  // lx_ from px_[first_trailing_] on before their factorisation
};

}  // namespace pfem
