// A piston wavemaker standing on the floor of a 1 m flume, 0.1 m deep (tests/data/piston-tank.json):
//  - held still, the paddle seals the floor it stands on (which runs on behind it): the water
//    stays at rest with its level and area (a paddle 3 mm above the floor let it run out under
//    it: the level at 0.3 m fell by 12 % in 0.8 s and the run failed at 0.89 s);
//  - pushing, the paddle keeps the water's area (the water is incompressible: it only rises);
//  - a slip paddle on the slip floor pushes without a spike in its force, and so does the
//    closed flume's paddle (examples/wave-flume-wall.json);
//  - the DDM of the wave gauges, the force on the paddle and the area with respect to the stroke
//    and the period against central FDM (within 1e-4; the area, nearly constant, 1e-3).
// The same DDM with a slip paddle. And the DDM of a solitary wave's height and a table's scale,
// of examples/wave-flume-wall.json's flexible wall and gauge, and of examples/wave-flume.json's
// submerged plate (below).
// Biesel's transfer function: tests/slow/wavemaker_transfer_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "engine/analysis/gradient_check.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

pfem::v1::Model piston_tank() { return read_model_file(std::string(PFEM_SOURCE_DIR) + "/tests/data/piston-tank.json"); }

// The largest jump of column col from the mean of its neighbours in time, from t = 0.1 s (the
// first record is before the water's load): a single-step spike stands out, a wave does not.
double largest_jump(const Histories& h, int col) {
  double jump = 0.0;
  for (std::size_t i = 1; i + 1 < h.rows.size(); ++i)
    if (h.time[i - 1] >= 0.1) jump = std::max(jump, std::abs(h.rows[i][col] - 0.5 * (h.rows[i - 1][col] + h.rows[i + 1][col])));
  return jump;
}

TEST(Wavemaker, APaddleStandingOnTheFloorSealsIt) {
  auto model = piston_tank();
  model.mutable_walls(1)->clear_motion();
  model.clear_parameters();
  model.mutable_analysis()->set_t_end(2.0);
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const int eta = r.responses.column("eta"), far = r.responses.column("eta_far");
  ASSERT_GE(std::min(eta, far), 0);
  double worst = 0.0;
  for (const auto& row : r.responses.rows) worst = std::max({worst, std::abs(row[eta] - 0.1), std::abs(row[far] - 0.1)});
  std::printf("still paddle, 2 s: max |eta - d| %.2e m, max |A/A0 - 1| %.2e\n", worst, r.summary.fluid_area_max_drift);
  EXPECT_LT(worst, 1e-4);
  EXPECT_LT(r.summary.fluid_area_max_drift, 1e-4);
}

TEST(Wavemaker, ThePushedWaterKeepsItsArea) {
  auto model = piston_tank();
  model.clear_parameters();
  model.mutable_analysis()->set_t_end(3.0);
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const int eta = r.responses.column("eta");
  ASSERT_GE(eta, 0);
  double low = 1.0, high = 0.0;
  for (std::size_t i = 0; i < r.responses.rows.size(); ++i)
    if (r.responses.time[i] > 2.0) low = std::min(low, r.responses.rows[i][eta]), high = std::max(high, r.responses.rows[i][eta]);
  std::printf("pushing paddle, 3 s: max |A/A0 - 1| %.2e, wave height at 0.3 m after 2 s %.4f m\n",
              r.summary.fluid_area_max_drift, high - low);
  EXPECT_LT(r.summary.fluid_area_max_drift, 5e-3);
  EXPECT_GT(high - low, 0.003);  // a wave (Biesel: 0.0068 m for this stroke, before reflections)
}

// A slip paddle on the slip floor, 20 mm stroke: the force on it has no single-step spike. Its
// largest jump from the mean of its neighbours in time was 204 N (a 236 N force on its 50 N at
// 2.765 s, as the paddle turned): particles taken out beside its foot were never replaced, the
// alpha test opened a void on the floor there and its zero pressure sucked at the paddle.
TEST(Wavemaker, ASlipPaddleOnASlipFloorPushesWithoutSpikes) {
  auto model = piston_tank();
  model.clear_parameters();
  model.mutable_walls(1)->set_slip(true);
  model.mutable_walls(1)->mutable_motion()->mutable_sinusoid()->set_stroke(0.02);
  model.mutable_analysis()->set_t_end(3.0);
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const int fx = r.responses.column("paddle_fx");
  ASSERT_GE(fx, 0);
  const double jump = largest_jump(r.responses, fx);
  double largest = 0.0;
  for (const auto& row : r.responses.rows) largest = std::max(largest, std::abs(row[fx]));
  std::printf("slip paddle on a slip floor, 3 s: largest |force| %.1f N, largest jump %.2f N\n", largest, jump);
  EXPECT_LT(largest, 70.0);  // hydrostatic 49 N and the wave's
  EXPECT_LT(jump, 10.0);
}

