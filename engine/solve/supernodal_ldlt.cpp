#include "engine/solve/supernodal_ldlt.h"

#include "engine/solve/supernodal_symbolic.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

// The BLAS (Fortran interface; the system's libblas.so.3 is OpenBLAS, as for CHOLMOD).
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc, std::size_t transa_len,
                       std::size_t transb_len);
extern "C" void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
                       const int* n, const double* alpha, const double* a, const int* lda, double* b, const int* ldb,
                       std::size_t side_len, std::size_t uplo_len, std::size_t transa_len, std::size_t diag_len);

namespace pfem {
namespace {

// c (m x n, leading dimension ldc) = beta c + alpha a b^T, a m x k, b n x k.
void gemm_nt(int m, int n, int k, double alpha, const double* a, int lda, const double* b, int ldb, double beta,
             double* c, int ldc) {
  dgemm_("N", "T", &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc, 1, 1);
}

// Supernodes wider than this are factorised a panel of this many columns at a time.
constexpr int kPanel = 32;

// In place LDL^T of one supernode: x is nsrow x nscol (leading dimension nsrow), its top
// nscol x nscol block the diagonal block (lower triangle read), the rows below it the
// off-diagonal block. On return the strictly lower part holds L (unit diagonal implied) and d
// the nscol pivots; the upper triangle of the diagonal block is left as scratch. w holds at
// least nscol * min(nscol, kPanel) doubles. Returns false on a zero or non-finite pivot.
bool factor_supernode(double* x, int nsrow, int nscol, double* d, double* w) {
  // A narrow supernode (one panel) is factorised right-looking over all its rows. A wide one
  // kPanel columns at a time over its diagonal block (the columns right of each panel updated
  // by dgemm, x22 -= L21 D L21^T), then its off-diagonal rows by dtrsm: L21 = X21 L11^-T D^-1.
  const bool wide = nscol > kPanel;
  const int rows = wide ? nscol : nsrow;
  for (int j0 = 0; j0 < nscol; j0 += kPanel) {
    const int j1 = std::min(j0 + kPanel, nscol);
    for (int j = j0; j < j1; ++j) {
      double* cj = x + static_cast<long>(j) * nsrow;
      const double dj = cj[j];
      if (dj == 0.0 || !std::isfinite(dj)) return false;
      d[j] = dj;
      const double inv = 1.0 / dj;
      for (int i = j + 1; i < rows; ++i) cj[i] *= inv;
      for (int k = j + 1; k < j1; ++k) {
        double* ck = x + static_cast<long>(k) * nsrow;
        const double f = cj[k] * dj;
        for (int i = k; i < rows; ++i) ck[i] -= cj[i] * f;
      }
    }
    if (j1 < nscol) {
      const int nt = nscol - j1, width = j1 - j0;
      for (int j = 0; j < width; ++j)
        for (int i = 0; i < nt; ++i) w[i + j * nt] = x[(j1 + i) + static_cast<long>(j0 + j) * nsrow] * d[j0 + j];
      gemm_nt(nt, nt, width, -1.0, x + j1 + static_cast<long>(j0) * nsrow, nsrow, w, nt, 1.0,
              x + j1 + static_cast<long>(j1) * nsrow, nsrow);
    }
  }
  const int m = nsrow - nscol;
  if (wide && m > 0) {
    const double one = 1.0;
    dtrsm_("R", "L", "T", "U", &m, &nscol, &one, x, &nsrow, x + nscol, &nsrow, 1, 1, 1, 1);
    for (int j = 0; j < nscol; ++j) {
      const double inv = 1.0 / d[j];
      double* below = x + nscol + static_cast<long>(j) * nsrow;
      for (int i = 0; i < m; ++i) below[i] *= inv;
    }
  }
  return true;
}

}  // namespace

void SupernodalLdlt::take_structure(SupernodalStructure&& structure) {
  perm_ = std::move(structure.perm);
  super_ = std::move(structure.super);
  pi_ = std::move(structure.pi);
  px_ = std::move(structure.px);
  ls_ = std::move(structure.rows);
  first_trailing_ = structure.first_trailing;
  n_ = static_cast<int>(perm_.size());
  nsuper_ = static_cast<int>(super_.size()) - 1;
  lx_.resize(static_cast<std::size_t>(px_[nsuper_]));
  iperm_.resize(n_);
  for (int k = 0; k < n_; ++k) iperm_[perm_[k]] = k;
  super_of_col_.resize(n_);
  max_rows_ = max_cols_ = 0;
  for (int k = 0; k < nsuper_; ++k) {
    std::fill(super_of_col_.begin() + super_[k], super_of_col_.begin() + super_[k + 1], k);
    max_cols_ = std::max(max_cols_, super_[k + 1] - super_[k]);
    max_rows_ = std::max(max_rows_, static_cast<int>(pi_[k + 1] - pi_[k]));
  }
  d_.resize(n_);
  ws_.local.assign(n_, 0);
  ws_.relative.assign(max_rows_, 0);
  ws_.head.assign(nsuper_, -1);
  ws_.next.assign(nsuper_, -1);
  ws_.lpos.assign(nsuper_, 0);
  ws_.update.resize(static_cast<std::size_t>(max_rows_) * max_cols_ + 1);
  ws_.w.resize(static_cast<std::size_t>(max_cols_) * max_cols_ + 1);
}

void SupernodalLdlt::analyze(int n, std::span<const int> group, std::span<const std::array<int, 2>> couplings,
                             std::span<const int> last) {
  take_structure(supernodal_symbolic(n, group, couplings, last));
  group_.assign(group.begin(), group.end());
  last_.assign(last.begin(), last.end());
  outer_.clear();
  inner_.clear();
  entry_src_.clear();
  entry_dst_.clear();
}

void SupernodalLdlt::analyze(const SparseMatrix& a, std::span<const int> group, std::span<const int> last) {
  if (a.rows() != a.cols() || !a.isCompressed())
    throw std::invalid_argument("SupernodalLdlt needs a square, compressed matrix");
  const int n = static_cast<int>(a.rows());
  if (!group.empty() && static_cast<int>(group.size()) != n)
    throw std::invalid_argument("SupernodalLdlt: one group per unknown");
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const auto id = [&group](int k) { return group.empty() ? k : group[k]; };
  std::vector<std::array<int, 2>> couplings;
  couplings.reserve(a.nonZeros());
  for (int j = 0; j < n; ++j)
    for (int p = outer[j]; p < outer[j + 1]; ++p)
      if (inner[p] > j) couplings.push_back({id(inner[p]), id(j)});
  analyze(n, group, couplings, last);
  outer_.assign(outer, outer + n + 1);
  inner_.assign(inner, inner + a.nonZeros());
  // Where each entry of a's lower triangle goes in the factor.
  for (int j = 0; j < n; ++j)
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      if (inner[p] < j) continue;
      entry_src_.push_back(p);
      entry_dst_.push_back(find_position(inner[p], j));
    }
}

