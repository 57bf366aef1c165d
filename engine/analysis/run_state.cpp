#include "engine/analysis/run_state.h"

#include "engine/solve/fluid_step.h"
#include "engine/solve/fractional_step.h"

namespace pfem {

namespace {

void archive(StateArchive& a, NodeState& n) {
  a(n.x0), a(n.y0), a(n.x), a(n.y), a(n.vx), a(n.vy), a(n.p), a(n.side_p), a(n.rz), a(n.wz), a(n.kind);
  a.expect(static_cast<std::uint64_t>(n.num_params), "parameters of the nodes");
  a(n.sens);
  const std::size_t size = n.x.size();
  for (const auto* field : {&n.x0, &n.y0, &n.y, &n.vx, &n.vy, &n.p, &n.rz, &n.wz})
    if (field->size() != size) throw CheckpointError("checkpoint: node fields of different lengths");
  if (n.kind.size() != size || n.side_p.size() != size * mesh::kMaxPressureSides || n.sens.size() != size * n.num_params * NodeState::kSensitivityFields)
    throw CheckpointError("checkpoint: node fields of different lengths");
}

void archive(StateArchive& a, mesh::FluidMesh& m) {
  a(m.triangles), a(m.in_mesh), a(m.free_surface), a(m.contact_edges), a(m.sides), a(m.corner_side);
  std::vector<std::array<std::int32_t, 3>> riders;
  for (const auto& r : m.riders) riders.push_back({r.node, r.a, r.b});
  a(riders);
  m.riders.clear();
  for (const auto& [node, first, second] : riders) m.riders.push_back({node, first, second});
}

void archive(StateArchive& a, Histories& h) { a(h.columns), a(h.time), a(h.rows); }

// The counts and timings so far (status and message belong to the end of a run).
void archive(StateArchive& a, RunSummary& s) {
  a(s.steps), a(s.wall_seconds), a(s.sensitivity_seconds), a(s.remesh_seconds), a(s.assemble_seconds);
  a(s.factorize_seconds), a(s.solve_seconds), a(s.newton_iterations), a(s.factorizations), a(s.substeps);
  a(s.deformation_substeps);
  a(s.removed_particles), a(s.inserted_particles), a(s.left_domain), a(s.fluid_area_max_drift), a(s.particles);
  a(s.max_elements), a(s.fluid_area_initial), a(s.fluid_area_final), a(s.fluid_area_left);
}

}  // namespace

std::unique_ptr<StepSolver> make_step_solver(const Problem& problem) {
  if (problem.incompressible) return std::make_unique<FractionalStep>();
  return std::make_unique<UnifiedStep>();
}

void archive(StateArchive& a, RunState& state) {
  archive(a, state.nodes);
  archive(a, state.mesh);
  a.expect(state.structure.has_value(), "structures");
  if (state.structure) state.structure->archive(a);
  state.solver->archive(a);
  state.water.archive(a);
  archive(a, state.out.responses);
  archive(a, state.out.sensitivities);
  archive(a, state.out.summary);
}

}  // namespace pfem
