// Water on both sides of a wall or a beam drawn as one line: each side has its own pressure at
// the line's nodes (mesh::FluidMesh::sides), so the line carries the difference. With one
// pressure per node for both sides the two levels below could not stand (the pressure's load
// cancelled wherever both sides were wet): the still water beside a rigid divider reached
// 1.15 m/s within 0.5 s and the force on the divider was a third of hydrostatics'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/gradient_check.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kRho = 1000.0, kG = 9.81;

// Still water 0.2 m deep left and 0.1 m deep right of a rigid divider (a wall of one line)
// standing on the floor of a 0.4 m tank: the divider carries rho g (h1^2 - h2^2) / 2 per unit
// thickness, each side's pressure is its own hydrostatic one, and the water stays at rest.
TEST(TwoSidedWalls, ARigidDividerHoldsTwoLevels) {
  const auto model = parse_model_json(R"({
    "name": "divider", "thickness": 1.0,
    "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.01},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.2, "y": 0.2}}},
                      {"rectangle": {"min": {"x": 0.2, "y": 0.0}, "max": {"x": 0.4, "y": 0.1}}}],
    "walls": [{"name": "box", "points": [{"x": 0.0, "y": 0.3}, {"x": 0.0, "y": 0.0}, {"x": 0.4, "y": 0.0}, {"x": 0.4, "y": 0.3}]},
              {"name": "divider", "points": [{"x": 0.2, "y": 0.0}, {"x": 0.2, "y": 0.3}]}],
    "domain": {"min": {"x": -0.1, "y": -0.1}, "max": {"x": 0.5, "y": 0.4}},
    "analysis": {"dt": 0.002, "t_end": 0.5},
    "recorders": [{"name": "fx", "quantity": "force_x", "boundary": "divider"},
                  {"name": "p_left", "quantity": "pressure", "point": {"x": 0.19, "y": 0.05}},
                  {"name": "p_right", "quantity": "pressure", "point": {"x": 0.21, "y": 0.05}},
                  {"name": "area", "quantity": "fluid_area"},
                  {"name": "speed", "quantity": "max_speed"}]
  })");
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const auto& last = r.responses.rows.back();
  const double force = kRho * kG * (0.2 * 0.2 - 0.1 * 0.1) / 2.0;
  std::printf("divider force %.5f N (hydrostatic %.5f), p left %.2f Pa (%.2f), right %.2f Pa (%.2f), speed %.2e m/s\n",
              last[0], force, last[1], kRho * kG * 0.15, last[2], kRho * kG * 0.05, last[4]);
  EXPECT_NEAR(last[0], force, 1e-3 * force);
  EXPECT_NEAR(last[1], kRho * kG * 0.15, 1e-3 * kRho * kG * 0.15);
  EXPECT_NEAR(last[2], kRho * kG * 0.05, 1e-3 * kRho * kG * 0.05);
  EXPECT_NEAR(last[3], 0.06, 1e-5 * 0.06);
  double speed = 0.0;
  for (const auto& row : r.responses.rows) speed = std::max(speed, row[4]);
  EXPECT_LT(speed, 1e-3);
}