long SupernodalLdlt::find_position(int row, int col) const {
  const int pr = iperm_[row], pc = iperm_[col];
  const int c = std::min(pr, pc), r = std::max(pr, pc);
  const int k = super_of_col_[c];
  const int nscol = super_[k + 1] - super_[k], nsrow = static_cast<int>(pi_[k + 1] - pi_[k]);
  int local = r - super_[k];  // the supernode's own columns come first, in order
  if (r >= super_[k + 1]) {
    const int* rows = ls_.data() + pi_[k];
    const int* found = std::lower_bound(rows + nscol, rows + nsrow, r);
    if (found == rows + nsrow || *found != r) return -1;
    local = static_cast<int>(found - rows);
  }
  return px_[k] + static_cast<long>(c - super_[k]) * nsrow + local;
}

SupernodalLdlt::Block SupernodalLdlt::block(int row0, int col0) const {
  const long position = find_position(row0, col0);
  if (position < 0) throw std::logic_error("SupernodalLdlt::block: the groups were not coupled at analysis");
  const int pr = iperm_[row0], pc = iperm_[col0];
  const int k = super_of_col_[std::min(pr, pc)];
  const long nsrow = pi_[k + 1] - pi_[k];
  return pr >= pc ? Block{position, 1, nsrow} : Block{position, nsrow, 1};
}

void SupernodalLdlt::zero_values() { std::fill(lx_.begin(), lx_.end(), 0.0); }

