// SupernodalLdlt against CHOLMOD's simplicial LDL^T on symmetric quasi-definite
// matrices shaped like the fluid's (a 2D grid, three unknowns per node: two velocity components
// in the positive definite block, the pressure in the negative definite one): same solutions to
// round-off for one and several right-hand sides and after refactorising new values on the same
// pattern; a zero pivot is reported. Unknowns ordered last (the structure's)
// take a change of their block without a full refactorisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <random>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/solve/linear_solvers.h"
#include "tests/unit/random_rhs.h"
#include "engine/solve/supernodal_ldlt.h"

namespace pfem {
namespace {

// Lower triangle of K = [A B; B^T -C] on an nx x ny grid of nodes joined to their right, upper
// and upper-right neighbours (a triangulated grid), unknowns interleaved per node (u, v, p).
// A and C are diagonally dominant with positive diagonals; B couples every velocity unknown to
// the pressures of the node's neighbours and its own. The pattern depends only on the grid.
SparseMatrix quasi_definite(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(0.1, 1.0), coupling(-0.5, 0.5), sign(-1.0, 1.0);
  const int n = 3 * nx * ny;
  std::vector<Eigen::Triplet<double>> t;
  std::vector<double> diagonal(n, 0.0);
  auto lower = [&t](int i, int j, double v) { t.emplace_back(std::max(i, j), std::min(i, j), v); };
  auto node = [nx](int i, int j) { return j * nx + i; };
  auto join = [&](int a, int b) {  // an edge between nodes a and b (a == b: the node itself)
    for (int c = 0; c < 3; ++c) {
      const int ia = 3 * a + c, ib = 3 * b + c;
      if (a != b) {
        const double w = weight(rng);
        lower(ia, ib, (c < 2 ? 1.0 : -1.0) * w * sign(rng));  // same-kind coupling, A or -C
        diagonal[ia] += w, diagonal[ib] += w;
      }
    }
    for (int c = 0; c < 2; ++c) {  // velocity-pressure coupling, B
      const double b1 = coupling(rng), b2 = coupling(rng);
      lower(3 * a + c, 3 * b + 2, b1);
      if (a != b) lower(3 * b + c, 3 * a + 2, b2);
      diagonal[3 * a + c] += 0.5, diagonal[3 * b + c] += 0.5;
    }
    if (a == b) lower(3 * a, 3 * a + 1, coupling(rng));  // u-v coupling within the node
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      join(node(i, j), node(i, j));
      if (i + 1 < nx) join(node(i, j), node(i + 1, j));
      if (j + 1 < ny) join(node(i, j), node(i, j + 1));
      if (i + 1 < nx && j + 1 < ny) join(node(i, j), node(i + 1, j + 1));
    }
  for (int k = 0; k < n; ++k) {
    const double d = diagonal[k] + 1.0 + weight(rng);
    t.emplace_back(k, k, k % 3 == 2 ? -d : d);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

double relative_difference(const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference) {
  return (x - reference).norm() / reference.norm();
}

// ||K x - b|| / ||b|| with K the symmetric matrix whose lower triangle is a.
double relative_residual(const SparseMatrix& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  const SparseMatrix k = a.selfadjointView<Eigen::Lower>();
  return (k * x - b).norm() / b.norm();
}

// CHOLMOD's simplicial LDL^T (the reference) with a analysed and factorised.
std::unique_ptr<SymmetricSolver> cholmod_factorised(const SparseMatrix& a) {
  auto solver = std::make_unique<SymmetricSolver>(SymmetricBackend::kCholmodLdlt);
  solver->analyze(a);
  solver->factorize(a);
  return solver;
}

// The solution of a factorised SupernodalLdlt for b.
Eigen::MatrixXd solved(const SupernodalLdlt& ldlt, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd x = b;
  ldlt.solve(x);
  return x;
}

// A SupernodalLdlt with a analysed and factorised.
std::unique_ptr<SupernodalLdlt> supernodal_factorised(const SparseMatrix& a) {
  auto ldlt = std::make_unique<SupernodalLdlt>();
  ldlt->analyze(a);
  EXPECT_TRUE(ldlt->factorize(a));
  return ldlt;
}

constexpr int kGrid = 36;  // 3888 unknowns; the top separators are several panels wide

TEST(SupernodalLdlt, SolvesAsCholmodSimplicial) {
  const SparseMatrix a = quasi_definite(kGrid, kGrid, 1);
  const Eigen::VectorXd b = random_rhs(static_cast<int>(a.rows()), 1, 2).col(0);
  const auto reference = cholmod_factorised(a);
  const auto supernodal = supernodal_factorised(a);
  const Eigen::VectorXd x_ref = reference->solve(b), x = solved(*supernodal, b);
  EXPECT_LT(relative_difference(x, x_ref), 1e-12);
  EXPECT_LT(relative_residual(a, x, b), 1e-13);
}

TEST(SupernodalLdlt, SolvesSeveralRightHandSides) {
  const SparseMatrix a = quasi_definite(kGrid, kGrid - 5, 3);
  const Eigen::MatrixXd b = random_rhs(static_cast<int>(a.rows()), 5, 4);
  const auto reference = cholmod_factorised(a);
  const auto supernodal = supernodal_factorised(a);
  const Eigen::MatrixXd x_ref = reference->solve(b), x = solved(*supernodal, b);
  ASSERT_EQ(x.cols(), 5);
  for (int c = 0; c < 5; ++c) {
    EXPECT_LT(relative_difference(x.col(c), x_ref.col(c)), 1e-12) << "column " << c;
    const Eigen::VectorXd one = solved(*supernodal, b.col(c));
    EXPECT_EQ((one - x.col(c)).norm(), 0.0) << "column " << c;
  }
}

TEST(SupernodalLdlt, RefactorisesNewValuesOnThePattern) {
  const SparseMatrix a1 = quasi_definite(kGrid, kGrid, 5), a2 = quasi_definite(kGrid, kGrid, 6);
  ASSERT_EQ(a1.nonZeros(), a2.nonZeros());
  const Eigen::VectorXd b = random_rhs(static_cast<int>(a1.rows()), 1, 7).col(0);
  SupernodalLdlt supernodal;
  supernodal.analyze(a1);
  ASSERT_TRUE(supernodal.factorize(a1));
  const Eigen::VectorXd x1 = solved(supernodal, b);
  ASSERT_TRUE(supernodal.factorize(a2));  // no new analysis
  const Eigen::VectorXd x2 = solved(supernodal, b);
  for (const auto* a : {&a1, &a2}) {
    EXPECT_LT(relative_difference(a == &a1 ? x1 : x2, cholmod_factorised(*a)->solve(b)), 1e-12);
  }
  EXPECT_GT(relative_difference(x2, x1), 1e-2);  // the values did change
}

// The engine refactorises within a step without a new analysis, and the structure's tangent
// leaves out exact zeros, so the pattern can change: more or fewer entries than analysed.
TEST(SupernodalLdlt, FactorisesAPatternOtherThanTheAnalysedOne) {
  const SparseMatrix full = quasi_definite(kGrid, kGrid, 10);
  SparseMatrix pruned = full;
  pruned.prune([](int row, int col, double) { return row == col || (row + 7 * col) % 5 != 0; });
  ASSERT_LT(pruned.nonZeros(), full.nonZeros());
  const Eigen::VectorXd b = random_rhs(static_cast<int>(full.rows()), 1, 11).col(0);
  using Pair = std::pair<const SparseMatrix*, const SparseMatrix*>;  // analysed, then factorised
  for (const auto& [analysed, values] : {Pair{&pruned, &full}, Pair{&full, &pruned}}) {
    SupernodalLdlt supernodal;
    supernodal.analyze(*analysed);
    ASSERT_TRUE(supernodal.factorize(*values));
    const auto reference = cholmod_factorised(*values);
    EXPECT_LT(relative_difference(solved(supernodal, b), reference->solve(b)), 1e-12);
  }
}

// The group of each unknown of the grid matrix: its node (numbered from the last node down).
std::vector<int> node_groups(int nodes) {
  std::vector<int> group(3 * nodes);
  for (int k = 0; k < 3 * nodes; ++k) group[k] = nodes - 1 - k / 3;
  return group;
}

// The analysis on the graph of the nodes orders and eliminates a node's unknowns together: the
// same solution.
TEST(SupernodalLdlt, AnalysisOnTheNodesSolvesAsOnTheUnknowns) {
  const SparseMatrix a = quasi_definite(kGrid, kGrid, 15);
  const Eigen::MatrixXd b = random_rhs(static_cast<int>(a.rows()), 1, 16);
  SupernodalLdlt by_node;
  by_node.analyze(a, node_groups(kGrid * kGrid));
  ASSERT_TRUE(by_node.factorize(a));
  Eigen::MatrixXd x = b;
  by_node.solve(x);
  EXPECT_LT(relative_difference(x, cholmod_factorised(a)->solve(b)), 1e-12);
  EXPECT_LT(relative_residual(a, x, b), 1e-13);
}

// The engine's way: the analysis from the couplings of the grid's nodes (no matrix), the
// entries added in place at block() positions, the factorisation from those values.
TEST(SupernodalLdlt, DirectAssemblyAtBlockPositionsSolvesAsTheMatrix) {
  const int nx = 24, ny = 20;
  const SparseMatrix a = quasi_definite(nx, ny, 17);
  const int n = static_cast<int>(a.rows());
  const std::vector<int> group = node_groups(nx * ny);
  std::vector<std::array<int, 2>> couplings;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int node = j * nx + i;
      if (i + 1 < nx) couplings.push_back({group[3 * node], group[3 * (node + 1)]});
      if (j + 1 < ny) couplings.push_back({group[3 * node], group[3 * (node + nx)]});
      if (i + 1 < nx && j + 1 < ny) couplings.push_back({group[3 * (node + nx + 1)], group[3 * node]});
    }
  SupernodalLdlt direct;
  direct.analyze(n, group, couplings);
  direct.zero_values();
  for (int col = 0; col < n; ++col)
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      const SupernodalLdlt::Block b = direct.block(row - row % 3, col - col % 3);
      direct.values()[b.base + (row % 3) * b.row_step + (col % 3) * b.col_step] += it.value();
    }
  ASSERT_TRUE(direct.factorize_values());
  const Eigen::MatrixXd b = random_rhs(n, 1, 18);
  Eigen::MatrixXd x = b;
  direct.solve(x);
  EXPECT_LT(relative_difference(x, cholmod_factorised(a)->solve(b)), 1e-12);
  EXPECT_THROW(direct.block(3 * (nx * ny - 1), 0), std::logic_error);  // opposite corners never couple
}

// The velocity unknowns of the grid's middle column of nodes (a beam through the water).
std::vector<int> beam_unknowns(int nx, int ny) {
  std::vector<int> last;
  for (int j = 0; j < ny; ++j)
    for (int c = 0; c < 2; ++c) last.push_back(3 * (j * nx + nx / 2) + c);
  return last;
}

// A symmetric change among the unknowns `last` (lower triangle): their diagonal grows, and two
// of them far apart in the grid (no entry of the matrix) are coupled.
std::vector<Eigen::Triplet<double>> change_among(const std::vector<int>& last) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t k = 0; k < last.size(); ++k) t.emplace_back(last[k], last[k], 0.5 + 0.1 * static_cast<double>(k % 7));
  t.emplace_back(std::max(last.front(), last.back()), std::min(last.front(), last.back()), 0.3);
  return t;
}

