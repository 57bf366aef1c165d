// SupernodalLu against dense partial-pivoting LU (Eigen) and UMFPACK on nonsymmetric matrices
// with the pattern of a PFEM step's Jacobian (a triangulated 2D grid, three unknowns per node),
// including matrices that need the row exchanges inside a diagonal block, entries added in place
// at block(), unknowns ordered last, a singular matrix (its pivots perturbed and counted) and a
// non-finite entry (reported).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <array>
#include <limits>
#include <random>
#include <vector>

#include "engine/solve/linear_solvers.h"
#include "engine/solve/supernodal_ldlt.h"
#include "engine/solve/supernodal_lu.h"
#include "tests/unit/random_rhs.h"

namespace pfem {
namespace {

// The nodes of an nx x ny grid joined to their right, upper and upper-right neighbours.
std::vector<std::array<int, 2>> grid_edges(int nx, int ny) {
  std::vector<std::array<int, 2>> edges;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * nx + i;
      if (i + 1 < nx) edges.push_back({a, a + 1});
      if (j + 1 < ny) edges.push_back({a, a + nx});
      if (i + 1 < nx && j + 1 < ny) edges.push_back({a, a + nx + 1});
    }
  return edges;
}

// Three unknowns a node, every unknown of a node coupled to every unknown of its own node and of
// its neighbours, each entry drawn on its own (so the matrix is not symmetric, its pattern is).
// Diagonal entries get `diagonal` plus the row's sum of magnitudes times `dominance`, except the
// first unknown of each node when zero_first: 0 there (a saddle point that needs row exchanges).
struct GridMatrix {
  int nx = 12, ny = 12;
  double dominance = 1.0;
  bool zero_first = false;
  unsigned seed = 1;
};
SparseMatrix grid_matrix(const GridMatrix& g) {
  std::mt19937 rng(g.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 3 * g.nx * g.ny;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> row_sum(n, 0.0);
  const auto couple = [&](int a, int b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int i = 3 * a + r, j = 3 * b + c;
        if (i == j) continue;
        const double v = u(rng);
        t.emplace_back(i, j, v);
        row_sum[i] += std::abs(v);
      }
  };
  for (int a = 0; a < g.nx * g.ny; ++a) couple(a, a);
  for (const auto& [a, b] : grid_edges(g.nx, g.ny)) couple(a, b), couple(b, a);
  for (int i = 0; i < n; ++i) {
    const bool zero = g.zero_first && i % 3 == 0;
    t.emplace_back(i, i, zero ? 0.0 : (u(rng) > 0 ? 1.0 : -1.0) * (0.1 + g.dominance * row_sum[i]));
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

std::vector<int> node_groups(int n) {
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[i] = i / 3;
  return group;
}

Eigen::MatrixXd lu_solved(const SupernodalLu& lu, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd x = b;
  lu.solve(x);
  return x;
}

double relative_residual(const SparseMatrix& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  return (a * x - b).norm() / b.norm();
}

TEST(SupernodalLu, SolvesAsDensePartialPivotingLu) {
  // Weakly dominant: the pivots of the diagonal blocks are not the largest entries of their
  // columns, so rows are exchanged.
  for (const bool zero_first : {false, true}) {
    const SparseMatrix a = grid_matrix({.dominance = 0.1, .zero_first = zero_first, .seed = 3});
    const Eigen::MatrixXd b = random_rhs(a.rows(), 3, 4);
    SupernodalLu lu;
    lu.analyze(a, node_groups(static_cast<int>(a.rows())));
    ASSERT_TRUE(lu.factorize(a));
    EXPECT_EQ(lu.perturbed_pivots(), 0);
    const Eigen::MatrixXd x = lu_solved(lu, b);
    const Eigen::MatrixXd x_ref = Eigen::MatrixXd(a).partialPivLu().solve(b);
    EXPECT_LT((x - x_ref).norm() / x_ref.norm(), 1e-11) << "zero_first " << zero_first;
    // Pivoting restricted to the diagonal blocks lets entries grow more than the dense LU's
    // search of whole columns does (residuals 2.7e-13 and 4.1e-12 here against 3.2e-14 and
    // 1.0e-12), not enough to matter.
    EXPECT_LT(relative_residual(a, x, b), 1e-11) << "zero_first " << zero_first;
  }
}

TEST(SupernodalLu, SolvesAsUmfpackOnWideSupernodes) {
  // 36 x 36 nodes: the top separators are several panels (32 columns) wide.
  const SparseMatrix a = grid_matrix({.nx = 36, .ny = 36, .dominance = 0.3, .zero_first = true, .seed = 5});
  const Eigen::MatrixXd b = random_rhs(a.rows(), 2, 6);
  SupernodalLu lu;
  lu.analyze(a, node_groups(static_cast<int>(a.rows())));
  ASSERT_TRUE(lu.factorize(a));
  EXPECT_EQ(lu.perturbed_pivots(), 0);
  LuSolver umfpack;
  umfpack.analyze(a);
  umfpack.factorize(a);
  const Eigen::MatrixXd x = lu_solved(lu, b), x_ref = umfpack.solve(b);
  EXPECT_LT((x - x_ref).norm() / x_ref.norm(), 1e-10);
  EXPECT_LT(relative_residual(a, x, b), 4 * relative_residual(a, x_ref, b));
  // New values on the same pattern.
  const SparseMatrix a2 = grid_matrix({.nx = 36, .ny = 36, .dominance = 0.3, .zero_first = true, .seed = 7});
  ASSERT_TRUE(lu.factorize(a2));
  umfpack.factorize(a2);
  EXPECT_LT(relative_residual(a2, lu_solved(lu, b), b), 4 * relative_residual(a2, umfpack.solve(b), b));
}

TEST(SupernodalLu, EntriesAddedInPlaceAtTheirBlocksGiveTheSameFactor) {
  // The analysis from the nodes' couplings, every node pair's 3 x 3 blocks added at block() in
  // both orders, against the factorisation of the assembled matrix; a node ordered last.
  const GridMatrix g{.nx = 10, .ny = 9, .dominance = 0.2, .zero_first = true, .seed = 8};
  const SparseMatrix a = grid_matrix(g);
  const int n = static_cast<int>(a.rows());
  const std::vector<int> group = node_groups(n), last{3 * 40, 3 * 40 + 1, 3 * 40 + 2};
  const Eigen::MatrixXd dense(a);
  SupernodalLu in_place;
  in_place.analyze(n, group, grid_edges(g.nx, g.ny), last);
  in_place.zero_values();
  const auto add = [&](int p, int q) {  // the block of node p's rows and node q's columns
    const SupernodalLu::Block blk = in_place.block(3 * p, 3 * q);
    double* values = in_place.values(blk.upper);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) values[blk.base + i * blk.row_step + j * blk.col_step] += dense(3 * p + i, 3 * q + j);
  };
  for (int p = 0; p < g.nx * g.ny; ++p) add(p, p);
  for (const auto& [p, q] : grid_edges(g.nx, g.ny)) add(p, q), add(q, p);
  ASSERT_TRUE(in_place.factorize_values());
  SupernodalLu assembled;
  assembled.analyze(a, group, last);
  ASSERT_TRUE(assembled.factorize(a));
  const Eigen::MatrixXd b = random_rhs(n, 1, 9);
  const Eigen::MatrixXd x = lu_solved(in_place, b);
  EXPECT_EQ(x, lu_solved(assembled, b));
  EXPECT_LT(relative_residual(a, x, b), 1e-12);
}

TEST(SupernodalLu, OnASymmetricMatrixSolvesAsTheLdlt) {
  const GridMatrix g{.dominance = 2.0, .seed = 10};
  const SparseMatrix a0 = grid_matrix(g);
  const SparseMatrix a = SparseMatrix(a0 + SparseMatrix(a0.transpose()));
  const SparseMatrix lower = a.triangularView<Eigen::Lower>();
  const std::vector<int> group = node_groups(static_cast<int>(a.rows()));
  SupernodalLu lu;
  lu.analyze(a, group);
  ASSERT_TRUE(lu.factorize(a));
  SupernodalLdlt ldlt;
  ldlt.analyze(lower, group);
  ASSERT_TRUE(ldlt.factorize(lower));
  const Eigen::MatrixXd b = random_rhs(a.rows(), 1, 11);
  Eigen::MatrixXd x_ldlt = b;
  ldlt.solve(x_ldlt);
  const Eigen::MatrixXd x = lu_solved(lu, b);
  EXPECT_LT((x - x_ldlt).norm() / x_ldlt.norm(), 1e-12);
}

TEST(SupernodalLu, ASingularMatrixHasItsPivotsPerturbedAndCounted) {
  // Node 5's first unknown decoupled with a zero diagonal: one pivot is perturbed, and the other
  // unknowns of a right-hand side that leaves it alone are solved as without it.
  SparseMatrix a = grid_matrix({.dominance = 0.5, .seed = 12});
  const int k = 15;
  for (int j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it)
      if (it.row() == k || it.col() == k) it.valueRef() = 0.0;
  SupernodalLu lu;
  lu.analyze(a, node_groups(static_cast<int>(a.rows())));
  ASSERT_TRUE(lu.factorize(a));
  EXPECT_EQ(lu.perturbed_pivots(), 1);
  Eigen::MatrixXd b = random_rhs(a.rows(), 1, 13);
  b(k, 0) = 0.0;
  const Eigen::MatrixXd x = lu_solved(lu, b);
  EXPECT_EQ(x(k, 0), 0.0);
  EXPECT_LT(relative_residual(a, x, b), 1e-12);
}

TEST(SupernodalLu, ANonFiniteEntryFailsTheFactorisation) {
  SparseMatrix a = grid_matrix({.seed = 14});
  a.coeffRef(30, 30) = std::numeric_limits<double>::quiet_NaN();
  SupernodalLu lu;
  lu.analyze(a, node_groups(static_cast<int>(a.rows())));
  EXPECT_FALSE(lu.factorize(a));
}

}  // namespace
}  // namespace pfem
