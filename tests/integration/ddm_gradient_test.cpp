// DDM against central finite differences on short versions of the paper's two examples
// (issue 4: "a short version of each (a few dozen steps) runs in the default test label"):
//  - sloshing-beam with the tank filled up to the beam, so that the water loads the beam from
//    the first step: tip_ux and base_p w.r.t. E, rho_f, mu, the out-of-plane thickness t and the
//    section width w; and b, the width linked to the thickness as in the paper, whose exact
//    derivative is zero (every force and stiffness then scales with it);
//  - dam-break-obstacle with a tall water column against the obstacle and a lower yield stress,
//    so that its base fibers yield within the run (a zero Fy sensitivity would fail the test):
//    tip_ux and the base fiber stress w.r.t. E and Fy.
// The largest |DDM - FDM| over time relative to the largest |FDM| must be below 1e-3 (the
// figure `pfem check-gradients` prints); the DDM without H and T must be visibly off.
// A directional parameter is the weighted sum of its parameters' DDM, from one solve. The DDM
// follows a beam rider where the surface meets a plate between two of its nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "engine/analysis/gradient_check.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

pfem::v1::Model example(const std::string& name) {
  return read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + name + ".json");
}

void set_region(pfem::v1::Model& model, double x0, double y0, double x1, double y1) {
  auto* r = model.mutable_fluid_regions(0)->mutable_rectangle();
  r->mutable_min()->set_x(x0), r->mutable_min()->set_y(y0);
  r->mutable_max()->set_x(x1), r->mutable_max()->set_y(y1);
}

GradientCheck check(const pfem::v1::Model& model, double t_end, std::vector<std::string> params) {
  RunOptions options;
  options.t_end = t_end;
  options.fdm_eps = 1e-6;  // FDM noise from the Newton tolerance reaches 1e-3 at 1e-7 here
  options.params = std::move(params);
  GradientCheck c = check_gradients(model, options, true);
  EXPECT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  EXPECT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
  for (const auto& r : c.rows)
    std::printf("%-18s %-6s max|FDM| %.4e  DDM %.2e  without H,T %.2e\n", r.recorder.c_str(), r.parameter.c_str(),
                r.max_fdm, r.ddm, r.without_geometric);
  return c;
}

// The rows of the given recorders pass the check and are not trivially zero; dropping H and T
// puts at least one of them off by more than `approximate_off`.
void expect_exact(const GradientCheck& c, const std::vector<std::string>& recorders, double approximate_off,
                  const std::string& skip_parameter = "") {
  double worst_approximate = 0.0;
  int checked = 0;
  for (const auto& r : c.rows) {
    if (std::find(recorders.begin(), recorders.end(), r.recorder) == recorders.end()) continue;
    if (r.parameter == skip_parameter) continue;
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LE(r.ddm, 1e-3) << r.recorder << "/" << r.parameter;
    worst_approximate = std::max(worst_approximate, r.without_geometric);
  }
  const int params = static_cast<int>(c.ddm.parameters.size()) - (skip_parameter.empty() ? 0 : 1);
  EXPECT_EQ(checked, params * static_cast<int>(recorders.size()));
  EXPECT_GT(worst_approximate, approximate_off);
}

TEST(DdmGradient, SloshingBeamLoadedFromTheStart) {
  auto model = example("sloshing-beam");
  set_region(model, 0.0, 0.0, 0.1, 0.06);  // water up to the beam, 0.06 m deep
  for (const auto& [name, target] : {std::pair{"t", "thickness"}, std::pair{"w", "section.square.width"}}) {
    auto* p = model.add_parameters();
    p->set_name(name);
    p->add_targets(target);
  }
  const GradientCheck c = check(model, 0.04, {"E", "rho_f", "mu", "t", "w", "b"});
  expect_exact(c, {"tip_ux", "base_p"}, 1e-2, "b");
  for (const auto& r : c.rows) {
    if (r.parameter != "b") continue;
    const auto t_row = std::find_if(c.rows.begin(), c.rows.end(), [&](const auto& o) {
      return o.recorder == r.recorder && o.parameter == "t";
    });
    EXPECT_LT(r.max_ddm, 1e-9 * t_row->max_ddm) << r.recorder;  // zero up to round-off
    EXPECT_LT(r.max_fdm, 1e-5 * t_row->max_fdm) << r.recorder;
    EXPECT_TRUE(r.negligible) << r.recorder;  // what check-gradients leaves out of its verdict
  }
  for (const auto& r : c.rows) EXPECT_EQ(r.negligible, r.parameter == "b") << r.recorder << "/" << r.parameter;
}

