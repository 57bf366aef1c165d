#include "engine/solve/fluid_step.h"

#include <Eigen/LU>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <string>

#include "engine/solve/step_commit.h"

namespace pfem {

namespace {
using Clock = std::chrono::steady_clock;
// Round-off allowance: a residual below kRoundoff times the sum of its terms' magnitudes is noise.
// It covers the rounding of the sums and that of the solved velocities they multiply: with
// 64 eps, residuals stalled at 1.1-2.8 times the allowance in the yielding-obstacle impact, and
// whether such a step failed (and was halved) became a round-off decision that perturbed
// finite-difference runs took differently.
constexpr double kRoundoff = 1024 * std::numeric_limits<double>::epsilon();
constexpr double kStructureTangentChange = 1e-3;  // see update_structure_tangent
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

void UnifiedStep::element_terms(const mesh::FluidMesh& mesh, const StepSettings& s) {
  const int ne = static_cast<int>(mesh.triangles.size());
  geometries_.resize(ne);
  element_residuals_.resize(ne);
  matrices_current_ = false;
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    std::array<double, 3> x, y, xn, yn;
    for (int a = 0; a < 3; ++a) {
      const int i = mesh.triangles[e][a];
      xn[a] = xn_[i], yn[a] = yn_[i];
      x[a] = xn_[i] + s.dt * velocity_x(i);
      y[a] = yn_[i] + s.dt * velocity_y(i);
    }
    geometries_[e] = fluid::triangle_geometry(x, y);
    fluid::continuity_at_midpoint(geometries_[e], xn, yn);
    element_residuals_[e] =
        fluid::element_residual(geometries_[e], s.fluid, s.thickness, s.gx, s.gy, s.dt, element_state(mesh, e));
  }
}

void UnifiedStep::element_matrices(const StepSettings& s) {
  if (matrices_current_) return;
  const int ne = static_cast<int>(geometries_.size());
  mats_.resize(ne);
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) fluid::mini_matrices(geometries_[e], s.fluid, s.thickness, s.gx, s.gy, mats_[e]);
  matrices_current_ = true;
}

fluid::ElementState UnifiedStep::element_state(const mesh::FluidMesh& mesh, int e) const {
  fluid::ElementState st;
  const auto& tri = mesh.triangles[e];
  for (int a = 0; a < 3; ++a) {
    const int i = tri[a], q = num_.corner_p[e][a];
    st.v(2 * a) = velocity_x(i);
    st.v(2 * a + 1) = velocity_y(i);
    st.vn(2 * a) = vxn_[i];
    st.vn(2 * a + 1) = vyn_[i];
    st.p(a) = p_[q];
    st.pn(a) = pn_[q];
  }
  const int b = num_.bubble(e);
  st.v(6) = v_[b], st.v(7) = v_[b + 1];
  st.vn.tail<2>() = vbn_[e];
  return st;
}

double UnifiedStep::wall_velocity(int i, int c) const {
  return wall_velocity_.empty() ? 0.0 : wall_velocity_[2 * static_cast<std::size_t>(i) + c];
}
double UnifiedStep::velocity_x(int i) const { return num_.vx[i] >= 0 ? v_[num_.vx[i]] : wall_velocity(i, 0); }
double UnifiedStep::velocity_y(int i) const { return num_.vy[i] >= 0 ? v_[num_.vy[i]] : wall_velocity(i, 1); }

void UnifiedStep::residuals(const mesh::FluidMesh& mesh) {
  rv_.setZero(num_.velocities);
  rp_.setZero(num_.pressures);
  rp_abs_.setZero(num_.pressures);
  mp_.setZero(num_.pressures);
  const int ne = static_cast<int>(mesh.triangles.size());
  for (int e = 0; e < ne; ++e) {
    const auto& r = element_residuals_[e];
    const auto& tri = mesh.triangles[e];
    for (int a = 0; a < 3; ++a) {
      const int i = tri[a], dx = num_.vx[i], dy = num_.vy[i], q = num_.corner_p[e][a];
      if (dx >= 0) rv_[dx] += r.rv(2 * a);
      if (dy >= 0) rv_[dy] += r.rv(2 * a + 1);
      rp_[q] += r.rp(a), rp_abs_[q] += r.rp_abs(a), mp_[q] += r.mp;
      if (volume_.dilatation != 0.0) {
        const double source = volume_.corner_source(e);  // the dilatation's share of the corner
        rp_[q] += source, rp_abs_[q] += std::abs(source);
      }
    }
    const int b = num_.bubble(e);
    rv_[b] += r.rv(6), rv_[b + 1] += r.rv(7);
  }
}

