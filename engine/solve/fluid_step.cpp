#include "engine/solve/fluid_step.h"

#include <chrono>
#include <cmath>
#include <string>
#include <cstdio>
#include <cstdlib>

namespace pfem {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
}  // namespace

void UnifiedStep::number_unknowns(const mesh::FluidMesh& mesh, const NodeState& nodes) {
  const std::size_t n = nodes.size();
  vdof_.assign(n, -1);
  pdof_.assign(n, -1);
  n_node_v_ = 0;
  n_p_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mesh.in_mesh[i]) continue;
    if (!nodes.is_fixed(i)) vdof_[i] = n_node_v_, n_node_v_ += 2;
    if (!mesh.free_surface[i]) pdof_[i] = n_p_++;
  }
  n_v_ = n_node_v_ + 2 * static_cast<int>(mesh.triangles.size());
}

void UnifiedStep::element_matrices(const mesh::FluidMesh& mesh, const StepSettings& s) {
  const int ne = static_cast<int>(mesh.triangles.size());
  mats_.resize(ne);
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    std::array<double, 3> x, y;
    for (int a = 0; a < 3; ++a) {
      const int i = mesh.triangles[e][a];
      const int d = vdof_[i];
      x[a] = xn_[i] + (d >= 0 ? s.dt * v_[d] : 0.0);
      y[a] = yn_[i] + (d >= 0 ? s.dt * v_[d + 1] : 0.0);
    }
    fluid::mini_matrices(fluid::triangle_geometry(x, y), s.fluid, s.thickness, s.gx, s.gy, mats_[e]);
  }
}

void UnifiedStep::residuals(const mesh::FluidMesh& mesh, const StepSettings& s) {
  rv_.setZero(n_v_);
  rp_.setZero(n_p_);
  mp_.setZero(n_p_);
  const double inv_dt = 1.0 / s.dt;
  const int ne = static_cast<int>(mesh.triangles.size());
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats_[e];
    const auto& tri = mesh.triangles[e];
    fluid::Vec8 v, vn;
    fluid::Vec3 p, pn;
    for (int a = 0; a < 3; ++a) {
      const int i = tri[a], d = vdof_[i], q = pdof_[i];
      v(2 * a) = d >= 0 ? v_[d] : 0.0;
      v(2 * a + 1) = d >= 0 ? v_[d + 1] : 0.0;
      vn(2 * a) = vxn_[i];
      vn(2 * a + 1) = vyn_[i];
      p(a) = q >= 0 ? p_[q] : 0.0;
      pn(a) = pn_[i];
    }
    const int b = n_node_v_ + 2 * e;
    v(6) = v_[b], v(7) = v_[b + 1];
    vn(6) = vn(7) = 0.0;  // hierarchical bubble: no enrichment carried from t_n
    const fluid::Vec8 rv = m.F - m.M * ((v - vn) * inv_dt) - m.K * v + m.G * p;
    const fluid::Vec3 rp = -m.Mp.cwiseProduct(p - pn) * inv_dt - m.G.transpose() * v;
    for (int a = 0; a < 3; ++a) {
      const int i = tri[a], d = vdof_[i], q = pdof_[i];
      if (d >= 0) rv_[d] += rv(2 * a), rv_[d + 1] += rv(2 * a + 1);
      if (q >= 0) rp_[q] += rp(a), mp_[q] += m.Mp(a);
    }
    rv_[b] += rv(6), rv_[b + 1] += rv(7);
  }
}

void UnifiedStep::assemble_condensed(const mesh::FluidMesh& mesh, const StepSettings& s) {
  const int ne = static_cast<int>(mesh.triangles.size());
  std::vector<Eigen::Triplet<double>> kt, gt;
  kt.reserve(64 * ne);
  gt.reserve(24 * ne);
  const double inv_dt = 1.0 / s.dt;
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats_[e];
    const auto& tri = mesh.triangles[e];
    std::array<int, 8> dof;
    for (int a = 0; a < 3; ++a) {
      const int d = vdof_[tri[a]];
      dof[2 * a] = d;
      dof[2 * a + 1] = d >= 0 ? d + 1 : -1;
    }
    dof[6] = n_node_v_ + 2 * e, dof[7] = dof[6] + 1;
    for (int r = 0; r < 8; ++r) {
      if (dof[r] < 0) continue;
      for (int c = 0; c < 8; ++c)
        if (dof[c] >= 0) kt.emplace_back(dof[r], dof[c], m.M(r, c) * inv_dt + m.K(r, c));
      for (int a = 0; a < 3; ++a)
        if (const int q = pdof_[tri[a]]; q >= 0) gt.emplace_back(dof[r], q, m.G(r, a));
    }
  }
  SparseMatrix kvv(n_v_, n_v_);
  kvv.setFromTriplets(kt.begin(), kt.end());
  g_.resize(n_v_, n_p_);
  g_.setFromTriplets(gt.begin(), gt.end());
  const Eigen::VectorXd d = s.dt * mp_.cwiseInverse();
  condensed_ = kvv + SparseMatrix(g_ * d.asDiagonal() * g_.transpose());
}

