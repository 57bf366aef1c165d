// The incompressible formulation (analysis.formulation "incompressible", engine/solve/
// fractional_step.h) on flows with a closed-form answer:
//  - still water in a closed box whose width is not a multiple of h stays still, keeps its area
//    and carries rho g d at the bottom (d its mean depth: its area over the box's width);
//  - the sloshing beam's DDM to 0.15 s, its first impact on the beam: the quasi-incompressible
//    DDM matches central finite differences, the incompressible formulation's approximate DDM
//    already does not (the long windows and the tips of both examples: tests/slow/);
//  - validation of the formulation's fields (unknown formulation, a bulk modulus it ignores,
//    the quasi-incompressible solver's setting), each with its field path.
// Start-up Poiseuille flow: viscous_test.cpp; the still cantilever: fsi_still_water_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "engine/io/model_warnings.h"
#include "tests/integration/formulation_comparison.h"

namespace pfem {
namespace {

constexpr double kWidth = 0.173, kG = 9.81, kRho = 1000.0;

const char* kStillWater = R"({
  "name": "incompressible-still-water",
  "description": "0.173 m x 0.11 m of water at rest in a closed box 0.173 m wide (h = 0.01: the particle grid's last column is 1.3 h from the right wall).",
  "fluid": {"rho": 1000.0, "mu": 0.001},
  "mesh": {"h": 0.01},
  "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.173, "y": 0.11}}}],
  "walls": [{"points": [{"x": 0.0, "y": 0.0}, {"x": 0.173, "y": 0.0}, {"x": 0.173, "y": 0.2}, {"x": 0.0, "y": 0.2}],
             "closed": true}],
  "analysis": {"dt": 0.002, "t_end": 1.0, "formulation": "incompressible"},
  "recorders": [{"name": "bottom_p", "quantity": "p", "point": {"x": 0.08, "y": 0.0}},
                {"name": "fluid_area", "quantity": "fluid_area"},
                {"name": "max_speed", "quantity": "max_speed"}]
})";

TEST(Incompressible, StillWaterKeepsRhoGDAtTheBottomAndItsArea) {
  const RunResult r = run(parse_model_json(kStillWater), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const auto& h = r.responses;
  const int p = h.column("bottom_p"), area = h.column("fluid_area"), speed = h.column("max_speed");
  ASSERT_GE(std::min({p, area, speed}), 0);
  const double area0 = h.rows.front()[area], rho_g_d = kRho * kG * area0 / kWidth;
  double worst_p = 0.0, worst_area = 0.0, fastest = 0.0;
  for (std::size_t i = 1; i < h.time.size(); ++i) {  // from the first step on: t = 0 has no pressure yet
    worst_p = std::max(worst_p, std::abs(h.rows[i][p] / rho_g_d - 1.0));
    worst_area = std::max(worst_area, std::abs(h.rows[i][area] / area0 - 1.0));
    fastest = std::max(fastest, h.rows[i][speed]);
  }
  std::printf(
      "mean depth %.5f m, rho g d = %.2f Pa, bottom_p at %.1f s %.2f Pa; largest deviation %.4f %%, largest "
      "area change %.2e, fastest particle %.2e m/s; %ld iterations in %d steps\n",
      area0 / kWidth, rho_g_d, h.time.back(), h.rows.back()[p], 100 * worst_p, worst_area, fastest,
      r.summary.newton_iterations, r.summary.steps);
  EXPECT_LT(worst_p, 0.01);
  EXPECT_LT(worst_area, 0.001);
}

TEST(Incompressible, OnlyTheQuasiIncompressibleDdmMatchesFdmOnTheSloshingBeam) {
  expect_only_the_exact_ddm_matches("sloshing-beam", 0.15, {"E", "rho_f"});
}

pfem::v1::Model still_water() { return parse_model_json(kStillWater); }

TEST(Incompressible, AnUnknownFormulationIsAFieldError) {
  auto model = still_water();
  model.mutable_analysis()->set_formulation("compressible");
  model.mutable_fluid()->set_kappa(2.15e9);  // what the quasi-incompressible default needs
  const auto errors = validate_model(model);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].to_string(),
            "analysis.formulation: must be quasi-incompressible or incompressible (got 'compressible')");
}

TEST(Incompressible, TheQuasiIncompressibleSolverSettingIsAFieldError) {
  auto model = still_water();
  model.mutable_analysis()->set_solver("condensed-bubble");
  const auto errors = validate_model(model);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].path, "analysis.solver");
}

TEST(Incompressible, ABulkModulusIsIgnoredWithAWarningOnTheField) {
  auto model = still_water();
  model.mutable_fluid()->set_kappa(2.15e9);
  EXPECT_TRUE(validate_model(model).empty());
  const auto warnings = model_warnings(model);
  const auto it =
      std::find_if(warnings.begin(), warnings.end(), [](const FieldError& w) { return w.path == "fluid.kappa"; });
  ASSERT_NE(it, warnings.end());
  EXPECT_NE(it->message.find("ignored"), std::string::npos) << it->message;
  // The run says so too, and the water is the same as without it.
  RunOptions options;
  options.t_end = 0.01;
  const RunResult with = run(model, options), without = run(still_water(), options);
  ASSERT_EQ(with.summary.warnings.size(), 1u);
  EXPECT_EQ(with.summary.warnings[0].rfind("fluid.kappa: is ignored", 0), 0u) << with.summary.warnings[0];
  EXPECT_TRUE(without.summary.warnings.empty());
  EXPECT_EQ(with.responses.rows, without.responses.rows);
  // The quasi-incompressible formulation needs one.
  model.mutable_analysis()->clear_formulation();
  model.mutable_fluid()->clear_kappa();
  const auto errors = validate_model(model);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].to_string(), "fluid.kappa: must be > 0");
}

}  // namespace
}  // namespace pfem