void UnifiedStep::factorize_global_bubble(const mesh::FluidMesh& mesh, const StepSettings& s, bool analyze) {
  element_matrices(s);
  const int ne = static_cast<int>(mesh.triangles.size());
  std::vector<Eigen::Triplet<double>> kt, gt;
  kt.reserve(64 * ne);
  gt.reserve(24 * ne);
  const double inv_dt = 1.0 / s.dt;
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats_[e];
    const auto& tri = mesh.triangles[e];
    const auto dof = num_.element_velocities(tri, e);
    for (int r = 0; r < 8; ++r) {
      if (dof[r] < 0) continue;
      for (int c = 0; c < 8; ++c)
        if (dof[c] >= 0) kt.emplace_back(dof[r], dof[c], m.M(r, c) * inv_dt + m.K(r, c));
      for (int a = 0; a < 3; ++a) gt.emplace_back(dof[r], num_.corner_p[e][a], m.G(r, a));
    }
  }
  structure_.add_tangent([&kt](int row, int col, double value) { kt.emplace_back(row, col, value); });
  SparseMatrix kvv(num_.velocities, num_.velocities);
  kvv.setFromTriplets(kt.begin(), kt.end());
  g_.resize(num_.velocities, num_.pressures);
  g_.setFromTriplets(gt.begin(), gt.end());
  factor_mp_ = mp_;
  const Eigen::VectorXd d = s.dt * mp_.cwiseInverse();
  matrix_ = kvv + SparseMatrix(g_ * d.asDiagonal() * g_.transpose());
  if (analyze) global_solver_.analyze(matrix_);
  global_solver_.factorize(matrix_);
}

void UnifiedStep::correct_global_bubble(const StepSettings& s) {
  const Eigen::VectorXd dp_star = (s.dt * rp_.array() / factor_mp_.array()).matrix();
  const Eigen::VectorXd dv = global_solver_.solve(Eigen::VectorXd(rv_ + g_ * dp_star));
  v_ += dv;
  p_ += dp_star - (s.dt * (g_.transpose() * dv).array() / factor_mp_.array()).matrix();
}

void UnifiedStep::element_jacobian(int e, const StepSettings& s, const fluid::GeometricDerivatives* geometric,
                                   fluid::Mat8& a, Eigen::Matrix<double, 3, 6>& q) const {
  const auto& m = mats_[e];
  // Element Jacobian -d(rv, rp)/d(v, p): [a -G; Q Gc_b^T Mp/dt] with a = M/dt + K - dt drv/dx and
  // Q = Gc_c^T - dt/2 drp/dx (the coordinates move with the corner velocities, x = x_n + dt v,
  // and the mass balance's midpoint with half of them). The Newton matrix takes G for Gc and no
  // drv/dx, drp/dx: symmetric, and off the Jacobian by terms of order dt |grad v|.
  const fluid::Mat83& gc = geometric ? m.Gc : m.G;
  a = m.M * (1.0 / s.dt) + m.K;
  q = gc.block<6, 3>(0, 0).transpose();
  if (geometric) {
    a.leftCols<6>() -= s.dt * geometric->drv_dx;
    q -= 0.5 * s.dt * geometric->drp_dx;
  }
}

