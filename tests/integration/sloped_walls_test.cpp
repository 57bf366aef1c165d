// Water against walls that are neither vertical nor level (engine/mesh/contact_line.h), at
// water's viscosity: the wall node at the contact line goes to the wall's point level with the
// last surface particle. Where it went to the particle's foot (square to the wall), the free edge
// on a wall at 60 degrees sloped at 30 degrees: still water in the trapezoid below moved at
// 0.175 m/s within 1 s (walls at 30 and 75 degrees: 0.12 and 0.15 m/s), and the tilted surface
// in the right-angled V tank swung 2.3 % fast against Kirchhoff's exact period (0.8 % now, at 30
// particles to the depth).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/analysis/gradient_check.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kG = 9.81, kRho = 1000.0;

// A model with one no-slip wall "tank" and one polygon of water, each a list of point() objects.
std::string model(const std::string& wall, const std::string& water, double h, double dt, double t_end,
                  const std::string& recorders, const std::string& extra = "") {
  char head[512];
  std::snprintf(head, sizeof head, R"({"name": "sloped", "fluid": {"rho": %.17g, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": %.17g}, "analysis": {"dt": %.17g, "t_end": %.17g},)", kRho, h, dt, t_end);
  return head + std::string(R"("walls": [{"name": "tank", "points": [)") + wall + R"(]}],
    "fluid_regions": [{"polygon": {"points": [)" + water + R"(]}}],
    "recorders": [)" + recorders + "]" + extra + "}";
}

std::string point(double x, double y) {
  char p[96];
  std::snprintf(p, sizeof p, R"({"x": %.17g, "y": %.17g})", x, y);
  return p;
}

// Still water 0.1 m deep on a floor 0.2 m wide between walls rising outward at `degrees`, h = 7.1 mm.
class StillWaterInATrapezoid : public testing::TestWithParam<double> {};

TEST_P(StillWaterInATrapezoid, StaysAtRest) {
  const double s = 1.0 / std::tan(GetParam() * M_PI / 180.0), d = 0.1, h = 0.0071;
  const std::string wall = point(-0.3 * s, 0.3) + ", " + point(0, 0) + ", " + point(0.2, 0) + ", " + point(0.2 + 0.3 * s, 0.3);
  const std::string water = point(0, 0) + ", " + point(0.2, 0) + ", " + point(0.2 + d * s, d) + ", " + point(-d * s, d);
  const std::string recorders = R"({"name": "fluid_area", "quantity": "fluid_area"},
    {"name": "max_speed", "quantity": "max_speed"},
    {"name": "bottom_p", "quantity": "pressure", "point": {"x": 0.1, "y": 0.002}},
    {"name": "fy", "quantity": "force_y", "boundary": "tank"})";
  const RunResult r = run(parse_model_json(model(wall, water, h, 0.002, 1.0, recorders)), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  double max_speed = 0.0;
  for (const auto& row : r.responses.rows) max_speed = std::max(max_speed, row[1]);
  const auto& last = r.responses.rows.back();
  std::printf("walls at %g degrees: max speed %.2e m/s, area drift %.2e, bottom p %.2f Pa (rho g d %.2f), floor and walls "
              "%.2f N (weight %.2f N)\n",
              GetParam(), max_speed, r.summary.fluid_area_max_drift, last[2], kRho * kG * (d - 0.002), last[3],
              kRho * kG * last[0]);
  EXPECT_LT(max_speed, 1e-3);
  EXPECT_LT(r.summary.fluid_area_max_drift, 1e-4);
  EXPECT_NEAR(last[2], kRho * kG * (d - 0.002), 0.005 * kRho * kG * d);
  EXPECT_NEAR(-last[3], kRho * kG * last[0], 0.005 * kRho * kG * last[0]);
}

INSTANTIATE_TEST_SUITE_P(SlopedWalls, StillWaterInATrapezoid, testing::Values(30.0, 60.0, 75.0),
                         [](const testing::TestParamInfo<double>& angle) {
                           return "WallsAt" + std::to_string(static_cast<int>(angle.param)) + "Degrees";
                         });

// A thin wall leaning at atan 3 (71.6 degrees) across a box 0.5 m wide, water 0.2 m deep on its
// left and 0.1 m on its right, each side with its own pressure (docs/theory.md section 6): at
// rest, with the hydrostatic resultants on the divider, rho g (H1^2 - H2^2) / 2 across and the
// weight of the water over its left face less the right's, rho g (H1^2 - H2^2) / (2 tan), down.
// With the contact nodes at the feet it moved at up to 0.62 m/s within 1 s, the forces 1 % off.
TEST(SlopedWalls, ALeaningDividerHoldsTwoLevelsAtRest) {
  const double h1 = 0.2, h2 = 0.1, tan = 3.0;
  const std::string json = R"({"name": "divider", "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.0071}, "analysis": {"dt": 0.002, "t_end": 1.0},
    "fluid_regions": [
      {"polygon": {"points": [)" + point(0, 0) + ", " + point(0.2, 0) + ", " + point(0.2 + h1 / tan, h1) + ", " + point(0, h1) + R"(]}},
      {"polygon": {"points": [)" + point(0.2, 0) + ", " + point(0.5, 0) + ", " + point(0.5, h2) + ", " + point(0.2 + h2 / tan, h2) + R"(]}}],
    "walls": [{"name": "box", "points": [)" + point(0, 0.4) + ", " + point(0, 0) + ", " + point(0.5, 0) + ", " + point(0.5, 0.4) + R"(]},
              {"name": "divider", "points": [)" + point(0.2, 0) + ", " + point(0.2 + 0.3 / tan, 0.3) + R"(]}],
    "recorders": [{"name": "max_speed", "quantity": "max_speed"},
                  {"name": "fx", "quantity": "force_x", "boundary": "divider"},
                  {"name": "fy", "quantity": "force_y", "boundary": "divider"}]})";
  const RunResult r = run(parse_model_json(json), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  double max_speed = 0.0;
  for (const auto& row : r.responses.rows) max_speed = std::max(max_speed, row[0]);
  const auto& last = r.responses.rows.back();
  const double fx = kRho * kG * (h1 * h1 - h2 * h2) / 2.0, fy = -fx / tan;
  std::printf("leaning divider: max speed %.2e m/s, force %.3f, %.3f N (hydrostatic %.3f, %.3f N)\n", max_speed, last[1],
              last[2], fx, fy);
  EXPECT_LT(max_speed, 1e-3);
  EXPECT_NEAR(last[1], fx, 0.005 * fx);
  EXPECT_NEAR(last[2], fy, 0.005 * std::abs(fy));
}