// A soft plate holding water whose surface meets it between two of its nodes for the whole run
// (0.04 m deep, nodes every 2.17 mm): the beam rider that ends the surface there (engine/mesh/
// beam_riders.h) moves with the plate and with its particle's level, and its rows go to the
// segment's ends by weights that move with that level too.
pfem::v1::Model plate_with_a_rider() {
  return parse_model_json(R"({
    "name": "plate", "thickness": 0.012,
    "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.0025},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.04}}}],
    "walls": [{"points": [{"x": 0.0, "y": 0.08}, {"x": 0.0, "y": 0.0}, {"x": 0.05, "y": 0.0}]}],
    "structure": {
      "nodes": [{"name": "base", "x": 0.05, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
                {"name": "tip", "x": 0.05, "y": 0.05}],
      "materials": [{"name": "soft", "elastic": {"e": 2e5}}],
      "sections": [{"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.012, "fibers": 10, "material": "soft"}}],
      "beams": [{"name": "plate", "from_node": "base", "to_node": "tip", "elements": 23,
                 "element_type": "elastic", "section": "square", "rho": 2500.0}]
    },
    "analysis": {"dt": 0.001, "t_end": 0.05},
    "recorders": [{"name": "tip_ux", "quantity": "ux", "node": "tip"},
                  {"name": "water_fx", "quantity": "force_x", "boundary": "plate"}],
    "parameters": [{"name": "E", "targets": ["material.soft.e"]},
                   {"name": "rho_f", "targets": ["fluid.rho"]},
                   {"name": "mu", "targets": ["fluid.mu"]}]
  })");
}

// Central FDM at eps 1e-5: the water's viscosity is 1e-3, and at 1e-6 the Newton tolerance's
// noise in the perturbed runs is 1.7e-4 of the force's sensitivity to it (1.9e-5 at 1e-5).
GradientCheck check_plate(const pfem::v1::Model& model) {
  RunOptions options;
  options.fdm_eps = 1e-5;
  options.params = {"E", "rho_f", "mu"};
  GradientCheck c = check_gradients(model, options, true);
  EXPECT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  for (const auto& r : c.rows)
    std::printf("%-9s %-6s max|FDM| %.4e  DDM %.2e  without H,T %.2e\n", r.recorder.c_str(), r.parameter.c_str(),
                r.max_fdm, r.ddm, r.without_geometric);
  return c;
}

// The DDM follows the rider, with the default solver and with the paper's global bubbles.
TEST(DdmGradient, ThroughABeamRiderAtTheWaterLevel) {
  auto model = plate_with_a_rider();
  for (const std::string solver : {"", "unified-fractional-step"}) {
    if (!solver.empty()) model.mutable_analysis()->set_solver(solver);
    const GradientCheck c = check_plate(model);
    for (const auto& r : c.rows) EXPECT_LE(r.ddm, 5e-5) << solver << " " << r.recorder << "/" << r.parameter;
    expect_exact(c, {"tip_ux", "water_fx"}, 1e-3);
  }
}

// The incompressible formulation's approximate DDM (the geometric terms on the previous step's
// sensitivities) takes the rider's terms as the exact DDM does: with them the tip's and the
// force's sensitivities to rho_f and mu are within 2.8e-5, 1.05e-4, 3.0e-4 and 2.4e-4 of central
// FDM; without the rider's moving-level terms 3.3e-4, 3.3e-4, 6.1e-3 and 1.2e-3.
TEST(DdmGradient, TheIncompressibleDdmThroughABeamRider) {
  auto model = plate_with_a_rider();
  model.mutable_analysis()->set_formulation("incompressible");
  model.mutable_fluid()->set_kappa(0.0);
  const GradientCheck c = check_plate(model);
  EXPECT_EQ(c.ddm.sensitivity_method, "ddm-approximate");
  const auto off = [&](const std::string& recorder, const std::string& parameter) {
    for (const auto& r : c.rows)
      if (r.recorder == recorder && r.parameter == parameter) return r.ddm;
    ADD_FAILURE() << recorder << "/" << parameter;
    return 1.0;
  };
  EXPECT_LT(off("tip_ux", "rho_f"), 1e-4);
  EXPECT_LT(off("water_fx", "rho_f"), 2e-4);
  EXPECT_LT(off("tip_ux", "mu"), 1e-3);
  EXPECT_LT(off("water_fx", "mu"), 6e-4);
}

TEST(DdmGradient, DamBreakObstacleYieldsWithinTheRun) {
  auto model = example("dam-break-obstacle");
  set_region(model, 0.19, 0.0, 0.292, 0.2);  // a 0.2 m column leaning on the obstacle
  for (auto& p : *model.mutable_parameters())
    if (p.name() == "Fy") p.set_value(1.2e4);  // the base fiber reaches it at ~0.02 s
  const GradientCheck c = check(model, 0.04, {"E", "Fy"});
  expect_exact(c, {"tip_ux", "base_fiber_stress"}, 1e-2);
}

// The elastic obstacle's front meets the obstacle at 0.127 s: steps there are halved before their
// attempt where a triangle would collapse (engine/mesh/deformation_cfl.h), a decision the DDM
// follows as it stands, so the sensitivities stay exact through those substeps.
TEST(DdmGradient, ThroughStepsHalvedBeforeTheirAttempt) {
  const GradientCheck c = check(example("dam-break-elastic-obstacle"), 0.16, {"E"});
  EXPECT_GT(c.ddm.deformation_substeps, 0);
  expect_exact(c, {"tip_ux", "base_p"}, 1e-2);
}

// A parameter at the bound of its range (a viscosity of 0: mu - eps is no model) is
// differentiated one-sided by the FDM, against the unperturbed run; the DDM needs no care.
TEST(DdmGradient, AViscosityOfZeroIsCheckedOneSided) {
  auto model = example("dam-break");
  model.mutable_mesh()->set_h(0.01);
  for (auto& p : *model.mutable_parameters())
    if (p.name() == "mu") p.set_value(0.0);
  const GradientCheck c = check(model, 0.05, {"mu"});
  for (const auto& r : c.rows) {
    if (r.recorder != "front_x" && r.recorder != "left_wall_p") continue;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder;
    EXPECT_FALSE(r.negligible) << r.recorder;
    EXPECT_LE(r.ddm, 1e-3) << r.recorder;
  }
}

// Up to two parameters the step's sensitivity system is solved by GMRES preconditioned with the
// Newton factorisation, above that by the Jacobian's LU, each to a relative residual of 1e-13:
// the same sensitivities either way, within 1e-8 of their largest (measured 9e-12 to 1.8e-9
// over 40 steps; 4e-14 to 2.6e-11 when both solved to 1e-14).
TEST(DdmGradient, IterativeAndDirectSensitivitySolvesAgree) {
  auto model = example("dam-break-obstacle");
  set_region(model, 0.19, 0.0, 0.292, 0.2);
  for (auto& p : *model.mutable_parameters())
    if (p.name() == "Fy") p.set_value(1.2e4);
  for (const auto& [name, target] : {std::pair{"hardening", "material.steel.hardening_ratio"},
                                     std::pair{"depth", "section.obstacle.depth"}, std::pair{"rho_s", "beam.obstacle.rho"}}) {
    auto* p = model.add_parameters();
    p->set_name(name);
    p->add_targets(target);
  }
  RunOptions options;
  options.t_end = 0.04;
  options.sensitivity = SensitivityMethod::kDdm;
  options.params = {"E"};
  const RunResult iterative = run(model, options);
  options.params = {"E", "Fy", "rho_f", "mu", "kappa", "hardening", "depth", "rho_s"};
  const RunResult direct = run(model, options);
  ASSERT_EQ(iterative.summary.status, RunStatus::kCompleted) << iterative.summary.message;
  ASSERT_EQ(direct.summary.status, RunStatus::kCompleted) << direct.summary.message;
  for (std::size_t j = 0; j < iterative.sensitivities.columns.size(); ++j) {
    const std::string& name = iterative.sensitivities.columns[j];  // d<recorder>/dE
    const int k = direct.sensitivities.column(name);
    ASSERT_GE(k, 0) << name;
    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < iterative.sensitivities.rows.size(); ++i) {
      scale = std::max(scale, std::abs(direct.sensitivities.rows[i][k]));
      diff = std::max(diff, std::abs(iterative.sensitivities.rows[i][j] - direct.sensitivities.rows[i][k]));
    }
    std::printf("%-26s max |d/dE| %.4e  max |GMRES - LU| / that %.2e\n", name.c_str(), scale,
                scale > 0.0 ? diff / scale : diff);
    EXPECT_GT(scale, 0.0) << name;
    EXPECT_LT(diff, 1e-8 * scale) << name;
  }
}

// Sloshing in a tank with free-slip walls (issue 14): the wall nodes carry a tangential velocity
// unknown and slide to the contact line; the wave gauge (a free edge's crossing with a fixed
// vertical line) and the pressure at a fixed point (interpolated in the triangle that holds it)
// are differentiated on dual numbers through the nodes' sensitivities. DDM against central FDM.
// The free surface 0.1 + 0.005 cos(pi x / 0.2) of a 0.2 m tank, from x = 0.2 to 0, as polygon
// points (each after a comma).
std::string tank_surface() {
  std::string points;
  for (int i = 0; i <= 20; ++i) {
    const double x = 0.2 - 0.01 * i;
    points += R"(, {"x": )" + std::to_string(x) + R"(, "y": )" + std::to_string(0.1 + 0.005 * std::cos(M_PI * x / 0.2)) + "}";
  }
  return points;
}

TEST(DdmGradient, SlipWallTankWithAWaveGaugeAndAPressurePoint) {
  const std::string points = tank_surface();
  const auto model = parse_model_json(R"({
    "name": "slip-tank", "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9}, "mesh": {"h": 0.01},
    "fluid_regions": [{"polygon": {"points": [{"x": 0, "y": 0}, {"x": 0.2, "y": 0})" + points + R"(]}}],
    "walls": [{"points": [{"x": 0, "y": 0.2}, {"x": 0, "y": 0}, {"x": 0.2, "y": 0}, {"x": 0.2, "y": 0.2}], "slip": true}],
    "analysis": {"dt": 0.004, "t_end": 0.12},
    "recorders": [{"name": "gauge", "quantity": "wave_gauge", "point": {"x": 0.005, "y": 0.1}},
                  {"name": "p_mid", "quantity": "pressure", "point": {"x": 0.1, "y": 0.03}},
                  {"name": "p_wall", "quantity": "pressure", "point": {"x": 0.2, "y": 0.05}}],
    "parameters": [{"name": "rho_f", "targets": ["fluid.rho"]}, {"name": "mu", "targets": ["fluid.mu"]},
                   {"name": "kappa", "targets": ["fluid.kappa"]}]
  })");
  const GradientCheck c = check(model, 0.12, {"rho_f", "mu", "kappa"});
  int checked = 0;
  for (const auto& r : c.rows) {
    if (r.negligible) continue;  // a gauge's rho and kappa sensitivities are round-off small
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LE(r.ddm, 1e-3) << r.recorder << "/" << r.parameter;
  }
  EXPECT_GE(checked, 4);  // at least the two pressures w.r.t. rho_f and mu
}