// A cantilever plate standing in a tank with water 0.05 m deep on its left and 0.02 m on its
// right: the net load per length is rho g t [(h1 - s)+ - (h2 - s)+] at height s, and the damped
// plate settles to the small-deflection tip deflection int q(s) s^2 (3 L - s) / (6 EI) ds and
// the base moment int q(s) s ds (integrated here by Simpson's rule, exact for the pieces).
std::string plate_model() {
  return R"({
    "name": "plate-two-levels", "thickness": 0.012,
    "fluid": {"rho": 1000.0, "mu": 0.01, "kappa": 2.15e9},
    "mesh": {"h": 0.0025},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.05}}},
                      {"rectangle": {"min": {"x": 0.05, "y": 0.0}, "max": {"x": 0.1, "y": 0.02}}}],
    "walls": [{"name": "tank", "points": [{"x": 0.0, "y": 0.08}, {"x": 0.0, "y": 0.0}, {"x": 0.1, "y": 0.0}, {"x": 0.1, "y": 0.08}]}],
    "structure": {
      "nodes": [{"name": "base", "x": 0.05, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
                {"name": "tip", "x": 0.05, "y": 0.06}],
      "materials": [{"name": "stiff", "elastic": {"e": 1e7}}],
      "sections": [{"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.012, "fibers": 10, "material": "stiff"}}],
      "beams": [{"name": "plate", "from_node": "base", "to_node": "tip", "elements": 24,
                 "element_type": "elastic", "section": "square", "rho": 2500.0}],
      "rayleigh": {"a0": 0.0, "a1": 0.002}, "self_weight": false
    },
    "domain": {"min": {"x": -0.05, "y": -0.05}, "max": {"x": 0.15, "y": 0.15}},
    "analysis": {"dt": 0.001, "t_end": 0.4},
    "recorders": [{"name": "tip_ux", "quantity": "ux", "node": "tip"},
                  {"name": "base_moment", "quantity": "basic_force", "element": "plate/1", "component": 1},
                  {"name": "water_fx", "quantity": "force_x", "boundary": "plate"},
                  {"name": "p_left", "quantity": "pressure", "point": {"x": 0.045, "y": 0.01}},
                  {"name": "area", "quantity": "fluid_area"}],
    "parameters": [{"name": "E", "targets": ["material.stiff.e"]}, {"name": "rho_f", "targets": ["fluid.rho"]}]
  })";
}

TEST(TwoSidedWalls, APlateBetweenTwoLevelsSettlesToBeamTheory) {
  const RunResult r = run(parse_model_json(plate_model()), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  constexpr double kL = 0.06, kB = 0.012, kH1 = 0.05, kH2 = 0.02;
  const double ei = 1e7 * kB * std::pow(kB, 3) / 12.0;
  const auto q = [&](double s) { return kRho * kG * kB * (std::max(kH1 - s, 0.0) - std::max(kH2 - s, 0.0)); };
  double tip = 0.0, moment = 0.0, force = 0.0;
  const auto simpson = [&](double a, double b) {  // q is linear on [a, b]
    constexpr int kN = 200;
    for (int i = 0; i <= kN; ++i) {
      const double s = a + (b - a) * i / kN, w = (i == 0 || i == kN ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (b - a) / (3.0 * kN);
      tip += w * q(s) * s * s * (3.0 * kL - s) / (6.0 * ei), moment += w * q(s) * s, force += w * q(s);
    }
  };
  simpson(0.0, kH2), simpson(kH2, kH1);
  const auto& last = r.responses.rows.back();
  std::printf("tip %.5e m (beam theory %.5e, %+.2f %%), base moment %.5e N m (%.5e), water force %.5e N (%.5e)\n",
              last[0], tip, 100.0 * (last[0] / tip - 1.0), std::abs(last[1]), moment, last[2], force);
  EXPECT_NEAR(last[0], tip, 0.02 * tip);
  EXPECT_NEAR(std::abs(last[1]), moment, 0.02 * moment);
  EXPECT_NEAR(last[2], force, 0.01 * force);
  EXPECT_NEAR(last[3], kRho * kG * (kH1 - 0.01), 0.01 * kRho * kG * (kH1 - 0.01));
  EXPECT_LT(r.summary.fluid_area_max_drift, 1e-3);
}

// The plate's start-up (the levels released at t = 0, water on both faces): the DDM of its tip,
// the water's force on it and a pressure beside it, against central FDM.
TEST(TwoSidedWalls, DdmOfAPlateWetOnBothSidesMatchesCentralFdm) {
  RunOptions options;
  options.t_end = 0.04;
  options.fdm_eps = 1e-6;
  const GradientCheck c = check_gradients(parse_model_json(plate_model()), options, false);
  ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
  int checked = 0;
  for (const auto& row : c.rows) {
    std::printf("%-12s %-6s max|FDM| %.4e  DDM %.2e\n", row.recorder.c_str(), row.parameter.c_str(), row.max_fdm,
                row.ddm);
    if (row.recorder == "area" || row.negligible) continue;
    ++checked;
    EXPECT_LE(row.ddm, 1e-4) << row.recorder << "/" << row.parameter;
  }
  EXPECT_GE(checked, 6);
}

}  // namespace
}  // namespace pfem