void UnifiedStep::condense_element(int e, const StepSettings& s, const fluid::GeometricDerivatives* geometric,
                                   BubbleCondensation& b, CondensedElement& k) const {
  const auto& m = mats_[e];
  const fluid::Mat83& gc = geometric ? m.Gc : m.G;
  fluid::Mat8 a;
  Eigen::Matrix<double, 3, 6> q;
  element_jacobian(e, s, geometric, a, q);
  b.inv_bb = a.block<2, 2>(6, 6).inverse();
  b.a_bc = a.block<2, 6>(6, 0);
  b.a_cb = a.block<6, 2>(0, 6);
  b.g_b = m.G.block<2, 3>(6, 0);
  b.gc_b = gc.block<2, 3>(6, 0);
  // Element Schur complements with dvb = Abb^-1 (r_b - A_bc dvc + G_b dp):
  // A' = A_cc - A_cb Abb^-1 A_bc, G' = G_c - A_cb Abb^-1 G_b (velocity rows),
  // Q' = Q - Gc_b^T Abb^-1 A_bc, C = Gc_b^T Abb^-1 G_b (pressure rows, negated).
  const Eigen::Matrix<double, 6, 2> acb_inv = b.a_cb * b.inv_bb;
  const Eigen::Matrix<double, 3, 2> gcb_inv = b.gc_b.transpose() * b.inv_bb;
  k.topLeftCorner<6, 6>() = a.block<6, 6>(0, 0) - acb_inv * b.a_bc;
  k.topRightCorner<6, 3>() = acb_inv * b.g_b - m.G.block<6, 3>(0, 0);
  k.bottomLeftCorner<3, 6>() = gcb_inv * b.a_bc - q;
  k.bottomRightCorner<3, 3>() = -(gcb_inv * b.g_b);
}

namespace {
// The corner pairs of a triangle whose blocks the symmetric Newton matrix needs once each: rows
// of the first corner, columns of the second.
constexpr std::array<std::array<int, 2>, 6> kCornerPairs{{{0, 0}, {1, 1}, {2, 2}, {1, 0}, {2, 0}, {2, 1}}};
}  // namespace

void UnifiedStep::analyze_condensed(const mesh::FluidMesh& mesh, const StepSettings& s) {
  // The unknowns of a node (velocities, pressure, a structure node's rotation) as one group,
  // coupled to the nodes it shares a triangle or a beam element with.
  const int n = num_.node_velocities + num_.pressures;
  std::vector<int> node_of(n, -1), structure_unknowns;
  for (std::size_t i = 0; i < num_.vx.size(); ++i) {
    if (num_.vx[i] >= 0) node_of[num_.vx[i]] = static_cast<int>(i);
    if (num_.vy[i] >= 0) node_of[num_.vy[i]] = static_cast<int>(i);
  }
  for (int q = 0; q < num_.pressures; ++q) node_of[num_.node_velocities + q] = num_.pressure_node[q];
  for (std::size_t j = 0; j < num_.structure.size(); ++j)
    if (const int d = num_.structure[j]; d >= 0) node_of[d] = s.structure.node[j / 3], structure_unknowns.push_back(d);
  std::vector<std::array<int, 2>> couplings;
  couplings.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) couplings.push_back({tri[0], tri[1]}), couplings.push_back({tri[1], tri[2]}),
                                         couplings.push_back({tri[2], tri[0]});
  if (const auto* model = s.structure.model)
    for (int e = 0; e < model->num_elements(); ++e) {
      const auto [i, j] = model->element(e).nodes();
      couplings.push_back({s.structure.node[i], s.structure.node[j]});
    }
  condensed_solver_.analyze(n, node_of, couplings, structure_unknowns);

  // Each unknown's rank among its node's unknowns, the first unknown of each node, and where
  // each triangle's blocks and each pressure's diagonal go in the factor.
  slot_.resize(n);
  std::vector<int> first(num_.vx.size(), -1), count(num_.vx.size(), 0);
  for (int u = 0; u < n; ++u) {
    const int i = node_of[u];
    if (first[i] < 0) first[i] = u;
    slot_[u] = count[i]++;
  }
  const int ne = static_cast<int>(mesh.triangles.size());
  element_blocks_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const auto& tri = mesh.triangles[e];
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const int row0 = first[tri[kCornerPairs[p][0]]], col0 = first[tri[kCornerPairs[p][1]]];
      element_blocks_[e][p] = row0 >= 0 && col0 >= 0 ? condensed_solver_.block(row0, col0) : SupernodalLdlt::Block{-1, 0, 0};
    }
  }
  pressure_diagonal_.resize(num_.pressures);
  for (int q = 0; q < num_.pressures; ++q) {
    const int u = num_.node_velocities + q;
    pressure_diagonal_[q] = condensed_solver_.block(u, u).base;
  }
  lu_layout_ready_ = false;
  analyzed_ = true;
  first_of_node_ = std::move(first);
}