StepReport UnifiedStep::advance(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes,
                                const std::atomic<bool>* cancel) {
  StepReport report;
  xn_ = nodes.x, yn_ = nodes.y, vxn_ = nodes.vx, vyn_ = nodes.vy, pn_ = nodes.p;
  number_unknowns(mesh, nodes);
  report.velocity_unknowns = n_v_;
  report.pressure_unknowns = n_p_;

  // Initial iterate: the velocities and pressures of t_n, zero bubbles.
  v_.setZero(n_v_);
  p_.setZero(n_p_);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (vdof_[i] >= 0) v_[vdof_[i]] = vxn_[i], v_[vdof_[i] + 1] = vyn_[i];
    if (pdof_[i] >= 0) p_[pdof_[i]] = pn_[i];
  }

  double previous_residual = 0.0;
  const double p_floor = s.fluid.rho * std::hypot(s.gx, s.gy) * 1e-3 + 1e-12;
  for (int it = 0;; ++it) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw StepCancelled();
    auto t0 = Clock::now();
    element_matrices(mesh, s);
    residuals(mesh, s);
    report.assemble_seconds += seconds_since(t0);

    // Convergence: the velocity residual against the step's force scale, and the pressure
    // correction the pressure residual would cause (dt Mp^-1 rp) against the pressure scale.
    const Eigen::VectorXd dp_star = (s.dt * rp_.array() / mp_.array()).matrix();
    double f_scale = 0.0;
    for (const auto& m : mats_) f_scale += m.F.squaredNorm();
    f_scale = std::sqrt(f_scale) + 1e-300;
    const double p_scale = std::max(p_.lpNorm<Eigen::Infinity>(), p_floor);
    const double r_v = rv_.norm() / f_scale;
    const double r_p = n_p_ ? dp_star.lpNorm<Eigen::Infinity>() / p_scale : 0.0;
    report.residual = std::max(r_v, r_p);
    if (std::getenv("PFEM_TRACE_NEWTON")) std::fprintf(stderr, "  it %d r_v %.3e r_p %.3e\n", it, r_v, r_p);
    if (!std::isfinite(report.residual))
      throw StepFailure("Newton produced a non-finite residual at iteration " + std::to_string(it));
    if (report.residual <= s.tolerance) break;
    if (it == s.max_iterations)
      throw StepFailure("Newton did not converge in " + std::to_string(it) +
                        " iterations (relative residual " + std::to_string(report.residual) + ")");

    // One factorisation per step serves every iteration (the tangent changes only through the
    // small geometry update); refactorise at the current iterate if convergence stalls.
    const bool stalled = it > 0 && report.residual > 0.05 * previous_residual;
    previous_residual = report.residual;
    if (it == 0 || stalled) {
      t0 = Clock::now();
      assemble_condensed(mesh, s);
      report.assemble_seconds += seconds_since(t0);
      t0 = Clock::now();
      if (it == 0) solver_.analyze(condensed_);
      try {
        solver_.factorize(condensed_);
      } catch (const std::runtime_error& e) {
        throw StepFailure(e.what());
      }
      report.factorize_seconds += seconds_since(t0);
      ++report.factorizations;
    }
    t0 = Clock::now();
    const Eigen::VectorXd dv = solver_.solve(Eigen::VectorXd(rv_ + g_ * dp_star));
    const Eigen::VectorXd dp = dp_star - (s.dt * (g_.transpose() * dv).array() / mp_.array()).matrix();
    v_ += dv;
    p_ += dp;
    report.solve_seconds += seconds_since(t0);
    report.iterations = it + 1;
  }

  // Commit the converged state to the nodes; particles outside the mesh fall freely.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.is_fixed(i)) continue;
    if (const int d = vdof_[i]; d >= 0) {
      nodes.vx[i] = v_[d], nodes.vy[i] = v_[d + 1];
    } else if (!mesh.in_mesh[i]) {
      nodes.vx[i] += s.dt * s.gx, nodes.vy[i] += s.dt * s.gy;
    }
    nodes.x[i] = xn_[i] + s.dt * nodes.vx[i];
    nodes.y[i] = yn_[i] + s.dt * nodes.vy[i];
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes.p[i] = pdof_[i] >= 0 ? p_[pdof_[i]] : 0.0;
  return report;
}

}  // namespace pfem
