#include "engine/solve/fractional_operators.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "engine/base/assert.h"
#include "engine/solve/gmres.h"

namespace pfem {

namespace {
// GMRES on the step's system (solve_accelerated): a restart long enough for the slowest
// contraction seen (0.45 a step of the three steps alone), and a cap; an outer iteration whose
// solve stops at the cap still reduces the residual, and the step's own tests decide.
constexpr int kRestart = 30, kMaxIterations = 60;

// G^T x, column by column of G. (Eigen's product with G.transpose(), a row-major expression,
// runs an OpenMP loop whose threads spin: three quarters of the step's time on a busy machine.)
Eigen::MatrixXd transpose_product(const SparseMatrix& g, const Eigen::MatrixXd& x) {
  Eigen::MatrixXd y(g.cols(), x.cols());
  for (Eigen::Index c = 0; c < x.cols(); ++c)
    for (int q = 0; q < g.outerSize(); ++q) {
      double sum = 0.0;
      for (SparseMatrix::InnerIterator it(g, q); it; ++it) sum += it.value() * x(it.row(), c);
      y(q, c) = sum;
    }
  return y;
}
}  // namespace

void FractionalOperators::build(const mesh::FluidMesh& mesh, const StepNumbering& num,
                                std::span<const fluid::MiniMatrices> mats, std::span<const fluid::Vec8> lumped,
                                const StepStructure& structure, double dt, bool analyze) {
  num_ = &num, dt_ = dt;
  if (analyze) predictor_analyzed_ = false;
  assemble_mass(mesh, mats, lumped, structure);
  assemble_poisson(mesh, mats, analyze);
  assemble_predictor(mesh, mats, !predictor_analyzed_);
}

void FractionalOperators::assemble_mass(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats,
                                        std::span<const fluid::Vec8> lumped, const StepStructure& structure) {
  const int nv = num_->node_velocities;
  first_structure_ = nv;
  for (const int d : num_->structure)
    if (d >= 0) first_structure_ = std::min(first_structure_, d);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(nv);
  // A beam rider's lumped mass, shared out to its segment's ends (structure unknowns) by their
  // weights: (row, col, value).
  std::vector<Eigen::Triplet<double>> shared;
  bubble_block_.resize(mesh.triangles.size());
  bubble_inverse_.resize(mesh.triangles.size());
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    const auto& tri = mesh.triangles[e];
    for (int r = 0; r < 6; ++r) {
      const VelocityTerms t = num_->velocity_terms(tri[r / 2], r % 2);
      const double m = lumped[e](r) / dt_;
      if (!num_->is_rider(tri[r / 2])) {
        if (t.u[0] >= 0) mass[t.u[0]] += m;
        continue;
      }
      put_term_pairs(t, t, m, [&shared](int row, int col, double value) { shared.emplace_back(row, col, value); });
    }
    Eigen::Matrix2d& bubble = bubble_block_[e];
    bubble = mats[e].K.block<2, 2>(6, 6);
    bubble(0, 0) += lumped[e](6) / dt_, bubble(1, 1) += lumped[e](7) / dt_;
    bubble_inverse_[e] = bubble.inverse();
  }
  node_mass_ = mass.head(first_structure_);
  const int ns = nv - first_structure_;
  structure_matrix_ = mass.tail(ns).asDiagonal();
  for (const auto& s : shared) {
    PFEM_ASSERT(s.row() >= first_structure_ && s.col() >= first_structure_, "a rider's ends are the structure's");
    structure_matrix_(s.row() - first_structure_, s.col() - first_structure_) += s.value();
  }
  structure.add_tangent([this](int row, int col, double value) {
    structure_matrix_(row - first_structure_, col - first_structure_) += value;
  });
  if (ns == 0) return;
  structure_block_.compute(structure_matrix_);
  if (structure_block_.info() != Eigen::Success)
    throw std::runtime_error("the structure's block of the fractional step could not be factorised");
}

void FractionalOperators::assemble_poisson(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats,
                                           bool analyze) {
  const int np = num_->pressures, ns = num_->node_velocities - first_structure_;
  std::vector<Eigen::Triplet<double>> g, z, gs;         // gs: G's structure rows, in coupled pressures
  std::vector<int> coupled(np, -1), coupled_pressures;  // pressures that act on the structure
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    const auto& m = mats[e];
    const int b = num_->bubble(static_cast<int>(e));
    const auto& tri = mesh.triangles[e];
    for (int a = 0; a < 3; ++a) {
      const int q = num_->corner_p[e][a];
      for (int r = 0; r < 6; ++r) {
        const VelocityTerms t = num_->velocity_terms(tri[r / 2], r % 2);
        for (int i = 0; i < 2; ++i) {
          const int d = t.u[i];
          if (d < 0) continue;
          const double value = t.w[i] * m.G(r, a);
          g.emplace_back(d, q, value);
          if (d < first_structure_) {
            z.emplace_back(d, q, value / node_mass_[d]);
            continue;
          }
          if (coupled[q] < 0) coupled[q] = static_cast<int>(coupled_pressures.size()), coupled_pressures.push_back(q);
          gs.emplace_back(d - first_structure_, coupled[q], value);
        }
      }
      const Eigen::Vector2d gb = m.G.block<2, 1>(6, a), zb = bubble_inverse_[e] * gb;
      g.emplace_back(b, q, gb(0)), g.emplace_back(b + 1, q, gb(1));
      z.emplace_back(b, q, zb(0)), z.emplace_back(b + 1, q, zb(1));
    }
  }
  if (!coupled_pressures.empty()) {  // the structure's exact share: its block of A solved for G's rows
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(ns, static_cast<Eigen::Index>(coupled_pressures.size()));
    for (const auto& t : gs) rows(t.row(), t.col()) += t.value();
    const Eigen::MatrixXd solved = structure_block_.solve(rows);
    for (int i = 0; i < ns; ++i)
      for (std::size_t j = 0; j < coupled_pressures.size(); ++j)
        z.emplace_back(first_structure_ + i, coupled_pressures[j], solved(i, static_cast<Eigen::Index>(j)));
  }
  g_.resize(num_->velocities, np);
  g_.setFromTriplets(g.begin(), g.end());
  z_.resize(num_->velocities, np);
  z_.setFromTriplets(z.begin(), z.end());
  double g_sum = 0.0;
  for (int k = 0; k < g_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(g_, k); it; ++it)
      if (it.row() < first_structure_) g_sum += std::abs(it.value());
  row_scale_ = g_sum > 0.0 ? node_mass_.sum() / g_sum : 1.0;
  if (np == 0) return;
  SparseMatrix poisson = SparseMatrix(g_.transpose()) * z_;
  poisson.makeCompressed();
  if (analyze) poisson_.analyze(poisson);
  if (!poisson_.factorize(poisson)) throw std::runtime_error("the pressure Poisson matrix could not be factorised");
}