void UnifiedStep::jacobian_layout(const mesh::FluidMesh& mesh) {
  // The LU takes the LDL^T's analysis, and each triangle's nine corner-pair blocks (both orders)
  // from the six the LDL^T has (a pair's reverse is the same place with the steps exchanged).
  const int ne = static_cast<int>(mesh.triangles.size());
  jacobian_lu_.analyze_as(condensed_solver_);
  lu_blocks_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const auto& tri = mesh.triangles[e];
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const SupernodalLdlt::Block& b = element_blocks_[e][p];
      const int a = kCornerPairs[p][0], c = kCornerPairs[p][1];
      if (b.base < 0) {
        lu_blocks_[e][3 * a + c] = lu_blocks_[e][3 * c + a] = SupernodalLu::Block{-1, 0, 0, false};
        continue;
      }
      const int row0 = first_of_node_[tri[a]], col0 = first_of_node_[tri[c]];
      lu_blocks_[e][3 * a + c] = jacobian_lu_.block(row0, col0, b.base, b.row_step, b.col_step);
      if (a != c) lu_blocks_[e][3 * c + a] = jacobian_lu_.block(col0, row0, b.base, b.col_step, b.row_step);
    }
  }
  lu_layout_ready_ = true;
}

void UnifiedStep::jacobian_elements(const mesh::FluidMesh& mesh, const StepSettings& s, bool geometric_terms) {
  element_matrices(s);
  const int ne = static_cast<int>(mesh.triangles.size());
  geometric_.resize(ne);
  jacobian_bubbles_.resize(ne);
  jacobian_elements_.resize(ne);
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    if (geometric_terms) {
      fluid::geometric_derivatives(geometries_[e], mats_[e], s.fluid.mu, s.thickness, s.dt, element_state(mesh, e),
                                   geometric_[e]);
    } else {
      geometric_[e].drv_dx.setZero();
      geometric_[e].drp_dx.setZero();
    }
    condense_element(e, s, &geometric_[e], jacobian_bubbles_[e], jacobian_elements_[e]);
  }
}

void UnifiedStep::factorize_jacobian(const mesh::FluidMesh& mesh, const StepSettings& s) {
  // The elements' condensed blocks added straight into the LU's storage, as the Newton matrix's
  // are into the LDL^T's.
  if (!lu_layout_ready_) jacobian_layout(mesh);
  jacobian_lu_.zero_values();
  const int ne = static_cast<int>(mesh.triangles.size());
  for (int e = 0; e < ne; ++e) {
    const CondensedElement& k = jacobian_elements_[e];
    const std::array<int, 9> u = num_.condensed_unknowns(mesh.triangles[e], e);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const SupernodalLu::Block& blk = lu_blocks_[e][3 * a + b];
        if (blk.base < 0) continue;
        double* values = jacobian_lu_.values(blk.upper);
        for (const int r : {2 * a, 2 * a + 1, 6 + a}) {
          if (u[r] < 0) continue;
          const long row = blk.base + slot_[u[r]] * blk.row_step;
          for (const int c : {2 * b, 2 * b + 1, 6 + b})
            if (u[c] >= 0) values[row + slot_[u[c]] * blk.col_step] += k(r, c);
        }
      }
  }
  for (int q = 0; q < num_.pressures; ++q) {
    const int u = num_.node_velocities + q;
    const SupernodalLu::Block blk = jacobian_lu_.block(u, u, pressure_diagonal_[q], 1, 1);
    jacobian_lu_.values(blk.upper)[blk.base] -= mp_[q] / s.dt;
  }
  structure_.add_tangent([this](int row, int col, double value) {
    const SupernodalLu::Block blk = jacobian_lu_.block(row, col);
    jacobian_lu_.values(blk.upper)[blk.base] += value;
  });
  if (!jacobian_lu_.factorize_values()) throw StepFailure("the Jacobian could not be factorised (non-finite pivot)");
}

