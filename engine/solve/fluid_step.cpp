#include "engine/solve/fluid_step.h"

#include "engine/solve/step_commit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

namespace pfem {

namespace {
using Clock = std::chrono::steady_clock;
// Round-off allowance: a residual below kRoundoff times the sum of its terms' magnitudes is noise.
// It covers the rounding of the sums and that of the solved velocities they multiply: with
// 64 eps, residuals stalled at 1.1-2.8 times the allowance in the yielding-obstacle impact, and
// whether such a step failed (and was halved) became a round-off decision that perturbed
// finite-difference runs took differently.
constexpr double kRoundoff = 1024 * std::numeric_limits<double>::epsilon();
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why Newton gave the step up.
StepFailure not_converged(const NewtonMonitor& newton) {
  char msg[192];
  std::snprintf(msg, sizeof msg, "Newton did not converge in %d iterations (relative residual %.3e%s)",
                newton.iteration(), newton.residual(),
                newton.inverted_and_stagnating() ? ", a triangle inverted and the residual stagnating"
                : newton.hopeless()              ? ", not halved in the last iterations"
                                                 : "");
  return StepFailure(msg);
}

}  // namespace

void UnifiedStep::solve(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes,
                        const std::atomic<bool>* cancel) {
  report_ = StepReport{};
  if (nodes.size() >= (std::size_t{1} << 21)) throw StepFailure("more than 2^21 nodes");
  num_ = number_unknowns(mesh, nodes, s.slip, s.structure.model, s.structure.node, s.riders);
  report_.velocity_unknowns = num_.velocities;
  report_.pressure_unknowns = num_.pressures;
  initial_iterate(mesh, s, nodes);

  NewtonMonitor newton(s.tolerance, s.max_iterations, s.give_up_inverted);
  for (;;) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw StepCancelled();
    assemble();
    newton.record(report_.residual = relative_residual(s), elements_.any_inverted());
    if (!std::isfinite(report_.residual))
      throw StepFailure("Newton produced a non-finite residual at iteration " + std::to_string(newton.iteration()));
    if (newton.converged()) break;
    if (newton.out_of_iterations() || newton.hopeless()) throw not_converged(newton);
    newton_correction(s, newton.iteration() == 0, newton.stalled());
    report_.iterations = newton.iteration() + 1;
  }
  check_admissible(mesh, s, nodes);
}

void UnifiedStep::initial_iterate(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  // The velocities, pressures and bubbles of t_n.
  Eigen::VectorXd vbn;
  bubble_history_.restore(mesh.triangles, static_cast<int>(s.sensitivity.size()), vbn, dvbn_);
  v_.setZero(num_.velocities);
  v_.segment(num_.bubble(0), vbn.size()) = vbn;  // bubble(e) = bubble(0) + 2 e
  elements_.begin(mesh, s, num_, nodes, std::move(vbn));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (num_.vx[i] >= 0) v_[num_.vx[i]] = nodes.vx[i];
    if (num_.vy[i] >= 0) v_[num_.vy[i]] = nodes.vy[i];
  }
  p_ = elements_.pressures_n();

  structure_.begin(s.structure, num_, s.dt, s.gx, s.gy, nodes, v_);
  condensed_.begin(mesh, s, num_, structure_);
  global_.begin(mesh, s, num_, structure_);
}

void UnifiedStep::assemble() {
  const auto t0 = Clock::now();
  elements_.update(v_, p_);
  elements_.assemble(residual_);
  s_force_scale_ = structure_.add_residual(v_, residual_.rv);
  report_.assemble_seconds += seconds_since(t0);
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
  for (const auto& r : elements_.residuals()) f_scale += r.f_squared;
  f_scale = std::sqrt(f_scale) + 1e-300;
  const double p_floor = s.fluid.rho * std::hypot(s.gx, s.gy) * 1e-3 + 1e-12;
  const double p_scale = std::max(p_.lpNorm<Eigen::Infinity>(), p_floor);
  const double r_v = residual_.rv.norm() / f_scale;
  double r_p = 0.0;
  for (int q = 0; q < num_.pressures; ++q) {
    const double allowed = residual_.mp[q] / s.dt * p_scale + std::max(1.0, kRoundoff / s.tolerance) * residual_.rp_abs[q];
    r_p = std::max(r_p, std::abs(residual_.rp[q]) / allowed);
  }
  return std::max(r_v, r_p);
}