void FractionalOperators::assemble_predictor(const mesh::FluidMesh& mesh, std::span<const fluid::MiniMatrices> mats,
                                             bool analyze) {
  const int nv = num_->node_velocities;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(36 * mesh.triangles.size() + nv);
  for (int d = 0; d < first_structure_; ++d) t.emplace_back(d, d, node_mass_[d]);
  for (Eigen::Index c = 0; c < structure_matrix_.cols(); ++c)  // whole, for a pattern that stays
    for (Eigen::Index r = 0; r < structure_matrix_.rows(); ++r)
      t.emplace_back(first_structure_ + r, first_structure_ + c, structure_matrix_(r, c));
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    std::array<VelocityTerms, 6> terms;
    for (int r = 0; r < 6; ++r) terms[r] = num_->velocity_terms(mesh.triangles[e][r / 2], r % 2);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        put_term_pairs(terms[r], terms[c], mats[e].K(r, c),
                       [&t](int row, int col, double value) { t.emplace_back(row, col, value); });
  }
  predictor_matrix_.resize(nv, nv);
  predictor_matrix_.setFromTriplets(t.begin(), t.end());
  if (nv == 0) return;
  predictor_matrix_.makeCompressed();
  if (analyze) predictor_.analyze(predictor_matrix_);
  predictor_analyzed_ = true;
  if (!predictor_.factorize(predictor_matrix_))
    throw std::runtime_error("the velocity predictor's matrix could not be factorised");
}

void FractionalOperators::solve(const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp, Eigen::MatrixXd& dv,
                                Eigen::MatrixXd& dp) const {
  const int nv = num_->node_velocities;
  Eigen::MatrixXd predicted(rv.rows(), rv.cols());  // step 1
  predicted.topRows(nv) = rv.topRows(nv);
  if (nv > 0) predictor_.solve(predicted.topRows(nv));
  for (std::size_t e = 0; e < bubble_inverse_.size(); ++e) {
    const int b = num_->bubble(static_cast<int>(e));
    predicted.middleRows<2>(b) = bubble_inverse_[e] * rv.middleRows<2>(b);
  }
  if (num_->pressures == 0) {
    dp.setZero(0, rv.cols());
    dv = predicted;
    return;
  }
  dp = rp - transpose_product(g_, predicted);  // step 2
  poisson_.solve(dp);
  dv = predicted + z_ * dp;  // step 3
}

Eigen::VectorXd FractionalOperators::scaled_product(const Eigen::VectorXd& x) const {
  const int nv = num_->node_velocities, nvel = num_->velocities;
  const Eigen::VectorXd v = x.head(nvel);
  Eigen::VectorXd y(x.size());
  y.head(nvel) = -(g_ * x.tail(num_->pressures));
  y.head(nv) += predictor_matrix_ * v.head(nv);
  for (std::size_t e = 0; e < bubble_block_.size(); ++e) {
    const int b = num_->bubble(static_cast<int>(e));
    y.segment<2>(b) += bubble_block_[e] * v.segment<2>(b);
  }
  y.tail(num_->pressures) = row_scale_ * transpose_product(g_, v);
  return y;
}

void FractionalOperators::solve_accelerated(const Eigen::VectorXd& rv, const Eigen::VectorXd& rp, double tolerance,
                                            Eigen::VectorXd& dv, Eigen::VectorXd& dp) const {
  const int nvel = num_->velocities, np = num_->pressures;
  const LinearOperator product = [this](const Eigen::VectorXd& x) { return scaled_product(x); };
  const LinearOperator three_steps = [&](const Eigen::VectorXd& r) {
    Eigen::MatrixXd v, p;
    solve(r.head(nvel), r.tail(np) / row_scale_, v, p);
    Eigen::VectorXd x(r.size());
    x << v.col(0), p.col(0);
    return x;
  };
  Eigen::VectorXd b(nvel + np), x;
  b << rv, row_scale_ * rp;
  gmres(product, three_steps, b, x, tolerance, kRestart, kMaxIterations);
  dv = x.head(nvel), dp = x.tail(np);
}

}  // namespace pfem