Eigen::VectorXd UnifiedStep::jacobian_product(const mesh::FluidMesh& mesh, const StepSettings& s,
                                              const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (std::size_t e = 0; e < jacobian_elements_.size(); ++e) {
    const std::array<int, 9> u = num_.condensed_unknowns(mesh.triangles[e], static_cast<int>(e));
    Eigen::Matrix<double, 9, 1> xe;
    for (int c = 0; c < 9; ++c) xe(c) = u[c] >= 0 ? x[u[c]] : 0.0;
    const Eigen::Matrix<double, 9, 1> ye = jacobian_elements_[e] * xe;
    for (int r = 0; r < 9; ++r)
      if (u[r] >= 0) y[u[r]] += ye(r);
  }
  for (int q = 0; q < num_.pressures; ++q) {
    const int u = num_.node_velocities + q;
    y[u] -= mp_[q] / s.dt * x[u];
  }
  structure_.add_tangent([&](int row, int col, double value) { y[row] += value * x[col]; });
  return y;
}

void UnifiedStep::factorize_condensed_bubble(const mesh::FluidMesh& mesh, const StepSettings& s, bool analyze) {
  // The symmetric matrix is added straight into the factor's storage, a triangle's blocks at
  // the places found by the analysis: no triplets to sort, no matrix to build.
  element_matrices(s);
  if (analyze) analyze_condensed(mesh, s);
  condensed_solver_.zero_values();
  double* lx = condensed_solver_.values();
  const int ne = static_cast<int>(mesh.triangles.size());
  bubbles_.resize(ne);
  CondensedElement k;
  for (int e = 0; e < ne; ++e) {
    condense_element(e, s, nullptr, bubbles_[e], k);
    const std::array<int, 9> u = num_.condensed_unknowns(mesh.triangles[e], e);
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const SupernodalLdlt::Block& b = element_blocks_[e][p];
      if (b.base < 0) continue;
      const int rc = kCornerPairs[p][0], cc = kCornerPairs[p][1];
      for (const int r : {2 * rc, 2 * rc + 1, 6 + rc}) {
        if (u[r] < 0) continue;
        const long row = b.base + slot_[u[r]] * b.row_step;
        for (const int c : {2 * cc, 2 * cc + 1, 6 + cc})
          if (u[c] >= 0) lx[row + slot_[u[c]] * b.col_step] += k(r, c);
      }
    }
  }
  for (int q = 0; q < num_.pressures; ++q) lx[pressure_diagonal_[q]] -= mp_[q] / s.dt;
  factor_structure_ = structure_.tangent_lower();
  structure_in_factor_ = factor_structure_;
  for (const auto& t : factor_structure_) lx[condensed_solver_.block(t.row(), t.col()).base] += t.value();
  if (!condensed_solver_.factorize_values())
    throw StepFailure("the Newton matrix could not be factorised (zero or wrong-signed pivot)");
}

bool UnifiedStep::update_structure_tangent() {
  std::vector<Eigen::Triplet<double>> current = structure_.tangent_lower();
  // The change from the tangent the factor holds, relative to the tangent (Frobenius norms over
  // the structure's block, its unknowns numbered consecutively). Below kStructureTangentChange
  // (an elastic beam's geometric stiffness between iterates: 1e-12 to 1e-5 on the sloshing beam)
  // the trailing block's refactorisation costs more than it saves; a yielding fiber changes it
  // by 1e-2 to 0.2 (the yielding obstacle: the same iterations at 1e-3 as at 0, more at 1e-2).
  int first = std::numeric_limits<int>::max(), last = -1;
  for (const int d : num_.structure)
    if (d >= 0) first = std::min(first, d), last = std::max(last, d);
  if (last < 0) return true;  // every structure dof supported
  const int m = last - first + 1;
  Eigen::MatrixXd change = Eigen::MatrixXd::Zero(m, m);
  for (const auto& e : current) change(e.row() - first, e.col() - first) += e.value();
  const Eigen::MatrixXd held = change;
  for (const auto& e : structure_in_factor_) change(e.row() - first, e.col() - first) -= e.value();
  if (change.norm() <= kStructureTangentChange * held.norm()) return true;
  std::vector<Eigen::Triplet<double>> delta = current;
  for (const auto& e : factor_structure_) delta.emplace_back(e.row(), e.col(), -e.value());
  structure_in_factor_ = std::move(current);
  return condensed_solver_.update_last(delta);
}

