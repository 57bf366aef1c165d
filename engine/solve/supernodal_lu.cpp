#include "engine/solve/supernodal_lu.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/solve/blas.h"

namespace pfem {
namespace {

// Diagonal blocks wider than this are factorised a panel of this many columns at a time.
constexpr int kPanel = 32;

// Exchanges rows i and j of the n columns of x (leading dimension ld).
void swap_rows(double* x, int ld, int n, int i, int j) {
  for (int c = 0; c < n; ++c) std::swap(x[i + static_cast<long>(c) * ld], x[j + static_cast<long>(c) * ld]);
}

// In place LU with partial pivoting of the n x n diagonal block x (leading dimension ld): the
// rows of the block are exchanged in full (pivot[j]: the row exchanged with row j at step j); a
// pivot below tiny[j] in magnitude is set to +-tiny[j] and counted. Panels of kPanel columns, the
// columns right of a panel updated by dtrsm and dgemm (LAPACK's dgetrf). -1 on a non-finite
// pivot, else the number of perturbed pivots.
int factor_diagonal_block(double* x, int ld, int n, int* pivot, const double* tiny) {
  int perturbed = 0;
  for (int j0 = 0; j0 < n; j0 += kPanel) {
    const int j1 = std::min(j0 + kPanel, n);
    for (int j = j0; j < j1; ++j) {
      double* cj = x + static_cast<long>(j) * ld;
      int p = j;
      for (int i = j + 1; i < n; ++i)
        if (std::abs(cj[i]) > std::abs(cj[p])) p = i;
      if (!std::isfinite(cj[p])) return -1;
      if (std::abs(cj[p]) < tiny[j]) {
        p = j;
        cj[j] = cj[j] < 0.0 ? -tiny[j] : tiny[j];
        ++perturbed;
      }
      pivot[j] = p;
      if (p != j) swap_rows(x, ld, n, j, p);
      const double inv = 1.0 / cj[j];
      for (int i = j + 1; i < n; ++i) cj[i] *= inv;
      for (int k = j + 1; k < j1; ++k) {
        double* ck = x + static_cast<long>(k) * ld;
        const double f = ck[j];
        for (int i = j + 1; i < n; ++i) ck[i] -= cj[i] * f;
      }
    }
    if (j1 < n) {
      const int width = j1 - j0, rest = n - j1;
      double* u12 = x + j0 + static_cast<long>(j1) * ld;
      blas::trsm('L', 'L', 'N', 'U', width, rest, x + j0 + static_cast<long>(j0) * ld, ld, u12, ld);
      blas::gemm('N', 'N', rest, rest, width, -1.0, x + j1 + static_cast<long>(j0) * ld, ld, u12, ld, 1.0,
                 x + j1 + static_cast<long>(j1) * ld, ld);
    }
  }
  return perturbed;
}

}  // namespace

void SupernodalLu::allocate() {
  lx_.resize(static_cast<std::size_t>(px_[nsuper_]));
  ux_.resize(lx_.size());
  pivot_.resize(n_);
  tiny_.resize(n_);
}

void SupernodalLu::analyze_as(const SupernodalFactor& other) {
  SupernodalFactor::operator=(other);
  outer_.clear();
  inner_.clear();
  entry_src_.clear();
  entry_dst_.clear();
  allocate();
}

long SupernodalLu::entry_destination(int row, int col) const {
  const Block b = block(row, col);
  return b.upper ? -1 - b.base : b.base;
}

SupernodalLu::Block SupernodalLu::block(int row0, int col0) const {
  const int pr = iperm_[row0], pc = iperm_[col0];
  const int k = super_of_col_[std::min(pr, pc)];
  const long rows = nsrow(k);
  if (super_of_col_[pr] == super_of_col_[pc]) return Block{diagonal_block_position(row0, col0), 1, rows, false};
  const long position = find_position(row0, col0);
  if (position < 0) throw std::logic_error("SupernodalLu::block: the groups were not coupled at analysis");
  return pr > pc ? Block{position, 1, rows, false} : Block{position, rows, 1, true};
}

SupernodalLu::Block SupernodalLu::block(int row0, int col0, long lower_base, long row_step, long col_step) const {
  const int pr = iperm_[row0], pc = iperm_[col0];
  if (pr >= pc) return Block{lower_base, row_step, col_step, false};
  if (super_of_col_[pr] != super_of_col_[pc]) return Block{lower_base, row_step, col_step, true};  // mirrored in ux_
  return Block{diagonal_block_position(row0, col0), 1, nsrow(super_of_col_[pr]), false};  // the full diagonal block
}

void SupernodalLu::zero_values() {
  std::fill(lx_.begin(), lx_.end(), 0.0);
  std::fill(ux_.begin(), ux_.end(), 0.0);
}

bool SupernodalLu::factorize(const SparseMatrix& a) {
  if (!same_pattern(a)) analyze(a, std::vector<int>(group_), std::vector<int>(last_));
  zero_values();
  const double* values = a.valuePtr();
  for (std::size_t q = 0; q < entry_src_.size(); ++q) {
    const long d = entry_dst_[q];
    (d >= 0 ? lx_[d] : ux_[-1 - d]) = values[entry_src_[q]];
  }
  return factorize_values();
}

bool SupernodalLu::factorize_values() {
  // Each column's pivot bound from its own diagonal entry (the unknowns' scales differ by many
  // orders: a beam's axial stiffness and a pressure's mass), from the largest one where it is 0.
  double largest = 0.0;
  for (int s = 0; s < nsuper_; ++s)
    for (int j = 0; j < nscol(s); ++j) {
      const double diagonal = std::abs(lx_[px_[s] + static_cast<long>(j) * (nsrow(s) + 1)]);
      tiny_[super_[s] + j] = kPivotTolerance * diagonal;
      largest = std::max(largest, diagonal);
    }
  for (double& t : tiny_)
    if (t == 0.0) t = kPivotTolerance * largest;
  perturbed_ = 0;
  std::fill(ws_.head.begin(), ws_.head.end(), -1);
  return eliminate(0, nsuper_, true);
}

void SupernodalLu::update(int d, int s, const UpdateRows& r) {
  // With L_1, U_1 d's rows in s's columns and L_2, U_2 all its rows from there on (U transposed):
  // s's columns take L_2 U_1 (its diagonal block in full, its L rows below), s's U rows take
  // L_1 U_(2 beyond 1), each subtracted at the rows' places.
  const int ndrow = nsrow(d), ndcol = nscol(d);
  const int n1 = r.split - r.first, n2 = r.end - r.first, nbelow = n2 - n1, ns = nsrow(s);
  const double* ld = lx_.data() + px_[d] + r.first;
  const double* ud = ux_.data() + px_[d] + r.first;
  double* lower = ws_.update.data();
  double* upper = lower + static_cast<long>(n2) * n1;
  blas::gemm('N', 'T', n2, n1, ndcol, 1.0, ld, ndrow, ud, ndrow, 0.0, lower, n2);
  if (nbelow > 0) blas::gemm('N', 'T', nbelow, n1, ndcol, 1.0, ud + n1, ndrow, ld, ndrow, 0.0, upper, nbelow);
  const int* relative = ws_.relative.data();
  double* xs = lx_.data() + px_[s];
  double* us = ux_.data() + px_[s];
  for (int j = 0; j < n1; ++j) {
    const long column = static_cast<long>(relative[j]) * ns;
    const double* l = lower + static_cast<long>(j) * n2;
    for (int i = 0; i < n2; ++i) xs[column + relative[i]] -= l[i];
    const double* u = upper + static_cast<long>(j) * nbelow;
    for (int i = 0; i < nbelow; ++i) us[column + relative[n1 + i]] -= u[i];
  }
}

bool SupernodalLu::factor(int s) {
  // The diagonal block P F = L11 U11, then L21 = A21 U11^-1 and U12 = L11^-1 P A12, this one
  // transposed: U12^T = (P A12)^T L11^-T, P exchanging the columns of the stored A12^T.
  const int ns = nsrow(s), nc = nscol(s), below = ns - nc;
  double* x = lx_.data() + px_[s];
  double* ut = ux_.data() + px_[s];
  int* pivot = pivot_.data() + super_[s];
  const int perturbed = factor_diagonal_block(x, ns, nc, pivot, tiny_.data() + super_[s]);
  if (perturbed < 0) return false;
  perturbed_ += perturbed;
  if (below == 0) return true;
  blas::trsm('R', 'U', 'N', 'N', below, nc, x, ns, x + nc, ns);
  for (int j = 0; j < nc; ++j)
    if (pivot[j] != j)
      std::swap_ranges(ut + nc + static_cast<long>(j) * ns, ut + ns + static_cast<long>(j) * ns,
                       ut + nc + static_cast<long>(pivot[j]) * ns);
  blas::trsm('R', 'L', 'T', 'U', below, nc, x, ns, ut + nc, ns);
  return true;
}

void SupernodalLu::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
  if (b.rows() != n_) throw std::invalid_argument("SupernodalLu::solve: wrong number of rows");
  // Every column at once, supernode by supernode: the exchanges of its rows and its triangles by
  // dtrsm, its off-diagonal blocks by dgemm, the rows below gathered or scattered once.
  const int m = static_cast<int>(b.cols());
  if (m == 0) return;
  Eigen::MatrixXd y(n_, m), t(max_rows_, m);
  for (int k = 0; k < n_; ++k) y.row(k) = b.row(perm_[k]);
  const int ldy = n_, ldt = max_rows_;
  // L y = P b.
  for (int s = 0; s < nsuper_; ++s) {
    const int k1 = super_[s], nc = nscol(s), ns = nsrow(s), rest = ns - nc;
    const int* rows = ls_.data() + pi_[s] + nc;
    const double* xs = lx_.data() + px_[s];
    for (int j = 0; j < nc; ++j)
      if (pivot_[k1 + j] != j) y.row(k1 + j).swap(y.row(k1 + pivot_[k1 + j]));
    blas::trsm('L', 'L', 'N', 'U', nc, m, xs, ns, y.data() + k1, ldy);
    if (rest == 0) continue;
    blas::gemm('N', 'N', rest, m, nc, 1.0, xs + nc, ns, y.data() + k1, ldy, 0.0, t.data(), ldt);
    for (int i = 0; i < rest; ++i) y.row(rows[i]) -= t.row(i).head(m);
  }
  // U x = y, backwards.
  for (int s = nsuper_ - 1; s >= 0; --s) {
    const int k1 = super_[s], nc = nscol(s), ns = nsrow(s), rest = ns - nc;
    const int* rows = ls_.data() + pi_[s] + nc;
    const double* xs = lx_.data() + px_[s];
    if (rest > 0) {
      for (int i = 0; i < rest; ++i) t.row(i).head(m) = y.row(rows[i]);
      blas::gemm('T', 'N', nc, m, rest, -1.0, ux_.data() + px_[s] + nc, ns, t.data(), ldt, 1.0, y.data() + k1, ldy);
    }
    blas::trsm('L', 'U', 'N', 'N', nc, m, xs, ns, y.data() + k1, ldy);
  }
  for (int k = 0; k < n_; ++k) b.row(perm_[k]) = y.row(k);
}

}  // namespace pfem
