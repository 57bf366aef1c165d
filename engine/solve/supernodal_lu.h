#pragma once
// Supernodal LU of a matrix with a structurally symmetric pattern (the exact Jacobian of a PFEM
// step, whose pattern is that of the symmetric Newton matrix), on the same symbolic analysis as
// the LDL^T (supernodal_symbolic.h): P A = L U with L's supernodal blocks stored as the LDL^T's
// and U's off-diagonal rows stored transposed in a second array of the same layout, so that
// an update between supernodes is two dense products of the LDL^T's shape.
//
// Pivoting (as PARDISO does for nonsymmetric matrices): rows are exchanged only inside a
// supernode's diagonal block (partial pivoting there), which keeps the symbolic structure; a
// pivot that is still below kPivotTolerance times its column's diagonal entry in the matrix (the
// largest diagonal entry where that is 0) is replaced by that bound with its sign and counted
// (perturbed_pivots()): the factor is then that of a
// nearby matrix, good as a Newton matrix or a preconditioner, and solves that must be exact
// refine against the matrix itself (GMRES, gmres.h). The matrices of a step are
// quasi-definite up to the geometric terms (dt times the velocity gradient), so perturbations
// are rare.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <span>
#include <vector>

#include "engine/solve/supernodal_factor.h"

namespace pfem {

class SupernodalLu : public SupernodalFactor {
 public:
  static constexpr double kPivotTolerance = 1e-13;

  // analyze() (supernodal_factor.h) symmetrises a matrix's pattern.
  // The analysis another factorisation made (the same matrix pattern; entries added in place).
  void analyze_as(const SupernodalFactor& other);
  // Numeric factorisation of a (compressed); another pattern than the analysed one is analysed
  // first. False on a non-finite pivot (the factor is then unusable).
  bool factorize(const SparseMatrix& a);

  // Where the entries between the unknowns of two groups go: entry (row0 + i, col0 + j) at
  // values(upper)[base + i row_step + j col_step], with row0, col0, i, j as for
  // SupernodalLdlt::block. Unlike the LDL^T every pair of groups is added in both orders.
  struct Block {
    long base;
    long row_step, col_step;
    bool upper;
  };
  Block block(int row0, int col0) const;  // throws std::logic_error if the groups do not couple
  // The same from where the analysis (shared through analyze_as) puts the pair in the lower
  // triangle (SupernodalLdlt::block's base and steps for row0, col0): no search.
  Block block(int row0, int col0, long lower_base, long row_step, long col_step) const;
  void zero_values();
  double* values(bool upper) { return upper ? ux_.data() : lx_.data(); }
  bool factorize_values();  // as factorize, from the values added in place
  int perturbed_pivots() const { return perturbed_; }
  // Solves A x = b in place for each column of b (n rows).
  void solve(Eigen::Ref<Eigen::MatrixXd> b) const;

 private:
  void update(int d, int s, const UpdateRows& rows) override;
  bool factor(int s) override;
  void allocate() override;
  // In lx_ if >= 0, else in ux_ at -1 - it.
  long entry_destination(int row, int col) const override;

  // Supernode s's block in lx_: its diagonal block in full (L below the diagonal, unit diagonal
  // implied, U on and above it) and L's off-diagonal rows; in ux_ at the same places the
  // off-diagonal rows of U transposed (the diagonal block unused).
  std::vector<double> lx_, ux_;
  std::vector<int> pivot_;  // per column: the row of its supernode's diagonal block exchanged with it
  std::vector<double> tiny_;  // per column: its pivot bound in the current factorisation
  int perturbed_ = 0;
};

}  // namespace pfem