void UnifiedStep::solve_condensed(const mesh::FluidMesh& mesh, const std::vector<BubbleCondensation>& bubbles,
                                  const CondensedSolve& solve, const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp,
                                  Eigen::MatrixXd& dv, Eigen::MatrixXd& dp) const {
  // Column by column with fixed-size element blocks (small dynamic products cost more than
  // their arithmetic). Right-hand side with the bubble rows condensed in; pressure rows negated.
  const long cols = rv.cols();
  const int ne = static_cast<int>(mesh.triangles.size());
  Eigen::MatrixXd rhs(num_.node_velocities + num_.pressures, cols);
  rhs.topRows(num_.node_velocities) = rv.topRows(num_.node_velocities);
  rhs.bottomRows(num_.pressures) = -rp;
  Eigen::MatrixXd z(2 * ne, cols);  // Abb^-1 r_b, two rows per element
  for (long c = 0; c < cols; ++c) {
    for (int e = 0; e < ne; ++e) {
      const auto& b = bubbles[e];
      const Eigen::Vector2d ze = b.inv_bb * rv.col(c).segment<2>(num_.bubble(e));
      z.col(c).segment<2>(2 * e) = ze;
      const auto& tri = mesh.triangles[e];
      for (int k = 0; k < 3; ++k) {
        if (const int dx = num_.vx[tri[k]]; dx >= 0) rhs(dx, c) -= b.a_cb.row(2 * k).dot(ze);
        if (const int dy = num_.vy[tri[k]]; dy >= 0) rhs(dy, c) -= b.a_cb.row(2 * k + 1).dot(ze);
        rhs(num_.node_velocities + num_.corner_p[e][k], c) += b.gc_b.col(k).dot(ze);
      }
    }
  }
  const Eigen::MatrixXd x = solve(rhs);
  dv.resize(num_.velocities, cols);
  dv.topRows(num_.node_velocities) = x.topRows(num_.node_velocities);
  dp = x.bottomRows(num_.pressures);
  // Recover each bubble: dvb = Abb^-1 (r_b - A_bc dvc + G_b dp).
  for (long c = 0; c < cols; ++c) {
    for (int e = 0; e < ne; ++e) {
      const auto& b = bubbles[e];
      const auto& tri = mesh.triangles[e];
      Eigen::Matrix<double, 6, 1> dvc;
      Eigen::Vector3d dpe;
      for (int k = 0; k < 3; ++k) {
        const int dx = num_.vx[tri[k]], dy = num_.vy[tri[k]];
        dvc(2 * k) = dx >= 0 ? x(dx, c) : 0.0;
        dvc(2 * k + 1) = dy >= 0 ? x(dy, c) : 0.0;
        dpe(k) = x(num_.node_velocities + num_.corner_p[e][k], c);
      }
      dv.col(c).segment<2>(num_.bubble(e)) = z.col(c).segment<2>(2 * e) + b.inv_bb * (b.g_b * dpe - b.a_bc * dvc);
    }
  }
}

void UnifiedStep::correct_condensed_bubble(const mesh::FluidMesh& mesh) {
  Eigen::MatrixXd dv, dp;
  const auto solve = [this](const Eigen::MatrixXd& b) {
    Eigen::MatrixXd x = b;
    condensed_solver_.solve(x);
    return x;
  };
  solve_condensed(mesh, bubbles_, solve, rv_, rp_, dv, dp);
  v_ += dv.col(0);
  p_ += dp.col(0);
}

bool UnifiedStep::any_inverted() const {
  return std::any_of(geometries_.begin(), geometries_.end(), [](const fluid::TriangleGeometry& g) { return !(g.A > 0.0); });
}

