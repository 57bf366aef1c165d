#include "engine/analysis/simulation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <sstream>

#include "engine/analysis/beam_rider_nodes.h"
#include "engine/analysis/moving_walls.h"
#include "engine/analysis/recorders.h"
#include "engine/analysis/run_state.h"
#include "engine/analysis/slip_wall_remap.h"
#include "engine/mesh/deformation_cfl.h"
#include "engine/mesh/particle_spacing.h"
#include "engine/io/model_size.h"
#include "engine/io/vtk_writer.h"
#include "engine/solve/fluid_step.h"

namespace pfem {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The first node (not a wall) outside the domain, or -1.
int node_outside(const NodeState& nodes, const Box& domain) {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (!nodes.is_fixed(i) && !domain.contains(nodes.x[i], nodes.y[i])) return static_cast<int>(i);
  return -1;
}
// Largest number of halvings of a step of each kind: before an attempt, where a triangle would
// collapse, and after a failed attempt (1/256 of dt at most, both together).
constexpr int kMaxHalvings = 4;
struct Halvings {
  int predicted = 0, failed = 0;
};

void add_work(RunSummary& sum, const StepReport& r) {
  sum.newton_iterations += r.iterations;
  sum.factorizations += r.factorizations;
  sum.assemble_seconds += r.assemble_seconds;
  sum.factorize_seconds += r.factorize_seconds;
  sum.solve_seconds += r.solve_seconds;
  sum.sensitivity_seconds += r.sensitivity_seconds;
  sum.removed_particles += r.removed_particles;
}

// The wall nodes at the contact lines of previous slide to them, every other sliding node goes
// home (mesh/contact_line.h), both as the walls are at time t, a slip node with the wall's
// velocity at its home (slip_wall_remap.h); a slid node's position follows its particle's
// along the wall, and so does its position sensitivity: with home h, tangent u and
// offset o = (p - h).u (to the foot; to the point level with p, ((p - h) x l) / (u x l) for the
// level l), the node h + o u has the derivative dh + do u + o du (SlidingWallNode).
// A slid slip node takes its particle's velocity along the wall (its free component): with one of
// its own, kept from step to step while its place is reset, it ran at 0.035 m/s up a slip paddle
// beside water rising at 0.002 m/s, and the paddle's waves came out 11 % low.
void slide_walls(const Problem& problem, const mesh::FluidMesh& previous, NodeState& nodes, double t) {
  const int P = nodes.num_params;
  std::vector<std::array<double, 4>> dwall;  // per sliding node and parameter: d(home_x, home_y, tx, ty)
  const auto sliding = sliding_walls_at(problem, P, t, dwall);
  remap_slip_velocities(sliding, dwall, problem.wall_slip, previous.in_mesh, nodes);
  for (std::size_t j = 0; j < sliding.size(); ++j) {
    const auto& s = sliding[j];
    nodes.x[s.node] = s.home_x, nodes.y[s.node] = s.home_y;
    for (int k = 0; k < P; ++k) {
      nodes.sensitivity(s.node, k)[NodeState::kDx] = dwall[j * P + k][0];
      nodes.sensitivity(s.node, k)[NodeState::kDy] = dwall[j * P + k][1];
    }
  }
  const std::array<double, 2> level = mesh::level_direction(problem.gx, problem.gy);
  for (const auto& slide : mesh::contact_line_slides(previous, nodes.x, nodes.y, sliding, problem.wall_neighbours, level)) {
    const mesh::SlidingWallNode& s = sliding[slide.index];
    const double tx = s.tx, ty = s.ty, o = slide.offset;
    nodes.x[s.node] = s.home_x + o * tx;
    nodes.y[s.node] = s.home_y + o * ty;
    const std::uint8_t free = problem.slip_of(s.node);
    if (free == kSlipX) nodes.vx[s.node] = nodes.vx[slide.particle];
    if (free == kSlipY) nodes.vy[s.node] = nodes.vy[slide.particle];
    for (int k = 0; k < P; ++k) {
      const double* dp = nodes.sensitivity(slide.particle, k);
      const auto& dh = dwall[static_cast<std::size_t>(slide.index) * P + k];
      const auto& [dhx, dhy, dtx, dty] = dh;
      // Held at its reach, the node's offset is a constant of the wall, not the particle's.
      const double along = !slide.follows ? 0.0
                           : slide.level ? s.level_offset_derivative(o, dp[NodeState::kDx], dp[NodeState::kDy], dh, level)
                                         : s.offset_derivative(nodes.x[slide.particle], nodes.y[slide.particle],
                                                               dp[NodeState::kDx], dp[NodeState::kDy], dh);
      double* dw = nodes.sensitivity(s.node, k);
      dw[NodeState::kDx] = dhx + along * tx + o * dtx, dw[NodeState::kDy] = dhy + along * ty + o * dty;
      if (free == kSlipX) dw[NodeState::kDvx] = dp[NodeState::kDvx];
      if (free == kSlipY) dw[NodeState::kDvy] = dp[NodeState::kDvy];
    }
  }
}

// Triangulates the nodes as they are (under a moving wall, see clear_under_moving_walls).
mesh::FluidMesh remesh_nodes(const Problem& problem, const NodeState& nodes, mesh::RemeshOptions options) {
  if (problem.moving_walls.empty()) return mesh::remesh(nodes.x, nodes.y, nodes.kind, options);
  std::vector<mesh::NodeKind> kind = nodes.kind;
  std::vector<std::array<std::int32_t, 2>> constraints = options.constraints;
  clear_under_moving_walls(problem, nodes, kind, constraints);
  options.constraints = std::move(constraints);
  return mesh::remesh(nodes.x, nodes.y, kind, options);
}

// Remeshes nodes after the step that used previous for a step of dt (see
// RemeshOptions::previous_boundary, previous_triangles), with the wall nodes slid to its contact
// lines and the beam riders (if any) placed at them first (t: the time now).
mesh::FluidMesh remesh_after(const Problem& problem, const mesh::FluidMesh& previous, NodeState& nodes,
                             BeamRiderNodes* riders, mesh::RemeshOptions options, double dt, double t) {
  // A slip wall's node out of the water keeps no velocity along its wall (a moving wall's normal one
  // is the wall's): one it had when last wet (or next to a paddle that then stood over it) would be
  // an impulse on the water that reaches it again. Slid to a contact particle, it takes the
  // particle's (slide_walls).
  for (std::size_t i = 0; i < problem.wall_slip.size() && i < previous.in_mesh.size(); ++i) {
    if (problem.wall_slip[i] == 0 || previous.in_mesh[i]) continue;
    const bool along_x = problem.wall_slip[i] == kSlipX;
    (along_x ? nodes.vx[i] : nodes.vy[i]) = 0.0;
    for (int k = 0; k < nodes.num_params; ++k) nodes.sensitivity(i, k)[along_x ? NodeState::kDvx : NodeState::kDvy] = 0.0;
  }
  slide_walls(problem, previous, nodes, t);
  if (riders) options.riders = riders->place(previous, nodes, mesh::level_direction(problem.gx, problem.gy), problem.h);
  std::vector<std::uint8_t> boundary(previous.free_surface.size());
  for (std::size_t i = 0; i < boundary.size(); ++i)
    boundary[i] = previous.free_surface[i] || (i < previous.in_mesh.size() && nodes.kind[i] == mesh::NodeKind::Fluid &&
                                               !previous.in_mesh[i]);
  options.previous_boundary = boundary;
  options.previous_triangles = previous.triangles;
  options.vx = nodes.vx, options.vy = nodes.vy;
  options.dt = dt;
  return remesh_nodes(problem, nodes, options);
}

// Advances nodes by dt on mesh, or in two halves of dt / 2 (kMaxHalvings deep for each reason):
// at once where a triangle would collapse within the step at the nodes' velocities
// (mesh/deformation_cfl.h; the first half, on the same mesh, is halved again until none does), or
// after an attempt whose Newton solve fails (typically a sliver that inverts within the step).
// Between the halves, too close particles are removed (as between steps; see particle_spacing.h)
// and the nodes remeshed, and the second half decides for itself. t: the time at its start
// (moving walls take their velocities over the step from it). Returns the Newton iterations of
// the last attempt; the work of every attempt, failed ones included, goes into sum. Halving is a
// decision taken from the response, which the DDM follows as it is (not differentiated).
int advance_adaptive(const Problem& problem, StepSolver& step, mesh::FluidMesh& mesh, StepSettings settings,
                     const mesh::RemeshOptions& remesh_options, BeamRiderNodes* riders, NodeState& nodes, double t,
                     double removal_distance, const std::atomic<bool>* cancel, RunSummary& sum, Halvings depth = {}) {
  if (depth.predicted < kMaxHalvings &&
      mesh::collapses_within(mesh, nodes.x, nodes.y, nodes.vx, nodes.vy, settings.dt)) {
    ++sum.deformation_substeps;
    ++depth.predicted;
  } else {
    try {
      const WallKinematics walls = wall_kinematics(problem, nodes, t, t + settings.dt);
      settings.wall_velocity = walls.velocity;
      settings.wall_velocity_sensitivity = walls.sensitivity;
      settings.give_up_inverted = depth.failed < kMaxHalvings;
      if (riders) settings.riders = riders->step_riders(mesh);
      step.solve(mesh, settings, nodes, cancel);
      step.solve_sensitivities(mesh, settings, nodes);
      step.commit(mesh, settings, nodes);
      place_moving_walls(problem, t + settings.dt, walls, nodes);
      add_work(sum, step.last_report());
      return step.last_report().iterations;
    } catch (const StepFailure&) {
      add_work(sum, step.last_report());
      if (depth.failed == kMaxHalvings) throw;
    }
    ++sum.substeps;
    ++depth.failed;
  }
  settings.dt *= 0.5;
  int iterations = 0;
  for (int half = 0; half < 2; ++half) {
    if (half == 1) {
      const auto t0 = Clock::now();
      // Particles squeezed together in the first half would only come closer in a shorter step.
      sum.removed_particles += mesh::remove_close_particles(mesh, nodes.x, nodes.y, nodes.kind, removal_distance);
      mesh = remesh_after(problem, mesh, nodes, riders, remesh_options, settings.dt, t + settings.dt);
      sum.remesh_seconds += since(t0);
    }
    iterations = advance_adaptive(problem, step, mesh, settings, remesh_options, riders, nodes,
                                  t + half * settings.dt, removal_distance, cancel, sum, depth);
  }
  return iterations;
}

// New particles at the middle of the edges that have grown too long (see edges_to_split), with
// the mean velocity and pressure of the edge's ends (and so the mean sensitivities); at a wall or
// beam node, the pressure of the edge's side of its lines.
// A particle on an edge of the free surface is on that surface too: mesh.free_surface grows to
// flag it for the next remeshing's gap rules (RemeshOptions::previous_boundary).
// lines: the wall and beam segments.
int insert_particles(mesh::FluidMesh& mesh, const Problem& problem, std::span<const std::array<std::int32_t, 2>> lines,
                     NodeState& nodes) {
  if (problem.insertion_length <= 0.0) return 0;
  const auto edges = mesh::edges_to_split(mesh, nodes.x, nodes.y, nodes.kind, problem.insertion_length * problem.h,
                                          problem.interior_insertion_length * problem.h, {lines, 0.5 * problem.h});
  for (const auto& [a, b, side, on_surface] : edges) {
    const bool multi = mesh.multi_sided(b);
    const int i = nodes.add(0.5 * (nodes.x[a] + nodes.x[b]), 0.5 * (nodes.y[a] + nodes.y[b]), mesh::NodeKind::Fluid,
                            0.5 * (nodes.vx[a] + nodes.vx[b]), 0.5 * (nodes.vy[a] + nodes.vy[b]));
    nodes.x0[i] = nodes.x[i], nodes.y0[i] = nodes.y[i];  // displacements count from its birth
    mesh.free_surface.resize(nodes.size(), 0);
    mesh.free_surface[i] = on_surface;
    nodes.p[i] = 0.5 * (nodes.p[a] + nodes.pressure(b, multi, side));
    for (int k = 0; k < nodes.num_params; ++k) {
      const double *da = nodes.sensitivity(a, k), *db = nodes.sensitivity(b, k);
      double* d = nodes.sensitivity(i, k);
      for (const int f : {NodeState::kDx, NodeState::kDy, NodeState::kDvx, NodeState::kDvy}) d[f] = 0.5 * (da[f] + db[f]);
      d[NodeState::kDp] = 0.5 * (da[NodeState::kDp] + nodes.pressure_sensitivity(b, multi, side, k));
    }
  }
  return static_cast<int>(edges.size());
}

}  // namespace