// A V tank of walls at +-45 degrees, water d deep, its surface tilted by a at the walls (2 % of
// d): Kirchhoff's exact linear mode, the potential x y, whose surface stays a plane and swings
// with the period 2 pi sqrt(d / g).
struct VTank {
  double d = 0.13, h = 0.13 / 30;
  double a() const { return 0.02 * d; }
  double period() const { return 2.0 * M_PI * std::sqrt(d / kG); }
  std::string json(double t_end, const std::string& extra = "") const {
    const double xr = d / (1.0 - a() / d), xl = -d / (1.0 + a() / d);  // where the plane meets the walls
    const std::string wall = point(-2 * d, 2 * d) + ", " + point(0, 0) + ", " + point(2 * d, 2 * d);
    const std::string water = point(0, 0) + ", " + point(xr, d + a() * xr / d) + ", " + point(xl, d + a() * xl / d);
    char recorders[256];
    std::snprintf(recorders, sizeof recorders, R"({"name": "eta", "quantity": "wave_gauge", "point": {"x": %.17g, "y": %.17g}},
      {"name": "fluid_area", "quantity": "fluid_area"})", 0.6 * d, d);
    return model(wall, water, h, period() / 200.0, t_end, recorders, extra);
  }
};

TEST(SlopedWalls, SloshingInARightAngledVTankSwingsWithKirchhoffsPeriod) {
  const VTank tank;
  const double T = tank.period(), d = tank.d;
  const RunResult r = run(parse_model_json(tank.json(3.3 * T)), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  // The gauge's downward crossings of the still level (interpolated between steps) and its
  // crests (the highest sample of each period-long window after the start).
  const auto& t = r.responses.time;
  std::vector<double> down;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double e0 = r.responses.rows[i][0] - d, e1 = r.responses.rows[i + 1][0] - d;
    if (e0 > 0.0 && e1 <= 0.0) down.push_back(t[i] + (t[i + 1] - t[i]) * e0 / (e0 - e1));
  }
  ASSERT_GE(down.size(), 3u);
  std::vector<double> crest;
  for (int n = 1; n <= 3; ++n) {
    double best = -1.0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] > (n - 0.5) * T && t[i] < (n + 0.5) * T) best = std::max(best, r.responses.rows[i][0]);
    crest.push_back(best - d);
  }
  const double measured = (down.back() - down.front()) / static_cast<double>(down.size() - 1);
  std::printf("V tank d %g, h %g: period %.4f s over %zu, Kirchhoff %.4f s (%+.2f %%); area drift %.2e; crests %.2f %.2f "
              "%.2f mm\n",
              d, tank.h, measured, down.size() - 1, T, 100.0 * (measured / T - 1.0), r.summary.fluid_area_max_drift,
              1e3 * crest[0], 1e3 * crest[1], 1e3 * crest[2]);
  EXPECT_NEAR(measured, T, 0.015 * T);
  EXPECT_LT(r.summary.fluid_area_max_drift, 1e-3);
  // Backward Euler damps about 9 % a period at T / 200 (tests/slow/sloshing_tank_test.cpp).
  EXPECT_LT(crest[2], crest[1]);
  EXPECT_LT(crest[1], crest[0]);
  EXPECT_GT(crest[2], 0.5 * 0.6 * tank.a());
}

TEST(SlopedWalls, DdmOfTheVTanksGaugeMatchesCentralFdm) {
  // The contact nodes on both walls go to the points level with their particles: their position
  // sensitivities are the level offset's derivative.
  const VTank tank;
  RunOptions options;
  options.t_end = 0.75;
  const GradientCheck c =
      check_gradients(parse_model_json(tank.json(0.75, R"(, "parameters": [{"name": "mu", "targets": ["fluid.mu"]}])")),
                      options, false);
  ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
  bool checked = false;
  for (const auto& row : c.rows) {
    if (row.recorder != "eta") continue;
    std::printf("eta / mu: max |FDM| %.4e, DDM %.2e\n", row.max_fdm, row.ddm);
    EXPECT_GT(row.max_fdm, 1e-3);
    EXPECT_LE(row.ddm, 1e-4);
    checked = true;
  }
  EXPECT_TRUE(checked);
}

}  // namespace
}  // namespace pfem