void UnifiedStep::check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  // A particle whose move crosses a wall or beam hits it (advance() takes it out): typically a
  // splash particle reaching the floor or the obstacle's back, in free-surface triangles that
  // have no pressure to stop it, or in none on that edge at all (the alpha test drops the
  // sliver it would make). A shorter step only brings it closer.
  std::vector<double> x1(nodes.size()), y1(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    x1[i] = xn_[i] + s.dt * velocity_x(static_cast<int>(i));
    y1[i] = yn_[i] + s.dt * velocity_y(static_cast<int>(i));
  }
  const StepEnds ends{xn_, yn_, x1, y1};
  walls_ = wall_pieces(s.walls, ends);
  hits_wall_ = particles_crossing_walls(mesh.triangles, nodes.kind, ends, walls_);
  // An inverted triangle is no solution of the step (retried shorter), unless a particle of it
  // crossed a wall: that move is not made.
  for (std::size_t e = 0; e < geometries_.size(); ++e) {
    const auto& t = mesh.triangles[e];
    if (!(geometries_[e].A > 0.0) && !hits_wall_[t[0]] && !hits_wall_[t[1]] && !hits_wall_[t[2]])
      throw StepFailure("a triangle inverted within the step");
  }
}

void UnifiedStep::initial_iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  // The velocities, pressures and bubbles of t_n.
  v_.setZero(num_.velocities);
  bubble_history_.restore(mesh.triangles, static_cast<int>(s.sensitivity.size()), vbn_, dvbn_);
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) v_.segment<2>(num_.bubble(e)) = vbn_[e];
  gather_velocities(num_, nodes, v_);
  p_ = pn_ = gather_pressures(num_, mesh, nodes);

  structure_.begin(s.structure, num_, s.dt, s.gx, s.gy, nodes, v_);
}

double UnifiedStep::relative_residual(const StepSettings& s) const {
  // The velocity residual against the step's force scale; the pressure residual of each node
  // (its mass balance) against the pressure change it would cause (dt rp / Mp) relative to the
  // pressure scale plus the sum of its own terms' magnitudes: each row's own relative residual.
  // Against dt rp / Mp alone a node of small Mp (a sliver, a corner) had to be driven to the
  // round-off of its terms whatever the tolerance: 22 % of the Newton iterations of the elastic
  // and the yielding obstacle went to that (a tolerance of 1e-8 instead of 1e-10 saved 2 %).
  // Below a tolerance of kRoundoff the terms' round-off bounds it.
  double f_scale = s_force_scale_ * s_force_scale_;  // the structure's, 0 without one
  for (const auto& r : element_residuals_) f_scale += r.f_squared;
  f_scale = std::sqrt(f_scale) + 1e-300;
  const double p_floor = s.fluid.rho * std::hypot(s.gx, s.gy) * 1e-3 + 1e-12;
  const double p_scale = std::max(p_.lpNorm<Eigen::Infinity>(), p_floor);
  const double r_v = rv_.norm() / f_scale;
  double r_p = 0.0;
  for (int q = 0; q < num_.pressures; ++q) {
    const double allowed = mp_[q] / s.dt * p_scale + std::max(1.0, kRoundoff / s.tolerance) * rp_abs_[q];
    r_p = std::max(r_p, std::abs(rp_[q]) / allowed);
  }
  return std::max(r_v, r_p);
}

void UnifiedStep::newton_correction(const mesh::FluidMesh& mesh, const StepSettings& s, bool first, bool stalled) {
  const bool global = s.formulation == StepSettings::Formulation::kGlobalBubble;
  auto t0 = Clock::now();
  // One factorisation per step serves every iteration (the fluid's tangent changes only
  // through the small geometry update); refactorise at the current iterate if convergence
  // stalls. The structure's block follows every iterate: a fiber that yields or unloads
  // changes its tangent fifty-fold, and a stale one held the yielding obstacle's steps at a
  // contraction of 0.4 per iteration (20 iterations instead of 8).
  const bool update = !first && !stalled && !global && s.structure.model;
  if (first || stalled || (update && !update_structure_tangent())) {
    try {
      if (global) factorize_global_bubble(mesh, s, first);
      else factorize_condensed_bubble(mesh, s, first);
    } catch (const std::runtime_error& e) {
      throw StepFailure(e.what());
    }
    ++report_.factorizations;
  }
  report_.factorize_seconds += seconds_since(t0);
  t0 = Clock::now();
  if (global) correct_global_bubble(s);
  else correct_condensed_bubble(mesh);
  report_.solve_seconds += seconds_since(t0);
}

