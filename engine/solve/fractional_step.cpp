#include "engine/solve/fractional_step.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "engine/solve/newton_monitor.h"
#include "engine/solve/step_commit.h"

namespace pfem {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
// A residual below this many ulps of the sum of its terms' magnitudes is round-off (the
// quasi-incompressible step's allowance, fluid_step.cpp).
constexpr double kRoundoff = 1024 * std::numeric_limits<double>::epsilon();
// Each iteration's linear solve (FractionalOperators::solve_accelerated) to this relative
// residual: below what the omitted geometric terms leave, so that the iterations contract as a
// modified Newton's.
constexpr double kInnerTolerance = 1e-4;
// Saved in checkpoints in place of a state: the incompressible step hands nothing on.
constexpr std::uint64_t kArchiveTag = 0x4653'4d31;  // "FSM1"
}  // namespace

void FractionalStep::archive(StateArchive& a) { a.expect(kArchiveTag, "(the incompressible step's tag)"); }

double FractionalStep::velocity(int i, int c) const {
  if (num_.is_rider(i)) return num_.velocity_in(i, c, v_);
  const int d = c == 0 ? num_.vx[i] : num_.vy[i];
  if (d >= 0) return v_[d];
  return wall_velocity_.empty() ? 0.0 : wall_velocity_[2 * static_cast<std::size_t>(i) + c];
}

void FractionalStep::begin(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  xn_ = nodes.x, yn_ = nodes.y, vxn_ = nodes.vx, vyn_ = nodes.vy;
  wall_velocity_ = s.wall_velocity;
  num_ = number_unknowns(mesh, nodes, s.slip, s.structure.model, s.structure.node, s.riders);
  report_.velocity_unknowns = num_.velocities, report_.pressure_unknowns = num_.pressures;
  volume_ = volume_correction(mesh, nodes, s.target_area, s.volume_relaxation, s.thickness);
  v_.setZero(num_.velocities);  // bubbles from rest (fluid/mini_lumped.h)
  gather_velocities(num_, nodes, v_);
  p_ = pn_ = gather_pressures(num_, mesh, nodes);
  structure_.begin(s.structure, num_, s.dt, s.gx, s.gy, nodes, v_);
}

fluid::ElementState FractionalStep::element_state(const mesh::FluidMesh& mesh, int e) const {
  fluid::ElementState st;
  for (int a = 0; a < 3; ++a) {
    const int i = mesh.triangles[e][a], q = num_.corner_p[e][a];
    st.v(2 * a) = velocity(i, 0), st.v(2 * a + 1) = velocity(i, 1);
    st.vn(2 * a) = vxn_[i], st.vn(2 * a + 1) = vyn_[i];
    st.p(a) = p_[q], st.pn(a) = pn_[q];
  }
  st.v.tail<2>() = v_.segment<2>(num_.bubble(e));
  st.vn.tail<2>().setZero();
  return st;
}

void FractionalStep::element_terms(const mesh::FluidMesh& mesh, const StepSettings& s) {
  const int ne = static_cast<int>(mesh.triangles.size());
  geometries_.resize(ne), mats_.resize(ne), lumped_.resize(ne), element_residuals_.resize(ne);
  const fluid::FluidConstants incompressible{s.fluid.rho, s.fluid.mu, std::numeric_limits<double>::infinity()};
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    std::array<double, 3> xn, yn, vx, vy;
    for (int a = 0; a < 3; ++a) {
      const int i = mesh.triangles[e][a];
      xn[a] = xn_[i], yn[a] = yn_[i], vx[a] = velocity(i, 0), vy[a] = velocity(i, 1);
    }
    geometries_[e] = fluid::step_geometry(xn, yn, vx, vy, s.dt);
    fluid::mini_matrices(geometries_[e], incompressible, s.thickness, s.gx, s.gy, mats_[e]);
    lumped_[e] = fluid::lumped_mass(mats_[e]);
    element_residuals_[e] = fluid::lumped_residual(mats_[e], lumped_[e], s.dt, element_state(mesh, e));
  }
}

void FractionalStep::residuals(const mesh::FluidMesh& mesh) {
  rv_.setZero(num_.velocities);
  rp_.setZero(num_.pressures);
  rp_terms_.setZero(num_.pressures);
  rp_reach_.setZero(num_.pressures);
  force_squared_ = 0.0;
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    const auto& r = element_residuals_[e];
    const auto& tri = mesh.triangles[e];
    const fluid::ElementState st = element_state(mesh, static_cast<int>(e));
    for (int k = 0; k < 6; ++k) num_.add_to_velocity(tri[k / 2], k % 2, r.rv(k), rv_);
    rv_.segment<2>(num_.bubble(static_cast<int>(e))) += r.rv.tail<2>();
    const double source = volume_.dilatation == 0.0 ? 0.0 : volume_.corner_source(e);
    for (int a = 0; a < 3; ++a) {
      const int q = num_.corner_p[e][a];
      const auto gc = mats_[e].Gc.col(a);
      rp_[q] += r.rp(a) + source;
      rp_terms_[q] += gc.cwiseProduct(st.v).cwiseAbs().sum() + std::abs(source);
      rp_reach_[q] += gc.cwiseAbs().sum();
    }
    force_squared_ += mats_[e].F.squaredNorm();
  }
  structure_force_ = structure_.add_residual(v_, rv_);
}

