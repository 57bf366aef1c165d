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

namespace pfem {

struct SupernodalStructure;

class SupernodalLdlt {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  // Ordering and supernodal symbolic factorisation of the lower triangle of a (which must be
  // compressed), on the graph of the groups of unknowns (group[k] of unknown k; empty: each
  // unknown alone), the groups holding an unknown of `last` ordered after all others.
  void analyze(const SparseMatrix& a, std::span<const int> group = {}, std::span<const int> last = {});
  // The same from the couplings between groups (supernodal_symbolic.h), with no matrix: its
  // entries are then added in place (zero_values, values() at block(), factorize_values).
  void analyze(int n, std::span<const int> group, std::span<const std::array<int, 2>> couplings,
               std::span<const int> last = {});
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
  struct Workspace {
    std::vector<int> local, relative, head, next, lpos;
    std::vector<double> update, w;
  };
  // Subtracts from supernode s (values xs; ws_.local maps its rows to positions) the update of
  // the factorised supernode d from d's rows at ws_.lpos[d] on, then links d to its next target.
  void apply_update(int d, int s, double* xs);
  // Links the factorised supernode s to the first supernode its off-diagonal rows update.
  void link(int s);
  // Supernodes first .. last-1 in turn take the updates linked to them and, if `factor`, are
  // factorised and linked on. False on a zero or non-finite pivot.
  bool eliminate(int first, int last, bool factor);
  // Where entry (row, col) of the lower triangle lies in lx_, or -1 if nowhere.
  long find_position(int row, int col) const;
  // Member arrays from the symbolic structure; max_rows_, workspaces.
  void take_structure(SupernodalStructure&& structure);
  // The trailing supernodes from their kept sums (a's entries and the leading supernodes'
  // updates) plus the (position, value) additions.
  bool factorize_trailing(std::span<const std::pair<long, double>> additions);

  int n_ = 0;
  int nsuper_ = 0;
  std::vector<int> outer_, inner_;  // the analysed pattern
  std::vector<int> group_, last_;   // as analysed
  std::vector<int> perm_, iperm_;   // row k of the factor is row perm_[k] of a
  std::vector<int> super_;          // supernode s holds columns super_[s] .. super_[s+1]-1
  std::vector<int> super_of_col_;   // the supernode of each column
  std::vector<long> pi_, px_;       // starts of each supernode's row indices (in ls_) and values (in lx_)
  std::vector<int> ls_;             // row indices of each supernode, its own columns first
  std::vector<int> entry_src_;      // a's lower entries (indices into its values) ...
  std::vector<long> entry_dst_;     // ... and where each goes in lx_
  int max_rows_ = 0, max_cols_ = 0;
  std::vector<double> lx_;          // supernodal L (unit diagonal implied), column-major blocks
  std::vector<double> d_;           // the diagonal D
  int first_trailing_ = 0;          // the first supernode holding an unknown of last_ (nsuper_ if none)
  std::vector<double> trailing_sums_;  // lx_ from px_[first_trailing_] on before their factorisation
  Workspace ws_;
};

}  // namespace pfem
