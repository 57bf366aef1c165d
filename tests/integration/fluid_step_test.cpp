// The Newton step: two exact block eliminations of the same system must agree (global bubbles
// with the unified fractional step vs bubbles condensed in each element), and still water must
// stay still with the hydrostatic pressure rho g h at the bottom.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/analysis/run.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "engine/solve/fluid_step.h"

namespace pfem {
namespace {

pfem::v1::Model example(const std::string& name) {
  return read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + name);
}

NodeState advance(const Problem& pb, StepSettings::Formulation formulation, int steps) {
  NodeState nodes = pb.nodes;
  StepSettings s;
  s.dt = pb.dt, s.fluid = pb.fluid, s.thickness = pb.thickness, s.gx = pb.gx, s.gy = pb.gy;
  s.formulation = formulation;
  UnifiedStep step;
  for (int k = 0; k < steps; ++k) {
    const auto mesh = mesh::remesh(nodes.x, nodes.y, nodes.kind, {pb.h, pb.alpha, pb.gx, pb.gy});
    step.advance(mesh, s, nodes);
  }
  return nodes;
}

TEST(FluidStep, GlobalAndCondensedBubbleFormulationsAgree) {
  auto model = example("dam-break.json");
  model.mutable_mesh()->set_h(0.01);
  const Problem pb = build_problem(model);
  const NodeState a = advance(pb, StepSettings::Formulation::kCondensedBubble, 15);
  const NodeState b = advance(pb, StepSettings::Formulation::kGlobalBubble, 15);
  double v_max = 0, p_max = 0, dv = 0, dp = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    v_max = std::max(v_max, std::hypot(a.vx[i], a.vy[i]));
    p_max = std::max(p_max, std::abs(a.p[i]));
    dv = std::max(dv, std::hypot(a.vx[i] - b.vx[i], a.vy[i] - b.vy[i]));
    dp = std::max(dp, std::abs(a.p[i] - b.p[i]));
  }
  ASSERT_GT(v_max, 0.05);  // the column is collapsing
  EXPECT_LT(dv, 1e-9 * v_max);
  EXPECT_LT(dp, 1e-9 * p_max);
}

TEST(FluidStep, SolverChoiceInTheModelGivesTheSameHistories) {
  auto model = example("dam-break.json");
  model.mutable_mesh()->set_h(0.01);
  RunOptions options;
  options.t_end = 0.03;
  const RunResult a = run(model, options);
  model.mutable_analysis()->set_solver("unified-fractional-step");
  const RunResult b = run(model, options);
  ASSERT_EQ(a.responses.rows.size(), b.responses.rows.size());
  const auto& ra = a.responses.rows.back();
  const auto& rb = b.responses.rows.back();
  for (std::size_t j = 0; j < ra.size(); ++j) EXPECT_NEAR(ra[j], rb[j], 1e-9 * (std::abs(ra[j]) + 1e-12)) << j;
  EXPECT_GT(ra[0], 0.146);  // front_x: the column has started to move
  model.mutable_analysis()->set_solver("gauss-seidel");
  EXPECT_THROW(run(model, options), ModelError);
}

TEST(FluidStep, StillWaterKeepsHydrostaticPressure) {
  auto model = example("hydrostatic.json");
  RunOptions options;
  options.t_end = 0.1;
  const RunResult r = run(model, options);
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const auto& last = r.responses.rows.back();
  const double rho_g_h = model.fluid().rho() * 9.81 * 0.2;
  EXPECT_NEAR(last[0], rho_g_h, 1e-3 * rho_g_h);  // bottom_p
  EXPECT_LT(last[2], 1e-4);                        // max_speed [m/s]
  EXPECT_NEAR(last[1], r.summary.fluid_area_initial, 1e-3 * r.summary.fluid_area_initial);
}

}  // namespace
}  // namespace pfem