SparseMatrix matrix_of(const std::vector<Eigen::Triplet<double>>& t, int n) {
  SparseMatrix m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

TEST(SupernodalLdlt, UnknownsOrderedLastTakeAChangeOfTheirBlock) {
  const SparseMatrix a = quasi_definite(kGrid, kGrid, 12);
  const int n = static_cast<int>(a.rows());
  const std::vector<int> last = beam_unknowns(kGrid, kGrid);
  const std::vector<Eigen::Triplet<double>> delta = change_among(last);
  const Eigen::MatrixXd b = random_rhs(n, 2, 13);
  SupernodalLdlt ldlt;
  ldlt.analyze(a, node_groups(kGrid * kGrid), last);
  ASSERT_TRUE(ldlt.factorize(a));
  Eigen::MatrixXd x = b;
  ldlt.solve(x);
  EXPECT_LT(relative_difference(x, cholmod_factorised(a)->solve(b)), 1e-12);

  // The change, twice (each relative to the matrix last factorised), then back to none.
  const SparseMatrix changed = a + matrix_of(delta, n);
  const Eigen::MatrixXd x_changed = cholmod_factorised(changed)->solve(b);
  EXPECT_GT(relative_difference(x_changed, x), 1e-3);
  for (int repeat = 0; repeat < 2; ++repeat) {
    ASSERT_TRUE(ldlt.update_last(delta));
    x = b;
    ldlt.solve(x);
    EXPECT_LT(relative_difference(x, x_changed), 1e-12) << "update " << repeat;
  }
  ASSERT_TRUE(ldlt.update_last({}));
  x = b;
  ldlt.solve(x);
  EXPECT_LT(relative_difference(x, cholmod_factorised(a)->solve(b)), 1e-12);
}

TEST(SupernodalLdlt, RefusesAChangeOutsideTheLastUnknowns) {
  const SparseMatrix a = quasi_definite(20, 20, 14);
  const int n = static_cast<int>(a.rows());
  SupernodalLdlt ldlt;
  ldlt.analyze(a, {}, beam_unknowns(20, 20));
  ASSERT_TRUE(ldlt.factorize(a));
  const std::vector<Eigen::Triplet<double>> corner{{0, 0, 1.0}};  // a velocity unknown of a corner node
  EXPECT_FALSE(ldlt.update_last(corner));
  // Without unknowns ordered last every change is refused.
  SupernodalLdlt plain;
  plain.analyze(a);
  ASSERT_TRUE(plain.factorize(a));
  EXPECT_FALSE(plain.update_last(change_among(beam_unknowns(20, 20))));
  EXPECT_THROW(ldlt.analyze(a, {}, std::vector<int>{n}), std::invalid_argument);
  EXPECT_THROW(ldlt.analyze(a, std::vector<int>(n - 1, 0)), std::invalid_argument);
}

// The smallest systems the engine meets when the water is almost gone: one node (its two
// velocity unknowns in one group, no coupling to any other), also when it is the structure's
// (every unknown ordered last).
TEST(SupernodalLdlt, OneIsolatedGroupAndEveryUnknownLast) {
  SparseMatrix a(2, 2);
  a.insert(0, 0) = 4.0;
  a.insert(1, 1) = -2.0;
  a.makeCompressed();
  for (const std::vector<int>& last : {std::vector<int>{}, std::vector<int>{0, 1}}) {
    SupernodalLdlt ldlt;
    ldlt.analyze(a, std::vector<int>{7, 7}, last);
    ASSERT_TRUE(ldlt.factorize(a));
    const Eigen::MatrixXd x = solved(ldlt, Eigen::Vector2d(1.0, 1.0));
    EXPECT_DOUBLE_EQ(x(0, 0), 0.25);
    EXPECT_DOUBLE_EQ(x(1, 0), -0.5);
  }
}

// Whether SupernodalLdlt factorises a, and whether CHOLMOD's LDL^T does.
std::pair<bool, bool> factorises(const SparseMatrix& a) {
  SupernodalLdlt ldlt;
  ldlt.analyze(a);
  const bool supernodal = ldlt.factorize(a);
  SymmetricSolver cholmod(SymmetricBackend::kCholmodLdlt);
  cholmod.analyze(a);
  try {
    cholmod.factorize(a);
  } catch (const std::runtime_error&) {
    return {supernodal, false};
  }
  return {supernodal, true};
}

TEST(SupernodalLdlt, ZeroPivotIsReported) {
  const std::pair<bool, bool> neither{false, false};
  // [1 1; 1 1]: the second pivot is exactly 0 after elimination, in either order.
  SparseMatrix singular(2, 2);
  singular.insert(0, 0) = 1.0;
  singular.insert(1, 0) = 1.0;
  singular.insert(1, 1) = 1.0;
  singular.makeCompressed();
  EXPECT_EQ(factorises(singular), neither);

  // A pressure unknown of the grid matrix whose row is zero (entries kept in the pattern).
  SparseMatrix a = quasi_definite(20, 20, 8);
  EXPECT_EQ(factorises(a), std::make_pair(true, true));
  const int dead = 3 * 210 + 2;
  for (int j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it)
      if (it.row() == dead || it.col() == dead) it.valueRef() = 0.0;
  EXPECT_EQ(factorises(a), neither);

  // A non-finite entry.
  SparseMatrix b = quasi_definite(20, 20, 9);
  b.coeffRef(100, 100) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(factorises(b).first);
}

}  // namespace
}  // namespace pfem