double FractionalStep::relative_residual(const StepSettings& s) const {
  // The momentum residual against the step's force scale (as the quasi-incompressible step);
  // each node's mass balance against what a velocity error of the step's velocity scale would
  // make of it, plus the round-off of its own terms.
  const double force = std::sqrt(force_squared_ + structure_force_ * structure_force_) + 1e-300;
  const double speed = std::max(v_.lpNorm<Eigen::Infinity>(), std::hypot(s.gx, s.gy) * s.dt) + 1e-300;
  const double roundoff = std::max(1.0, kRoundoff / s.tolerance);
  double r_p = 0.0;
  for (int q = 0; q < num_.pressures; ++q)
    r_p = std::max(r_p, std::abs(rp_[q]) / (rp_reach_[q] * speed + roundoff * rp_terms_[q] + 1e-300));
  return std::max(rv_.norm() / force, r_p);
}

void FractionalStep::check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  // As the quasi-incompressible step (fluid_step.h): a particle whose move crosses a wall or
  // beam is taken out; any other inverted triangle fails the step, which is then retried shorter.
  std::vector<double> x1(nodes.size()), y1(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    x1[i] = xn_[i] + s.dt * velocity(static_cast<int>(i), 0);
    y1[i] = yn_[i] + s.dt * velocity(static_cast<int>(i), 1);
  }
  const StepEnds ends{xn_, yn_, x1, y1};
  walls_ = wall_pieces(s.walls, ends);
  hits_wall_ = particles_crossing_walls(mesh.triangles, nodes.kind, ends, walls_);
  for (std::size_t e = 0; e < geometries_.size(); ++e) {
    const auto& t = mesh.triangles[e];
    const bool hit = hits_wall_[t[0]] || hits_wall_[t[1]] || hits_wall_[t[2]];
    if (!hit && !(geometries_[e].A > 0.0)) throw StepFailure("a triangle inverted within the step");
  }
}

void FractionalStep::commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (num_.vx[i] < 0 && num_.vy[i] < 0 && !num_.is_rider(static_cast<int>(i))) continue;
    if (hits_wall_[i]) {  // taken out where it was
      nodes.kind[i] = mesh::NodeKind::Removed;
      ++report_.removed_particles;
      continue;
    }
    nodes.vx[i] = velocity(static_cast<int>(i), 0), nodes.vy[i] = velocity(static_cast<int>(i), 1);
    nodes.x[i] = xn_[i] + s.dt * nodes.vx[i], nodes.y[i] = yn_[i] + s.dt * nodes.vy[i];
  }
  for (std::size_t k = 0; k < s.structure.node.size(); ++k) {
    const int node = s.structure.node[k], d = num_.structure[3 * k + 2];
    nodes.wz[node] = d >= 0 ? v_[d] : 0.0;
    nodes.rz[node] += s.dt * nodes.wz[node];
  }
  node_pressures(num_, mesh, p_, nodes.size(), nodes.p, nodes.side_p);
  if (!s.sensitivity.empty()) commit_sensitivities(mesh, s, nodes);
  if (s.structure.model) s.structure.model->commit();
  move_free_particles(mesh.in_mesh, walls_, {s.gx, s.gy}, s.dt, nodes);
}

void FractionalStep::iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const std::atomic<bool>* cancel) {
  NewtonMonitor monitor(s.tolerance, s.max_iterations);
  for (;;) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw StepCancelled();
    auto t0 = Clock::now();
    element_terms(mesh, s);
    residuals(mesh);
    report_.assemble_seconds += seconds_since(t0);
    monitor.record(report_.residual = relative_residual(s));
    const int it = monitor.iteration();
    const bool failed = monitor.out_of_iterations() || monitor.hopeless();
    if (!std::isfinite(report_.residual) || (failed && !monitor.converged())) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "the fractional step did not converge in %d iterations (relative residual %.3e%s)",
                    it, report_.residual, monitor.hopeless() ? ", not halved in the last iterations" : "");
      throw StepFailure(msg);
    }
    if (monitor.converged()) return;
    // The operators at the first iterate serve the step's iterations, unless they stall (a
    // structure whose tangent changed as fibers yield, a geometry that moved far).
    if (it == 0 || monitor.stalled()) {
      t0 = Clock::now();
      factorize_or_fail([&] { operators_.build(mesh, num_, mats_, lumped_, structure_, s.dt, it == 0); });
      ++report_.factorizations;
      report_.factorize_seconds += seconds_since(t0);
    }
    t0 = Clock::now();
    Eigen::VectorXd dv, dp;
    operators_.solve_accelerated(rv_, rp_, kInnerTolerance, dv, dp);
    v_ += dv, p_ += dp;
    report_.solve_seconds += seconds_since(t0);
    report_.iterations = it + 1;
  }
}

void FractionalStep::solve(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes,
                           const std::atomic<bool>* cancel) {
  report_ = StepReport{};
  begin(mesh, s, nodes);
  iterate(mesh, s, cancel);
  check_admissible(mesh, s, nodes);
}

}  // namespace pfem