// The volume correction (mesh.volume_relaxation_steps) at its strongest, 1 step: each step
// gives the whole area the remeshings made or lost back to the water, through the mesh's area
// at t_n, whose sensitivity comes from every node's. The collapsing column's area, front and
// wall pressure against central FDM.
TEST(DdmGradient, DamBreakWithTheStrongestVolumeCorrection) {
  auto model = example("dam-break");
  model.mutable_mesh()->set_h(0.01);
  model.mutable_mesh()->set_volume_relaxation_steps(1.0);
  const GradientCheck c = check(model, 0.25, {"rho_f", "mu"});
  int checked = 0;
  for (const auto& r : c.rows) {
    if (r.negligible) continue;
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LE(r.ddm, 1e-4) << r.recorder << "/" << r.parameter;
  }
  EXPECT_GE(checked, 4);
}

// The fluid's resultant force and moment on a wall and on a beam (traction integrals along the
// edges on them): their DDM sensitivities against central FDM, in a slip-wall tank sloshing
// around a flexible post.
TEST(DdmGradient, ForceAndMomentOnAWallAndABeam) {
  const std::string points = tank_surface();
  const auto model = parse_model_json(R"({
    "name": "slip-tank-forces", "thickness": 0.05, "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.01},
    "fluid_regions": [{"polygon": {"points": [{"x": 0, "y": 0}, {"x": 0.2, "y": 0})" + points + R"(]}}],
    "walls": [{"name": "tank", "points": [{"x": 0, "y": 0.2}, {"x": 0, "y": 0}, {"x": 0.2, "y": 0}, {"x": 0.2, "y": 0.2}], "slip": true}],
    "structure": {
      "nodes": [{"name": "base", "x": 0.055, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}}, {"name": "tip", "x": 0.055, "y": 0.06}],
      "materials": [{"name": "m", "elastic": {"e": 5e5}}],
      "sections": [{"name": "s", "fiber_rectangle": {"width": 0.05, "depth": 0.006, "fibers": 6, "material": "m"}}],
      "beams": [{"name": "post", "from_node": "base", "to_node": "tip", "elements": 6, "element_type": "elastic",
                 "section": "s", "transformation": "corotational", "rho": 1200.0}]
    },
    "analysis": {"dt": 0.004, "t_end": 0.2},
    "recorders": [{"name": "tank_fx", "quantity": "force_x", "boundary": "tank"},
                  {"name": "tank_m", "quantity": "moment", "boundary": "tank", "about": {"x": 0.1, "y": 0.0}},
                  {"name": "post_fx", "quantity": "force_x", "boundary": "post"},
                  {"name": "post_fy", "quantity": "force_y", "boundary": "post"},
                  {"name": "post_m", "quantity": "moment", "boundary": "post"}],
    "parameters": [{"name": "rho_f", "targets": ["fluid.rho"]}, {"name": "mu", "targets": ["fluid.mu"]},
                   {"name": "E", "targets": ["material.m.e"]}, {"name": "t", "targets": ["thickness"]}]
  })");
  const GradientCheck c = check(model, 0.2, {"rho_f", "mu", "E", "t"});
  int checked = 0;
  for (const auto& r : c.rows) {
    if (r.negligible) continue;
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LE(r.ddm, 1e-3) << r.recorder << "/" << r.parameter;
    if (r.recorder.rfind("tank", 0) == 0) {
      EXPECT_LE(r.ddm, 1e-4) << r.recorder << "/" << r.parameter;
    }
  }
  EXPECT_GE(checked, 16);
}