SimulationOutput simulate(const Problem& problem, const RunOptions& options, const Checkpointing* checkpoints) {
  const auto start = Clock::now();
  RunState state;
  NodeState& nodes = state.nodes;
  mesh::FluidMesh& mesh = state.mesh;
  SimulationOutput& out = state.out;
  RunSummary& sum = out.summary;
  sum.dt = problem.dt;
  sum.t_end = problem.t_end;
  // The last step is shortened to end at t_end when dt does not divide it.
  const int total_steps = static_cast<int>(count_steps(problem.t_end, problem.dt));
  const double last_dt = problem.t_end - (total_steps - 1) * problem.dt;
  const bool short_last = last_dt < problem.dt * (1.0 - 1e-9);
  const auto time_of = [&](int n) { return short_last && n == total_steps ? problem.t_end : n * problem.dt; };
  for (const auto& r : problem.recorders) out.responses.columns.push_back(r.name);
  const bool ddm = !problem.sensitivity_params.empty();
  for (const auto& r : problem.recorders)
    for (const auto& p : problem.sensitivity_params) out.sensitivities.columns.push_back("d" + r.name + "/d" + p);

  nodes = problem.nodes;
  for (const auto k : nodes.kind) sum.particles += k == mesh::NodeKind::Fluid;
  // Walls and beams are constraints of the triangulation: no triangle spans them.
  auto constraints = problem.wall_segments;
  constraints.insert(constraints.end(), problem.beam_segments.begin(), problem.beam_segments.end());
  mesh::RemeshOptions remesh_options{problem.h, problem.alpha, problem.gx, problem.gy, constraints};
  remesh_options.boundary_alpha = problem.boundary_alpha;
  if (problem.structure) state.structure.emplace(*problem.structure);  // this run's own state
  StepSettings settings;
  settings.dt = problem.dt;
  settings.tolerance = problem.newton_tolerance;
  settings.max_iterations = problem.newton_max_iterations;
  settings.fluid = problem.fluid;
  settings.thickness = problem.thickness;
  settings.gx = problem.gx;
  settings.gy = problem.gy;
  settings.threads = options.threads;
  settings.walls = constraints;  // beams too: they move little within a step
  settings.slip = problem.wall_slip;
  if (problem.unified_fractional_step) settings.formulation = StepSettings::Formulation::kGlobalBubble;
  if (state.structure) settings.structure = {&*state.structure, problem.structure_nodes, problem.structure_self_weight};
  settings.sensitivity = problem.fluid_seeds;
  settings.geometric_terms = !options.drop_geometric_terms;
  state.solver = make_step_solver(problem);
  StepSolver& step = *state.solver;
  // Beam riders (mesh/beam_riders.h), whose rows every step's systems take to their segments' ends.
  std::optional<BeamRiderNodes> riders;
  if (state.structure && !problem.beam_segments.empty()) riders.emplace(problem.beam_segments, nodes);

  const int vtk_every = options.vtk_every.value_or(problem.vtk_every);
  std::unique_ptr<VtkSeries> vtk;
  if (!options.vtk_dir.empty())
    vtk = std::make_unique<VtkSeries>(options.vtk_dir, problem.sensitivity_params, problem.structure_nodes);
  const auto archive_all = [&](StateArchive& a) {
    archive(a, state);
    if (vtk) vtk->archive(a);
  };
  const structure::StructureModel* model = state.structure ? &*state.structure : nullptr;
  const auto record = [&](double time) {
    out.responses.time.push_back(time);
    out.responses.rows.push_back(sample_recorders(problem, nodes, mesh, model));
    if (!ddm) return;
    out.sensitivities.time.push_back(time);
    out.sensitivities.rows.push_back(sample_recorder_sensitivities(problem, nodes, mesh, model));
  };

  if (checkpoints && checkpoints->restore) {
    StateArchive a = StateArchive::restoring(*checkpoints->restore);
    archive_all(a);
    if (!a.at_end()) throw CheckpointError("checkpoint: its state is longer than this problem's");
  } else {
    auto t0 = Clock::now();
    place_moving_walls(problem, 0.0, {}, nodes);
    mesh = remesh_nodes(problem, nodes, remesh_options);
    if (!problem.sliding_walls.empty() || riders) {
      mesh::RemeshOptions placed = remesh_options;
      slide_walls(problem, mesh, nodes, 0.0);
      if (riders) placed.riders = riders->place(mesh, nodes, mesh::level_direction(problem.gx, problem.gy), problem.h);
      mesh = remesh_nodes(problem, nodes, placed);
    }
    sum.remesh_seconds += since(t0);
    sum.fluid_area_initial = sum.fluid_area_final = fluid_area(mesh, nodes);
    record(0.0);
    if (vtk) vtk->write(0.0, nodes, mesh, model);
  }
  // The volume correction (StepSettings::target_area): back to the initial area, less the water
  // in flight or gone (water_account.h), set at each step's start.
  settings.volume_relaxation = problem.volume_relaxation_steps * problem.dt;
  std::vector<double> target_sensitivity;
  const int first_step = sum.steps + 1;
  const double earlier_seconds = sum.wall_seconds;  // of the run before the restart
  const auto save_checkpoint = [&] {
    sum.wall_seconds = earlier_seconds + since(start);
    StateArchive a = StateArchive::saving();
    archive_all(a);
    write_checkpoint(checkpoints->file, {checkpoints->run, sum.steps, time_of(sum.steps), a.bytes()});
  };

  for (int n = first_step; n <= total_steps; ++n) {
    const bool shortened = short_last && n == total_steps;
    const double time = time_of(n);
    settings.dt = shortened ? last_dt : problem.dt;
    if (options.cancel && options.cancel->load()) {
      sum.status = RunStatus::kCancelled;
      sum.message = "cancelled before step " + std::to_string(n);
      // Between steps the state is whole: a restart continues from here.
      if (checkpoints && checkpoints->every > 0 && n > first_step) save_checkpoint();
      break;
    }
    try {
      if (n > 1) {  // the step-1 mesh is the initial one
        const auto t0 = Clock::now();
        mesh = remesh_after(problem, mesh, nodes, riders ? &*riders : nullptr, remesh_options, settings.dt,
                            time_of(n - 1));
        sum.remesh_seconds += since(t0);
      }
      state.water.update(mesh, nodes);
      settings.target_area = state.water.target(sum.fluid_area_initial, mesh, nodes, target_sensitivity);
      settings.target_area_sensitivity = target_sensitivity;
      const int iterations =
          advance_adaptive(problem, step, mesh, settings, remesh_options, riders ? &*riders : nullptr, nodes,
                           time_of(n - 1), problem.removal_distance * problem.h, options.cancel, sum);
      sum.max_elements = std::max<int>(sum.max_elements, static_cast<int>(mesh.triangles.size()));
      sum.steps = n;
      for (int i; (i = node_outside(nodes, problem.domain)) >= 0;) {
        if (problem.fail_on_exit) {
          std::ostringstream msg;
          msg << "particle " << i << " left the domain at (" << nodes.x[i] << ", " << nodes.y[i] << ")";
          throw StepFailure(msg.str());
        }
        nodes.kind[i] = mesh::NodeKind::Removed;  // is_fixed from now on: node_outside skips it
        state.water.leave(i);
        ++sum.left_domain;
      }
      sum.fluid_area_left = state.water.left();
      if (n % problem.record_every == 0 || n == total_steps) record(time);
      if (vtk && (n % vtk_every == 0 || n == total_steps)) vtk->write(time, nodes, mesh, model);
      sum.fluid_area_final = fluid_area(mesh, nodes);
      sum.fluid_area_max_drift = std::max(sum.fluid_area_max_drift,
                                          std::abs(sum.fluid_area_final / settings.target_area - 1.0));
      if (n < total_steps) {  // spacing for the next step (none after the last: the outputs are final)
        sum.removed_particles += mesh::remove_close_particles(mesh, nodes.x, nodes.y, nodes.kind,
                                                              problem.removal_distance * problem.h);
        sum.inserted_particles += insert_particles(mesh, problem, constraints, nodes);
        if (checkpoints && checkpoints->every > 0 && n % checkpoints->every == 0) save_checkpoint();
      }
      if (options.progress) {
        Progress pr;
        pr.step = n;
        pr.total_steps = total_steps;
        pr.time = time;
        pr.t_end = problem.t_end;
        pr.newton_iterations = iterations;
        pr.elapsed_seconds = since(start);
        pr.remaining_seconds = pr.elapsed_seconds / (n - first_step + 1) * (total_steps - n);
        options.progress(pr);
      }
    } catch (const StepCancelled&) {
      sum.status = RunStatus::kCancelled;
      sum.message = "cancelled during step " + std::to_string(n);
      break;
    } catch (const std::exception& e) {
      sum.status = RunStatus::kFailed;
      sum.failed_step = n;
      sum.failed_time = time;
      std::ostringstream msg;
      msg << "step " << n << " (t = " << time << " s): " << e.what();
      sum.message = msg.str();
      break;
    }
  }
  if (sum.left_domain > 0)
    sum.warnings.push_back(std::to_string(sum.left_domain) + " particle(s) left the domain and were removed");
  if (sum.fluid_area_max_drift > kAreaDriftWarning) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "the fluid area drifted by up to %.1f %% of its initial value (more than %g %%)",
                  100.0 * sum.fluid_area_max_drift, 100.0 * kAreaDriftWarning);
    sum.warnings.push_back(msg);
  }
  sum.wall_seconds = earlier_seconds + since(start);
  sum.response_seconds = sum.wall_seconds - sum.sensitivity_seconds;
  return std::move(out);
}

}  // namespace pfem
