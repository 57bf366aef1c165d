#include "engine/solve/supernodal_factor.h"

#include "engine/solve/supernodal_symbolic.h"

#include <algorithm>
#include <stdexcept>

namespace pfem {

void SupernodalFactor::analyze(int n, std::span<const int> group, std::span<const std::array<int, 2>> couplings,
                               std::span<const int> last) {
  SupernodalStructure structure = supernodal_symbolic(n, group, couplings, last);
  perm_ = std::move(structure.perm);
  super_ = std::move(structure.super);
  pi_ = std::move(structure.pi);
  px_ = std::move(structure.px);
  ls_ = std::move(structure.rows);
  first_trailing_ = structure.first_trailing;
  n_ = static_cast<int>(perm_.size());
  nsuper_ = static_cast<int>(super_.size()) - 1;
  iperm_.resize(n_);
  for (int k = 0; k < n_; ++k) iperm_[perm_[k]] = k;
  super_of_col_.resize(n_);
  max_rows_ = max_cols_ = 0;
  for (int k = 0; k < nsuper_; ++k) {
    std::fill(super_of_col_.begin() + super_[k], super_of_col_.begin() + super_[k + 1], k);
    max_cols_ = std::max(max_cols_, nscol(k));
    max_rows_ = std::max(max_rows_, nsrow(k));
  }
  ws_.local.assign(n_, 0);
  ws_.relative.assign(max_rows_, 0);
  ws_.head.assign(nsuper_, -1);
  ws_.next.assign(nsuper_, -1);
  ws_.lpos.assign(nsuper_, 0);
  ws_.update.resize(2 * static_cast<std::size_t>(max_rows_) * max_cols_ + 1);
  ws_.w.resize(static_cast<std::size_t>(max_cols_) * max_cols_ + 1);
  group_.assign(group.begin(), group.end());
  last_.assign(last.begin(), last.end());
  outer_.clear();
  inner_.clear();
  entry_src_.clear();
  entry_dst_.clear();
  allocate();
}

void SupernodalFactor::analyze(const SparseMatrix& a, std::span<const int> group, std::span<const int> last) {
  if (a.rows() != a.cols() || !a.isCompressed())
    throw std::invalid_argument("a supernodal factorisation needs a square, compressed matrix");
  const int n = static_cast<int>(a.rows());
  if (!group.empty() && static_cast<int>(group.size()) != n)
    throw std::invalid_argument("a supernodal factorisation needs one group per unknown");
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const auto id = [&group](int k) { return group.empty() ? k : group[k]; };
  std::vector<std::array<int, 2>> couplings;
  couplings.reserve(a.nonZeros());
  for (int j = 0; j < n; ++j)
    for (int p = outer[j]; p < outer[j + 1]; ++p)
      if (inner[p] != j) couplings.push_back({id(inner[p]), id(j)});
  analyze(n, group, couplings, last);
  outer_.assign(outer, outer + n + 1);
  inner_.assign(inner, inner + a.nonZeros());
  for (int j = 0; j < n; ++j)
    for (int p = outer[j]; p < outer[j + 1]; ++p)
      if (const long d = entry_destination(inner[p], j); d != kNotKept) {
        entry_src_.push_back(p);
        entry_dst_.push_back(d);
      }
}

bool SupernodalFactor::same_pattern(const SparseMatrix& a) const {
  return a.isCompressed() && a.rows() == n_ && a.nonZeros() == static_cast<long>(inner_.size()) &&
         std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
}

long SupernodalFactor::find_position(int row, int col) const {
  const int pr = iperm_[row], pc = iperm_[col];
  const int c = std::min(pr, pc), r = std::max(pr, pc);
  const int k = super_of_col_[c];
  const int ncol = nscol(k), nrow = nsrow(k);
  int local = r - super_[k];  // the supernode's own columns come first, in order
  if (r >= super_[k + 1]) {
    const int* rows = ls_.data() + pi_[k];
    const int* found = std::lower_bound(rows + ncol, rows + nrow, r);
    if (found == rows + nrow || *found != r) return -1;
    local = static_cast<int>(found - rows);
  }
  return px_[k] + static_cast<long>(c - super_[k]) * nrow + local;
}

long SupernodalFactor::diagonal_block_position(int row, int col) const {
  const int pr = iperm_[row], pc = iperm_[col];
  const int k = super_of_col_[pr];
  if (super_of_col_[pc] != k) return -1;
  return px_[k] + static_cast<long>(pc - super_[k]) * nsrow(k) + (pr - super_[k]);
}

void SupernodalFactor::link(int s) {
  const int ncol = nscol(s);
  if (nsrow(s) == ncol) return;
  ws_.lpos[s] = ncol;
  const int target = super_of_col_[ls_[pi_[s] + ncol]];
  ws_.next[s] = ws_.head[target];
  ws_.head[target] = s;
}

bool SupernodalFactor::eliminate(int first, int last, bool factor_them) {
  for (int s = first; s < last; ++s) {
    const long psi = pi_[s];
    const int k2 = super_[s + 1];
    for (int i = 0; i < nsrow(s); ++i) ws_.local[ls_[psi + i]] = i;
    for (int d = ws_.head[s]; d >= 0;) {
      const int dnext = ws_.next[d];
      const int* rows = ls_.data() + pi_[d];
      UpdateRows r{ws_.lpos[d], ws_.lpos[d], nsrow(d)};
      while (r.split < r.end && rows[r.split] < k2) ++r.split;
      for (int i = r.first; i < r.end; ++i) ws_.relative[i - r.first] = ws_.local[rows[i]];
      update(d, s, r);
      // d's next target is the supernode of its first row past s.
      ws_.lpos[d] = r.split;
      if (r.split < r.end) {
        const int target = super_of_col_[rows[r.split]];
        ws_.next[d] = ws_.head[target];
        ws_.head[target] = d;
      }
      d = dnext;
    }
    if (!factor_them) continue;
    if (!factor(s)) return false;
    link(s);
  }
  return true;
}

}  // namespace pfem