void UnifiedStep::newton_correction(const StepSettings& s, bool first, bool stalled) {
  StepLinearSystem& system = s.formulation == StepSettings::Formulation::kGlobalBubble
                                 ? static_cast<StepLinearSystem&>(global_)
                                 : condensed_;
  auto t0 = Clock::now();
  // One factorisation per step serves every iteration (the fluid's tangent changes only
  // through the small geometry update); refactorise at the current iterate if convergence
  // stalls. The structure's block follows every iterate: a fiber that yields or unloads
  // changes its tangent fifty-fold, and a stale one held the yielding obstacle's steps at a
  // contraction of 0.4 per iteration (20 iterations instead of 8).
  if (first || stalled || !system.refresh_structure()) {
    factorize_or_fail([&] { system.factorize(elements_, residual_.mp, first); });
    ++report_.factorizations;
  }
  report_.factorize_seconds += seconds_since(t0);
  t0 = Clock::now();
  Eigen::VectorXd dv, dp;
  system.solve(residual_, dv, dp);
  v_ += dv;
  p_ += dp;
  report_.solve_seconds += seconds_since(t0);
}

void UnifiedStep::solve_sensitivities(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  if (s.sensitivity.empty()) return;
  const auto t0 = Clock::now();
  const bool newton_factorized =
      s.formulation == StepSettings::Formulation::kCondensedBubble && condensed_.analyzed();
  if (!condensed_.analyzed()) condensed_.analyze();  // the DDM's LU takes its analysis
  sensitivity_.solve({mesh, s, num_, v_, p_, elements_, residual_, structure_, condensed_, newton_factorized, dvbn_},
                     nodes);
  report_.sensitivity_seconds = seconds_since(t0);
}

void UnifiedStep::check_admissible(const mesh::FluidMesh& mesh, const StepSettings& s, const NodeState& nodes) {
  // A particle whose move crosses a wall or beam hits it (commit() takes it out): typically a
  // splash particle reaching the floor or the obstacle's back, in free-surface triangles that
  // have no pressure to stop it, or in none on that edge at all (the alpha test drops the
  // sliver it would make). A shorter step only brings it closer.
  std::vector<double> x1(nodes.size()), y1(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    x1[i] = elements_.x_n()[i] + s.dt * elements_.velocity_x(static_cast<int>(i), v_);
    y1[i] = elements_.y_n()[i] + s.dt * elements_.velocity_y(static_cast<int>(i), v_);
  }
  const StepEnds ends{elements_.x_n(), elements_.y_n(), x1, y1};
  walls_ = wall_pieces(s.walls, ends);
  hits_wall_ = particles_crossing_walls(mesh.triangles, nodes.kind, ends, walls_);
  // An inverted triangle is no solution of the step (retried shorter), unless a particle of it
  // crossed a wall: that move is not made.
  const auto& geometries = elements_.geometries();
  for (std::size_t e = 0; e < geometries.size(); ++e) {
    const auto& t = mesh.triangles[e];
    if (!(geometries[e].A > 0.0) && !hits_wall_[t[0]] && !hits_wall_[t[1]] && !hits_wall_[t[2]])
      throw StepFailure("a triangle inverted within the step");
  }
}

void UnifiedStep::commit(const mesh::FluidMesh& mesh, const StepSettings& s, NodeState& nodes) {
  // The converged state to the nodes; particles outside the mesh fall freely.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int dx = num_.vx[i], dy = num_.vy[i];
    if (dx < 0 && dy < 0 && !num_.is_rider(static_cast<int>(i))) continue;
    // A particle that hits a wall is taken out where it was, as one closer to a wall than the
    // removal distance is between steps (stopped there instead, the jet behind it collides with it).
    if (hits_wall_[i]) {
      nodes.kind[i] = mesh::NodeKind::Removed;
      ++report_.removed_particles;
      continue;
    }
    nodes.vx[i] = elements_.velocity_x(static_cast<int>(i), v_), nodes.vy[i] = elements_.velocity_y(static_cast<int>(i), v_);
    nodes.x[i] = elements_.x_n()[i] + s.dt * nodes.vx[i];
    nodes.y[i] = elements_.y_n()[i] + s.dt * nodes.vy[i];
  }
  const auto& sn = s.structure.node;
  for (std::size_t k = 0; k < sn.size(); ++k) {
    const int d = num_.structure[3 * k + 2];
    nodes.wz[sn[k]] = d >= 0 ? v_[d] : 0.0;
    nodes.rz[sn[k]] += s.dt * nodes.wz[sn[k]];
  }
  node_pressures(num_, mesh, p_, nodes.size(), nodes.p, nodes.side_p);
  const int num_params = static_cast<int>(s.sensitivity.size());
  if (num_params > 0) sensitivity_.commit(s, num_, mesh, structure_, hits_wall_, nodes);
  if (s.structure.model) s.structure.model->commit();
  move_free_particles(mesh.in_mesh, walls_, {s.gx, s.gy}, s.dt, nodes);
  const int bubbles = num_.velocities - num_.node_velocities;
  bubble_history_.store(mesh.triangles, v_.tail(bubbles),
                        num_params > 0 ? Eigen::MatrixXd(sensitivity_.velocities().bottomRows(bubbles)) : Eigen::MatrixXd());
}

}  // namespace pfem