// A directional parameter "dir" weighing the given parameters (model.proto, Parameter.direction):
// from one sensitivity solve per step (one sensitivity column per recorder) its DDM is the
// weighted sum of theirs from a P-parameter run to 1e-10 of the terms' size (the largest over
// time of sum_k |w_k d/dtheta_k|: the terms may cancel; measured 3e-13 to 2e-11, the step's
// sensitivity solves stop at a residual of 1e-13), with the same responses bit for bit;
// and it matches the engine's central differences along it (two runs at v_k +- w_k s) within
// 1e-4 of their largest.
void check_direction(pfem::v1::Model model, double t_end,
                     const std::vector<std::pair<std::string, double>>& weights,
                     const std::vector<std::string>& recorders) {
  RunOptions options;
  options.t_end = t_end;
  options.sensitivity = SensitivityMethod::kDdm;
  for (const auto& [name, weight] : weights) options.params.push_back(name);
  const RunResult each = run(model, options);
  auto* dir = model.add_parameters();
  dir->set_name("dir");
  for (const auto& [name, weight] : weights) {
    auto* w = dir->add_direction();
    w->set_parameter(name);
    w->set_weight(weight);
  }
  options.params = {"dir"};
  const RunResult one = run(model, options);
  EXPECT_EQ(each.summary.status, RunStatus::kCompleted) << each.summary.message;
  EXPECT_EQ(one.summary.status, RunStatus::kCompleted) << one.summary.message;
  EXPECT_EQ(one.summary.parameters, std::vector<std::string>{"dir"});
  EXPECT_EQ(one.summary.parameter_values, std::vector<double>{0.0});
  EXPECT_EQ(one.sensitivities.columns.size(), static_cast<std::size_t>(model.recorders_size()));
  EXPECT_EQ(each.sensitivities.columns.size(), model.recorders_size() * weights.size());
  EXPECT_EQ(one.responses.rows, each.responses.rows);  // the seeds do not touch the response

  for (const auto& r : model.recorders()) {
    const int j = one.sensitivities.column("d" + r.name() + "/ddir");
    ASSERT_GE(j, 0) << r.name();
    // scale: the largest sum_k |w_k d/dtheta_k|, the size of the terms (they may cancel).
    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < one.sensitivities.rows.size(); ++i) {
      double expected = 0.0, terms = 0.0;
      for (const auto& [name, weight] : weights) {
        const int k = each.sensitivities.column("d" + r.name() + "/d" + name);
        ASSERT_GE(k, 0) << name;
        const double term = weight * each.sensitivities.rows[i][k];
        expected += term;
        terms += std::abs(term);
      }
      scale = std::max(scale, terms);
      diff = std::max(diff, std::abs(one.sensitivities.rows[i][j] - expected));
    }
    std::printf("%-18s max sum_k |w_k d/dtheta_k| %.4e  max |dir - sum w_k d/dtheta_k| / that %.2e\n",
                r.name().c_str(), scale, scale > 0.0 ? diff / scale : diff);
    if (std::find(recorders.begin(), recorders.end(), r.name()) == recorders.end()) continue;
    EXPECT_GT(scale, 0.0) << r.name();
    EXPECT_LE(diff, 1e-10 * scale) << r.name();
  }

  const GradientCheck c = check(model, t_end, {"dir"});
  for (const auto& r : c.rows) {
    if (std::find(recorders.begin(), recorders.end(), r.recorder) == recorders.end()) continue;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder;
    EXPECT_LE(r.ddm, 1e-4) << r.recorder;
  }
}

TEST(DdmGradient, ADirectionalParameterIsTheWeightedSumOfItsParametersOnABeam) {
  auto model = example("sloshing-beam");
  set_region(model, 0.0, 0.0, 0.1, 0.06);  // as in SloshingBeamLoadedFromTheStart
  auto* w = model.add_parameters();
  w->set_name("w");
  w->add_targets("section.square.width");
  // Weights of the parameters' size (E ~ 1e6 Pa, rho_f 1000, mu 1e-3, w ~ 1e-2 m), mixed signs.
  check_direction(model, 0.04, {{"E", 4e5}, {"rho_f", -300.0}, {"mu", 2e-3}, {"w", 5e-3}},
                  {"tip_ux", "base_p"});
}

TEST(DdmGradient, ADirectionalParameterIsTheWeightedSumOfItsParametersInWaterAlone) {
  auto model = example("dam-break");
  model.mutable_mesh()->set_h(0.01);
  check_direction(model, 0.05, {{"rho_f", 200.0}, {"mu", -5e-4}, {"kappa", 1e9}},
                  {"front_x", "left_wall_p"});
}

}  // namespace
}  // namespace pfem