void SupernodalLdlt::apply_update(int d, int s, double* xs) {
  Workspace& ws = ws_;
  const int k2 = super_[s + 1], nsrow = static_cast<int>(pi_[s + 1] - pi_[s]);
  const long pdi = pi_[d], pdend = pi_[d + 1];
  const int ndrow = static_cast<int>(pdend - pdi), ndcol = super_[d + 1] - super_[d];
  const long pdi1 = pdi + ws.lpos[d];
  long pdi2 = pdi1;
  while (pdi2 < pdend && ls_[pdi2] < k2) ++pdi2;
  const int ndrow1 = static_cast<int>(pdi2 - pdi1), ndrow2 = static_cast<int>(pdend - pdi1);
  const std::size_t update_size = static_cast<std::size_t>(ndrow1) * ndrow2;
  if (update_size > ws.update.size()) ws.update.resize(update_size);
  // update (ndrow2 x ndrow1) = L_d(rows from pdi1) D_d L_d(rows pdi1..pdi2)^T
  const double* ld = lx_.data() + px_[d] + (pdi1 - pdi);
  const double* dd = d_.data() + super_[d];
  double* w = ws.w.data();
  for (int j = 0; j < ndcol; ++j)
    for (int i = 0; i < ndrow1; ++i) w[i + j * ndrow1] = ld[i + static_cast<long>(j) * ndrow] * dd[j];
  gemm_nt(ndrow2, ndrow1, ndcol, 1.0, ld, ndrow, w, ndrow1, 0.0, ws.update.data(), ndrow2);
  int* relative = ws.relative.data();
  for (int i = 0; i < ndrow2; ++i) relative[i] = ws.local[ls_[pdi1 + i]];
  for (int j = 0; j < ndrow1; ++j) {
    double* col = xs + static_cast<long>(relative[j]) * nsrow;
    const double* u = ws.update.data() + static_cast<long>(j) * ndrow2;
    for (int i = j; i < ndrow2; ++i) col[relative[i]] -= u[i];
  }
  // d's next target is the supernode of its first row past s.
  ws.lpos[d] = static_cast<int>(pdi2 - pdi);
  if (pdi2 < pdend) {
    const int target = super_of_col_[ls_[pdi2]];
    ws.next[d] = ws.head[target];
    ws.head[target] = d;
  }
}

void SupernodalLdlt::link(int s) {
  Workspace& ws = ws_;
  const int nscol = super_[s + 1] - super_[s];
  if (pi_[s + 1] - pi_[s] == nscol) return;
  ws.lpos[s] = nscol;
  const int target = super_of_col_[ls_[pi_[s] + nscol]];
  ws.next[s] = ws.head[target];
  ws.head[target] = s;
}

bool SupernodalLdlt::factorize(const SparseMatrix& a) {
  if (!a.isCompressed()) throw std::invalid_argument("SupernodalLdlt needs a compressed matrix");
  const bool same_pattern = a.rows() == n_ && a.nonZeros() == static_cast<long>(inner_.size()) &&
                            std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
                            std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
  if (!same_pattern) analyze(a, std::vector<int>(group_), std::vector<int>(last_));
  zero_values();
  const double* values = a.valuePtr();
  for (std::size_t q = 0; q < entry_src_.size(); ++q) lx_[entry_dst_[q]] = values[entry_src_[q]];
  return factorize_values();
}

bool SupernodalLdlt::factorize_values() {
  // Left-looking: supernode s holds its entries of the matrix, then takes the updates of every
  // earlier supernode d with rows in s's columns. Supernodes waiting to update s are linked
  // from head[s] (next[] chains them); lpos[d] is where d's next rows to use start. The
  // trailing supernodes only collect the leading ones' updates here (kept for update_last).
  std::fill(ws_.head.begin(), ws_.head.end(), -1);
  if (!eliminate(0, first_trailing_, true)) return false;
  eliminate(first_trailing_, nsuper_, false);
  trailing_sums_.assign(lx_.begin() + px_[first_trailing_], lx_.end());
  return factorize_trailing({});
}

bool SupernodalLdlt::eliminate(int first, int last, bool factor) {
  for (int s = first; s < last; ++s) {
    const long psi = pi_[s];
    const int nsrow = static_cast<int>(pi_[s + 1] - psi);
    double* xs = lx_.data() + px_[s];
    for (int i = 0; i < nsrow; ++i) ws_.local[ls_[psi + i]] = i;
    for (int d = ws_.head[s]; d >= 0;) {
      const int dnext = ws_.next[d];
      apply_update(d, s, xs);
      d = dnext;
    }
    if (!factor) continue;
    if (!factor_supernode(xs, nsrow, super_[s + 1] - super_[s], d_.data() + super_[s], ws_.w.data())) return false;
    link(s);
  }
  return true;
}

