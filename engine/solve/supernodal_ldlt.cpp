#include "engine/solve/supernodal_ldlt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "engine/solve/blas.h"

namespace pfem {
namespace {

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
      blas::gemm('N', 'T', nt, nt, width, -1.0, x + j1 + static_cast<long>(j0) * nsrow, nsrow, w, nt, 1.0,
                 x + j1 + static_cast<long>(j1) * nsrow, nsrow);
    }
  }
  const int m = nsrow - nscol;
  if (wide && m > 0) {
    blas::trsm('R', 'L', 'T', 'U', m, nscol, x, nsrow, x + nscol, nsrow);
    for (int j = 0; j < nscol; ++j) {
      const double inv = 1.0 / d[j];
      double* below = x + nscol + static_cast<long>(j) * nsrow;
      for (int i = 0; i < m; ++i) below[i] *= inv;
    }
  }
  return true;
}

}  // namespace

void SupernodalLdlt::allocate() {
  lx_.resize(static_cast<std::size_t>(px_[nsuper_]));
  d_.resize(n_);
}

long SupernodalLdlt::entry_destination(int row, int col) const {
  return row < col ? kNotKept : find_position(row, col);  // the lower triangle
}

SupernodalLdlt::Block SupernodalLdlt::block(int row0, int col0) const {
  const long position = find_position(row0, col0);
  if (position < 0) throw std::logic_error("SupernodalLdlt::block: the groups were not coupled at analysis");
  const int pr = iperm_[row0], pc = iperm_[col0];
  const long rows = nsrow(super_of_col_[std::min(pr, pc)]);
  return pr >= pc ? Block{position, 1, rows} : Block{position, rows, 1};
}

void SupernodalLdlt::zero_values() { std::fill(lx_.begin(), lx_.end(), 0.0); }

void SupernodalLdlt::update(int d, int s, const UpdateRows& r) {
  // update (ndrow2 x ndrow1) = L_d(rows from first) D_d L_d(rows first..split)^T, then its lower
  // triangle subtracted from s at the rows' places.
  const int ndrow = nsrow(d), ndcol = nscol(d);
  const int ndrow1 = r.split - r.first, ndrow2 = r.end - r.first, ns = nsrow(s);
  const double* ld = lx_.data() + px_[d] + r.first;
  const double* dd = d_.data() + super_[d];
  double* w = ws_.w.data();
  for (int j = 0; j < ndcol; ++j)
    for (int i = 0; i < ndrow1; ++i) w[i + j * ndrow1] = ld[i + static_cast<long>(j) * ndrow] * dd[j];
  blas::gemm('N', 'T', ndrow2, ndrow1, ndcol, 1.0, ld, ndrow, w, ndrow1, 0.0, ws_.update.data(), ndrow2);
  const int* relative = ws_.relative.data();
  double* xs = lx_.data() + px_[s];
  for (int j = 0; j < ndrow1; ++j) {
    double* col = xs + static_cast<long>(relative[j]) * ns;
    const double* u = ws_.update.data() + static_cast<long>(j) * ndrow2;
    for (int i = j; i < ndrow2; ++i) col[relative[i]] -= u[i];
  }
}

bool SupernodalLdlt::factor(int s) {
  return factor_supernode(lx_.data() + px_[s], nsrow(s), nscol(s), d_.data() + super_[s], ws_.w.data());
}

bool SupernodalLdlt::factorize(const SparseMatrix& a) {
  if (!a.isCompressed()) throw std::invalid_argument("SupernodalLdlt needs a compressed matrix");
  if (!same_pattern(a)) analyze(a, std::vector<int>(group_), std::vector<int>(last_));
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