// examples/wave-flume-wall.json to 5.6 s: its paddle's force jumped by 42 N at 5.58 s (on 41 N),
// when a particle at the paddle's foot, 0.2 h above the floor, made a triangle of circumradius
// 1.22 h that the alpha test dropped; inside the water the test now takes 1.25 alpha.
TEST(Wavemaker, TheClosedFlumesPaddleForceHasNoSpike) {
  auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/wave-flume-wall.json");
  model.clear_parameters();
  model.mutable_analysis()->set_t_end(5.6);
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const int fx = r.responses.column("paddle_fx");
  ASSERT_GE(fx, 0);
  const double jump = largest_jump(r.responses, fx);
  std::printf("closed flume to 5.6 s: the paddle force's largest jump %.2f N\n", jump);
  EXPECT_LT(jump, 10.0);
}

// Each parameter at its own FDM step: the stroke's at 1e-8 is round-off (2e-4 on the paddle
// force), the period's perturbed runs part at 1e-6 (remeshed apart at 0.705 s) and, since slip
// nodes go home with the wall's velocity there, at 1e-7 too (the paddle force's largest |FDM|
// 16.1 against 13.8 at 1e-8 and 1e-9).
TEST(Wavemaker, DdmOfGaugesAndPaddleForceMatchesCentralFdm) {
  int checked = 0;
  for (const auto& [param, eps] : {std::pair{"S", 1e-7}, std::pair{"T", 1e-8}}) {
    RunOptions options;
    options.t_end = 1.0;
    options.fdm_eps = eps;
    options.params = {param};
    const GradientCheck c = check_gradients(piston_tank(), options, true);
    ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
    ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
    for (const auto& r : c.rows) {
      std::printf("%-10s %-2s max|FDM| %.4e  DDM %.2e\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm, r.ddm);
      ++checked;
      EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
      // The area hardly changes: its FDM at this step is round-off against round-off (1e-4 there).
      EXPECT_LE(r.ddm, r.recorder == "fluid_area" ? 1e-3 : 1e-4) << r.recorder << "/" << r.parameter;
    }
  }
  EXPECT_EQ(checked, 8);
}

// A slip paddle: its nodes' vertical velocity is the water's, the one at the waterline the contact
// particle's (with its sensitivity); the DDM of the gauges and the paddle force w.r.t. the stroke.
TEST(Wavemaker, DdmOfASlipPaddleMatchesCentralFdm) {
  auto model = piston_tank();
  model.mutable_walls(1)->set_slip(true);
  RunOptions options;
  options.t_end = 1.0;
  options.fdm_eps = 1e-7;
  options.params = {"S"};
  const GradientCheck c = check_gradients(model, options, true);
  ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
  int checked = 0;
  for (const auto& r : c.rows) {
    std::printf("slip %-10s %-2s max|FDM| %.4e  DDM %.2e\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm, r.ddm);
    if (r.recorder == "fluid_area") continue;  // round-off against round-off (see above)
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder;
    EXPECT_LE(r.ddm, 1e-4) << r.recorder;
  }
  EXPECT_EQ(checked, 3);
}

// The piston tank driven by Goring's solitary trajectory (H = 0.2 d) and by a cubic table: the
// DDM of its gauges and paddle force with respect to the wave height and the table's scale.
TEST(Wavemaker, DdmOfASolitaryWavesHeightAndATablesScale) {
  for (const bool solitary : {true, false}) {
    auto model = piston_tank();
    auto* motion = model.mutable_walls(1)->mutable_motion();
    model.clear_parameters();
    auto* p = model.add_parameters();
    if (solitary) {
      motion->mutable_solitary()->set_height(0.02);
      motion->mutable_solitary()->set_depth(0.1);
      p->set_name("H"), p->add_targets("wavemaker.paddle.height");
    } else {
      auto* table = motion->mutable_table();
      for (const double t : {0.0, 0.3, 0.6, 1.0}) table->add_t(t);
      for (const double v : {0.0, 0.004, 0.001, 0.006}) table->add_s(v);
      table->set_interpolation("cubic");
      p->set_name("A"), p->add_targets("wavemaker.paddle.scale");
    }
    RunOptions options;
    options.t_end = 1.2;
    options.fdm_eps = 1e-7;
    const GradientCheck c = check_gradients(model, options, true);
    ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
    ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
    int checked = 0;
    for (const auto& r : c.rows) {
      if (r.recorder == "fluid_area") continue;  // nearly constant (see above)
      std::printf("%-10s %-2s max|FDM| %.4e  DDM %.2e\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm, r.ddm);
      ++checked;
      EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
      EXPECT_LE(r.ddm, 1e-4) << r.recorder << "/" << r.parameter;
    }
    EXPECT_EQ(checked, 3);
  }
}

// The DDM of the flume's recorders against central FDM to t_end, for each (parameter, FDM step);
// newton_tolerance > 0 replaces the model's (the FDM's noise is each run's Newton error over the step).
void expect_flume_ddm(const std::string& file, double t_end, const std::vector<std::string>& recorders,
                      std::initializer_list<std::pair<const char*, double>> cases, double newton_tolerance = 0.0) {
  auto flume = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + file);
  if (newton_tolerance > 0.0) flume.mutable_analysis()->set_newton_tolerance(newton_tolerance);
  for (const auto& [parameter, eps] : cases) {
    RunOptions options;
    options.t_end = t_end;
    options.fdm_eps = eps;
    options.params = {parameter};
    const GradientCheck c = check_gradients(flume, options, true);
    ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
    ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
    int checked = 0;
    for (const auto& r : c.rows) {
      if (std::find(recorders.begin(), recorders.end(), r.recorder) == recorders.end()) continue;
      std::printf("%-10s %-2s max|FDM| %.4e  DDM %.2e\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm, r.ddm);
      ++checked;
      EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
      EXPECT_LE(r.ddm, 1e-4) << r.recorder << "/" << r.parameter;
    }
    EXPECT_EQ(checked, static_cast<int>(recorders.size()));
  }
}

// examples/wave-flume-wall.json to 2.5 s (the first waves reach its flexible wall): the wall's
// tip, the gauge before it and the water's force on it, with respect to the stroke and the
// period (FDM step 1e-7). Newton tolerance 1e-12: at the default 1e-10 the gauge's FDM was
// 3.3e-3 off the DDM at a step of 1e-7, 3.3e-4 at 1e-6 and 3.3e-2 at 1e-8 (the runs' Newton error
// over the step; the wall's beam rider, which ends the surface at its contact line, changed
// their paths); at 1e-12, 1e-6. The period's perturbed runs remesh apart at a step of 1e-8 (at
// 1e-7 before the rider, at 0.95 s); at 1e-6 its FDM's truncation error is 2e-3 of the gauge's.
TEST(Wavemaker, DdmOfTheFlumesWallAndGaugeMatchesCentralFdm) {
  expect_flume_ddm("wave-flume-wall.json", 2.5, {"tip_ux", "eta_1.2", "plate_fx"}, {{"S", 1e-7}, {"T", 1e-7}}, 1e-12);
}

// examples/wave-flume.json to 2 s (the first waves pass over its submerged plate, water on both
// of its sides): the plate's tip, the water's force on it and the gauge behind it with respect to
// the stroke, the tip and the force with respect to the plate's E (the gauge's derivative with
// respect to E is 1e-11 m/Pa). FDM step 1e-6: at 1e-8 the FDM's round-off is 1e-4 of the gauge's
// derivative; to 2.5 s the perturbed runs remesh apart at both 1e-6 and 1e-7. Newton tolerance
// 1e-12: at the default 1e-10 each run's Newton error (about 1e-12 m in the gauge) over the
// stroke's step (2e-8 m) put the FDM 5e-4 off the gauge's derivative near 2 s (1e-7: 3e-3; the
// DDM's gap to each FDM scaling with 1 / step is the FDM's own error), 8e-5 at 1e-12.
TEST(Wavemaker, DdmOfTheSubmergedPlateAndTheGaugeBehindItMatchesCentralFdm) {
  expect_flume_ddm("wave-flume.json", 2.0, {"tip_ux", "eta_1.2", "plate_fx"}, {{"S", 1e-6}}, 1e-12);
  expect_flume_ddm("wave-flume.json", 2.0, {"tip_ux", "plate_fx"}, {{"E", 1e-6}}, 1e-12);
}

}  // namespace
}  // namespace pfem
