#pragma once
// What the supernodal factorisations (supernodal_ldlt.h, supernodal_lu.h) share: the layout of
// the factor from the symbolic analysis of supernodal_symbolic.h (the permutation, the
// supernodes, their rows and where their values lie) and the left-looking schedule of the
// numeric factorisation, in which each supernode takes the updates of the earlier ones that
// touch it, is factorised, and is linked to the next supernode it updates.
//
// Storage: supernode s holds columns super[s] .. super[s+1]-1 of the permuted matrix; its values
// are a column-major block of nsrow x nscol doubles at px[s] (its own columns' rows first, then
// its off-diagonal rows, ascending). A factorisation keeps one or more arrays of that layout.
#include <Eigen/SparseCore>
#include <array>
#include <span>
#include <vector>

namespace pfem {

struct SupernodalStructure;

class SupernodalFactor {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  virtual ~SupernodalFactor() = default;
  int size() const { return n_; }

  // Ordering and supernodal symbolic factorisation from the couplings between groups of
  // unknowns (supernodal_symbolic.h), the groups holding an unknown of `last` ordered after all
  // others; the matrix's entries are then added in place (the factorisation's block()).
  void analyze(int n, std::span<const int> group, std::span<const std::array<int, 2>> couplings,
               std::span<const int> last = {});
  // The same from the pattern of a (compressed; group[k] the group of unknown k, empty: each
  // unknown alone), with where each of its entries goes kept for factorize(a).
  void analyze(const SparseMatrix& a, std::span<const int> group = {}, std::span<const int> last = {});

 protected:
  // The value arrays for the analysed layout.
  virtual void allocate() = 0;
  // Where the factorisation keeps entry (row, col) of the matrix, kNotKept if it ignores it.
  static constexpr long kNotKept = -(1L << 62);
  virtual long entry_destination(int row, int col) const = 0;
  // Whether a has the pattern of the last analysed matrix (outer_, inner_).
  bool same_pattern(const SparseMatrix& a) const;
  // Where entry (row, col) of the matrix lies in the supernode that holds column min(row, col) of
  // the permuted matrix: with the permuted row r and column c, at (max(r, c), min(r, c)) of that
  // block, or -1 if the analysis gave it no place.
  long find_position(int row, int col) const;
  // Where entry (row, col) lies when both are columns of one supernode (its diagonal block,
  // kept in full by the LU): at (r, c) of the block; -1 otherwise.
  long diagonal_block_position(int row, int col) const;

  // The rows of the factorised supernode d that update supernode s, as positions in d's row
  // list: [first, split) are columns of s, [first, end) all the rows they update.
  struct UpdateRows {
    int first, split, end;
  };
  // Supernodes first .. last-1 in turn take the updates of the factorised supernodes linked to
  // them (update(d, s, rows) with ws_.local mapping every row to its place in s) and then, if
  // `factor`, are factorised (factor(s)) and linked to the next supernode they update. False when
  // a factorisation fails. Clear ws_.head (from `first` on) before the first call.
  bool eliminate(int first, int last, bool factor);
  virtual void update(int d, int s, const UpdateRows& rows) = 0;
  virtual bool factor(int s) = 0;

  int nsrow(int s) const { return static_cast<int>(pi_[s + 1] - pi_[s]); }
  int nscol(int s) const { return super_[s + 1] - super_[s]; }

  int n_ = 0;
  int nsuper_ = 0;
  std::vector<int> outer_, inner_;  // the analysed pattern (analysis from a matrix)
  std::vector<int> entry_src_;      // its kept entries (indices into its values) ...
  std::vector<long> entry_dst_;     // ... and where each goes (entry_destination)
  std::vector<int> group_, last_;   // as analysed
  std::vector<int> perm_, iperm_;   // row k of the factor is row perm_[k] of the matrix
  std::vector<int> super_;          // supernode s holds columns super_[s] .. super_[s+1]-1
  std::vector<int> super_of_col_;   // the supernode of each column
  std::vector<long> pi_, px_;       // starts of each supernode's row indices (in ls_) and values
  std::vector<int> ls_;             // row indices of each supernode, its own columns first
  int max_rows_ = 0, max_cols_ = 0;
  int first_trailing_ = 0;  // the first supernode holding an unknown of last_ (nsuper_ if none)
  struct Workspace {
    std::vector<int> local, relative, head, next, lpos;
    std::vector<double> update, w;
  };
  Workspace ws_;

 private:
  // Links the factorised supernode s to the first supernode its off-diagonal rows update.
  void link(int s);
};

}  // namespace pfem
