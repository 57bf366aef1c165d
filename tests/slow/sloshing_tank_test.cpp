// Linear sloshing in a rectangular tank at water's viscosity (issue 14): B = 0.5 m, depth
// d = 0.25 m, the surface started as d + a cos(pi x / B) with a = 2 % of d (one polygon, whose
// particles follow the cosine), h = B / 40, dt = T / 200. The wave gauge next to the left wall
// must swing with linear theory's period T = 2 pi / sqrt(g k tanh(k d)), k = pi / B, within 2 %
// over four periods, with free-slip and with no-slip walls, and the fluid area stay within 1 %.
// The amplitude decays by backward Euler's numerical damping, about 1 - (1 + (w dt)^2)^(-N/2)
// per period of N steps (9 % at N = 200), which the test prints.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kB = 0.5, kD = 0.25, kA = 0.02 * kD, kG = 9.81;

double linear_period() {
  const double k = M_PI / kB;
  return 2.0 * M_PI / std::sqrt(kG * k * std::tanh(k * kD));
}

std::string tank(bool slip) {
  std::string surface;
  for (int i = 0; i <= 80; ++i) {
    const double x = kB - kB * i / 80.0;
    char p[96];
    std::snprintf(p, sizeof p, R"(, {"x": %.17g, "y": %.17g})", x, kD + kA * std::cos(M_PI * x / kB));
    surface += p;
  }
  char rest[1024];
  std::snprintf(rest, sizeof rest, R"(]}}],
    "walls": [{"points": [{"x": 0, "y": 0.5}, {"x": 0, "y": 0}, {"x": 0.5, "y": 0}, {"x": 0.5, "y": 0.5}], "slip": %s}],
    "analysis": {"dt": %.17g, "t_end": %.17g},
    "recorders": [{"name": "gauge", "quantity": "wave_gauge", "point": {"x": 0.00625, "y": 0.25}},
                  {"name": "fluid_area", "quantity": "fluid_area"}]
  })", slip ? "true" : "false", linear_period() / 200.0, 4.05 * linear_period());
  return R"({"name": "sloshing-tank", "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9}, "mesh": {"h": 0.0125},
    "fluid_regions": [{"polygon": {"points": [{"x": 0, "y": 0}, {"x": 0.5, "y": 0})" + surface + rest;
}

void expect_linear_sloshing(bool slip) {
  const RunResult r = run(parse_model_json(tank(slip)), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const double period = linear_period();
  // The gauge's crests: the highest sample of each period-long window after the start.
  std::vector<double> crest_time, crest;
  const auto& t = r.responses.time;
  for (int n = 1; n <= 4; ++n) {
    double best = -1.0, best_t = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] > (n - 0.5) * period && t[i] < (n + 0.5) * period && r.responses.rows[i][0] > best)
        best = r.responses.rows[i][0], best_t = t[i];
    crest_time.push_back(best_t), crest.push_back(best - kD);
  }
  const double measured = (crest_time.back() - crest_time.front()) / 3.0;
  std::printf("%s walls: period %.4f s, linear theory %.4f s (%+.2f %%); area drift %.2e; crests", slip ? "slip" : "no-slip",
              measured, period, 100.0 * (measured / period - 1.0), r.summary.fluid_area_max_drift);
  double previous = r.responses.rows.front()[0] - kD;
  for (const double c : crest) std::printf(" %.2f mm (%.1f %% lower)", 1e3 * c, 100.0 * (1.0 - c / previous)), previous = c;
  std::printf("\n");
  EXPECT_NEAR(measured, period, 0.02 * period);
  EXPECT_LT(r.summary.fluid_area_max_drift, 0.01);
  EXPECT_GT(crest.back(), 0.5 * kA);  // still a wave after four periods
}

TEST(SloshingTank, FreeSlipWallsFollowLinearTheory) { expect_linear_sloshing(true); }
TEST(SloshingTank, NoSlipWallsFollowLinearTheory) { expect_linear_sloshing(false); }

}  // namespace
}  // namespace pfem