void UnifiedStep::commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) {
  // The converged state to the nodes; particles outside the mesh fall freely.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int dx = num_.vx[i], dy = num_.vy[i];
    if (dx < 0 && dy < 0) continue;
    // A particle that hits a wall is taken out where it was, as one closer to a wall than the
    // removal distance is between steps (stopped there instead, the jet behind it collides with it).
    if (hits_wall_[i]) {
      nodes.kind[i] = mesh::NodeKind::Removed;
      ++report_.removed_particles;
      continue;
    }
    nodes.vx[i] = velocity_x(static_cast<int>(i)), nodes.vy[i] = velocity_y(static_cast<int>(i));
    nodes.x[i] = xn_[i] + s.dt * nodes.vx[i];
    nodes.y[i] = yn_[i] + s.dt * nodes.vy[i];
  }
  const auto& sn = s.structure.node;
  for (std::size_t k = 0; k < sn.size(); ++k) {
    const int d = num_.structure[3 * k + 2];
    nodes.wz[sn[k]] = d >= 0 ? v_[d] : 0.0;
    nodes.rz[sn[k]] += s.dt * nodes.wz[sn[k]];
  }
  node_pressures(num_, mesh, p_, nodes.size(), nodes.p, nodes.side_p);
  const int num_params = static_cast<int>(s.sensitivity.size());
  if (num_params > 0) commit_sensitivities(mesh, s, nodes);
  if (s.structure.model) s.structure.model->commit();
  move_free_particles(mesh.in_mesh, walls_, {s.gx, s.gy}, s.dt, nodes);
  const int bubbles = num_.velocities - num_.node_velocities;
  bubble_history_.store(mesh.triangles, v_.tail(bubbles),
                        num_params > 0 ? Eigen::MatrixXd(dv_.bottomRows(bubbles)) : Eigen::MatrixXd());
}

StepReport UnifiedStep::advance(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes,
                                const std::atomic<bool>* cancel) {
  report_ = StepReport{};
  analyzed_ = false;
  xn_ = nodes.x, yn_ = nodes.y, vxn_ = nodes.vx, vyn_ = nodes.vy;
  wall_velocity_ = s.wall_velocity;
  if (nodes.size() >= (std::size_t{1} << 21)) throw StepFailure("more than 2^21 nodes");
  num_ = number_unknowns(mesh, nodes, s.slip, s.structure.model, s.structure.node);
  volume_ = volume_correction(mesh, nodes, s.target_area, s.volume_relaxation, s.thickness);
  report_.velocity_unknowns = num_.velocities;
  report_.pressure_unknowns = num_.pressures;
  initial_iterate(mesh, s, nodes);

  NewtonMonitor newton(s.tolerance, s.max_iterations, s.give_up_inverted);
  for (;;) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw StepCancelled();
    auto t0 = Clock::now();
    element_terms(mesh, s);
    residuals(mesh);
    s_force_scale_ = structure_.add_residual(v_, rv_);
    report_.assemble_seconds += seconds_since(t0);
    newton.record(report_.residual = relative_residual(s), any_inverted());
    const int it = newton.iteration();
    if (!std::isfinite(report_.residual))
      throw StepFailure("Newton produced a non-finite residual at iteration " + std::to_string(it));
    if (newton.converged()) break;
    if (newton.out_of_iterations() || newton.hopeless()) {
      char msg[128];
      std::snprintf(msg, sizeof msg, "Newton did not converge in %d iterations (relative residual %.3e%s)", it,
                    report_.residual,
                    newton.inverted_and_stagnating() ? ", a triangle inverted and the residual stagnating"
                    : newton.hopeless()              ? ", not halved in the last iterations"
                                                     : "");
      throw StepFailure(msg);
    }
    newton_correction(mesh, s, it == 0, newton.stalled());
    report_.iterations = it + 1;
  }
  check_admissible(mesh, s, nodes);
  if (!s.sensitivity.empty()) {
    const auto t0 = Clock::now();
    solve_sensitivities(mesh, s, nodes);
    report_.sensitivity_seconds = seconds_since(t0);
  }
  commit(mesh, s, nodes);
  return report_;
}

}  // namespace pfem