bool SupernodalLdlt::factorize_trailing(std::span<const std::pair<long, double>> additions) {
  std::copy(trailing_sums_.begin(), trailing_sums_.end(), lx_.begin() + px_[first_trailing_]);
  for (const auto& [position, value] : additions) lx_[position] += value;
  std::fill(ws_.head.begin() + first_trailing_, ws_.head.end(), -1);
  return eliminate(first_trailing_, nsuper_, true);
}

bool SupernodalLdlt::update_last(std::span<const Eigen::Triplet<double>> delta) {
  const int first_column = super_[first_trailing_];
  std::vector<std::pair<long, double>> additions;
  additions.reserve(delta.size());
  for (const auto& e : delta) {
    if (e.row() < e.col()) continue;
    if (e.row() >= n_ || e.col() < 0) throw std::invalid_argument("SupernodalLdlt::update_last: entry out of range");
    if (std::min(iperm_[e.row()], iperm_[e.col()]) < first_column) return false;
    const long position = find_position(e.row(), e.col());
    if (position < 0) return false;
    additions.emplace_back(position, e.value());
  }
  return factorize_trailing(additions);
}

void SupernodalLdlt::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
  if (b.rows() != n_) throw std::invalid_argument("SupernodalLdlt::solve: wrong number of rows");
  using ConstColumn = Eigen::Map<const Eigen::VectorXd>;
  // Per supernode: the triangular diagonal block on its own (contiguous) unknowns, and the
  // off-diagonal block as dense products with t, gathered or scattered once per row.
  Eigen::VectorXd buffer(n_), t_buffer(max_rows_);
  double* y = buffer.data();
  double* t = t_buffer.data();
  const double* lx = lx_.data();
  for (long c = 0; c < b.cols(); ++c) {
    for (int k = 0; k < n_; ++k) y[k] = b(perm_[k], c);
    // L y = b.
    for (int s = 0; s < nsuper_; ++s) {
      const int k1 = super_[s], nscol = super_[s + 1] - k1;
      const int nsrow = static_cast<int>(pi_[s + 1] - pi_[s]), nrest = nsrow - nscol;
      const int* rows = ls_.data() + pi_[s] + nscol;
      const double* xs = lx + px_[s];
      double* ys = y + k1;
      Eigen::Map<Eigen::VectorXd> tr(t, nrest);
      tr.setZero();
      for (int j = 0; j < nscol; ++j) {
        const double* col = xs + static_cast<long>(j) * nsrow;
        const double yj = ys[j];
        Eigen::Map<Eigen::VectorXd>(ys + j + 1, nscol - j - 1) -= yj * ConstColumn(col + j + 1, nscol - j - 1);
        tr += yj * ConstColumn(col + nscol, nrest);
      }
      for (int i = 0; i < nrest; ++i) y[rows[i]] -= t[i];
    }
    for (int k = 0; k < n_; ++k) y[k] /= d_[k];
    // L^T x = y, backwards.
    for (int s = nsuper_ - 1; s >= 0; --s) {
      const int k1 = super_[s], nscol = super_[s + 1] - k1;
      const int nsrow = static_cast<int>(pi_[s + 1] - pi_[s]), nrest = nsrow - nscol;
      const int* rows = ls_.data() + pi_[s] + nscol;
      const double* xs = lx + px_[s];
      double* ys = y + k1;
      for (int i = 0; i < nrest; ++i) t[i] = y[rows[i]];
      const ConstColumn tr(t, nrest);
      for (int j = nscol - 1; j >= 0; --j) {
        const double* col = xs + static_cast<long>(j) * nsrow;
        ys[j] -= ConstColumn(col + nscol, nrest).dot(tr) +
                 ConstColumn(col + j + 1, nscol - j - 1).dot(ConstColumn(ys + j + 1, nscol - j - 1));
      }
    }
    for (int k = 0; k < n_; ++k) b(perm_[k], c) = y[k];
  }
}

}  // namespace pfem
