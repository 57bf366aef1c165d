// A viscous flow with an exact answer, so that the viscous matrix K (not only the pressure) is
// checked: start-up of gravity-driven plane Poiseuille flow.
//
// Setup: a column of fluid 0.2 m tall between two vertical no-slip walls W = 0.04 m apart (the
// walls reach 0.1 m below and 0.05 m above it), no bottom, gravity g along the walls, fluid at
// rest at t = 0. Far from the two free ends (the column is 5 W long; we look at its middle)
// the pressure stays ~0 and the downward velocity u(y, t), y measured from the centre line,
// obeys u_t = nu u_yy + g, u(+-W/2, t) = 0, u(y, 0) = 0, nu = mu / rho.
//
// Series solution. Steady part u_s = g/(2 nu) (W^2/4 - y^2) = (g W^2 / (8 nu)) [1 - (2y/W)^2].
// The rest w = u - u_s solves the heat equation with w(+-W/2) = 0 and w(y, 0) = -u_s(y); it is
// even in y, so w = -sum_k b_k cos(l_k y) exp(-nu l_k^2 t) with l_k = (2k+1) pi / W and
//   b_k = (2/a) int_0^a u_s cos(l_k y) dy,  a = W/2.
// Integrating by parts twice with cos(l_k a) = 0 and sin(l_k a) = (-1)^k:
//   int_0^a (a^2 - y^2) cos(l y) dy = 2 (-1)^k / l^3,
// so b_k = (2/a) (g / (2 nu)) 2 (-1)^k / l_k^3 = 4 g W^2 (-1)^k / (nu pi^3 (2k+1)^3), and
//   u(y,t) = (g W^2/(8 nu)) [1 - (2y/W)^2]
//            - sum_k 4 g W^2 (-1)^k / (nu pi^3 (2k+1)^3) cos((2k+1) pi y / W) exp(-(2k+1)^2 pi^2 nu t / W^2).
// Check: at t = 0, y = 0 the sum is (4 g W^2 / (nu pi^3)) (pi^3 / 32) = g W^2 / (8 nu) = u_s(0),
// since sum_k (-1)^k / (2k+1)^3 = pi^3 / 32. (A prefactor 32 instead of 4 would not vanish at t = 0.)
//
// Numbers: rho = 1000, mu = 20 (nu = 0.02 m^2/s), W = 0.04 m: u_s(0) = 0.0981 m/s, slowest decay
// rate pi^2 nu / W^2 = 123 1/s (time constant 8.1 ms), Reynolds number u W / nu ~ 0.2. Particles
// at h = W/8 (287 of them), dt = 0.2 ms (backward Euler: 0.025 of the time constant, so its
// error is well below 1 % at the times compared). The recorders follow the particles at the
// centre line and at the quarter widths (2y/W = +-1/2) at mid-height of the column; they move
// down by about 3 mm in the 0.04 s simulated, so they stay in the middle of the column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kRho = 1000.0, kMu = 20.0, kG = 9.81, kW = 0.04;

// Downward velocity of start-up plane Poiseuille flow (series above).
double poiseuille(double y, double t) {
  const double nu = kMu / kRho, pi = std::numbers::pi;
  double u = kG * kW * kW / (8 * nu) * (1 - (2 * y / kW) * (2 * y / kW));
  for (int k = 0; k < 200; ++k) {
    const double m = 2 * k + 1;
    u -= 4 * kG * kW * kW * (k % 2 ? -1.0 : 1.0) / (nu * pi * pi * pi * m * m * m) * std::cos(m * pi * y / kW) *
         std::exp(-m * m * pi * pi * nu * t / (kW * kW));
  }
  return u;
}

const char* kModel = R"({
  "name": "startup-poiseuille",
  "description": "Gravity-driven start-up of plane Poiseuille flow in a fluid column between two vertical no-slip walls.",
  "gravity": {"x": 0.0, "y": -9.81},
  "fluid": {"rho": 1000.0, "mu": 20.0, "kappa": 2.15e9},
  "mesh": {"h": 0.005, "alpha": 1.2},
  "fluid_regions": [{"name": "column", "rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.04, "y": 0.2}}}],
  "walls": [
    {"name": "left", "points": [{"x": 0.0, "y": -0.1}, {"x": 0.0, "y": 0.25}]},
    {"name": "right", "points": [{"x": 0.04, "y": -0.1}, {"x": 0.04, "y": 0.25}]}
  ],
  "analysis": {"dt": 0.0002, "t_end": 0.04},
  "recorders": [
    {"name": "v_centre", "quantity": "vy", "point": {"x": 0.02, "y": 0.1}},
    {"name": "v_quarter_left", "quantity": "vy", "point": {"x": 0.01, "y": 0.1}},
    {"name": "v_quarter_right", "quantity": "vy", "point": {"x": 0.03, "y": 0.1}}
  ]
})";

RunResult run_column(double dt, const std::string& formulation = "quasi-incompressible", double h = 0.005) {
  auto model = parse_model_json(kModel);
  model.mutable_mesh()->set_h(h);
  model.mutable_analysis()->set_formulation(formulation);
  if (formulation == "incompressible") model.mutable_fluid()->clear_kappa();  // it has none
  EXPECT_TRUE(validate_model(model).empty());
  RunOptions options;
  options.dt = dt;
  return run(model, options);
}

// The sample nearest to time t.
std::size_t row_at(const Histories& h, double t) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < h.time.size(); ++i)
    if (std::abs(h.time[i] - t) < std::abs(h.time[best] - t)) best = i;
  return best;
}

// The centre line's and the quarter widths' velocities against the series, within `tolerance`
// of it, at 0.5, 1, 2 and 4 time constants.
void expect_series(const RunResult& r, double tolerance) {
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const auto& h = r.responses;
  ASSERT_EQ(h.columns.size(), 3u);
  std::printf("%8s %6s | %9s %9s %7s | %9s %9s %9s %7s\n", "t [s]", "l1 t", "u_c sim", "u_c exact", "error",
              "u_q left", "u_q right", "u_q exact", "error");
  for (const double t : {0.004, 0.008, 0.016, 0.032}) {
    const std::size_t i = row_at(h, t);
    ASSERT_NEAR(h.time[i], t, 1e-9);
    const double uc = -h.rows[i][0], ql = -h.rows[i][1], qr = -h.rows[i][2];
    const double uc_exact = poiseuille(0.0, t), uq_exact = poiseuille(kW / 4, t);
    const double ec = uc / uc_exact - 1, eq = std::max(std::abs(ql / uq_exact - 1), std::abs(qr / uq_exact - 1));
    std::printf("%8.4f %6.2f | %9.5f %9.5f %+6.2f%% | %9.5f %9.5f %9.5f %6.2f%%\n", t,
                std::numbers::pi * std::numbers::pi * kMu / kRho * t / (kW * kW), uc, uc_exact, 100 * ec, ql, qr,
                uq_exact, 100 * eq);
    EXPECT_NEAR(uc, uc_exact, tolerance * uc_exact) << "centre line at t = " << t;
    EXPECT_NEAR(ql, uq_exact, tolerance * uq_exact) << "left quarter width at t = " << t;
    EXPECT_NEAR(qr, uq_exact, tolerance * uq_exact) << "right quarter width at t = " << t;
  }
}

TEST(Viscous, StartupPoiseuilleFollowsTheSeriesSolution) { expect_series(run_column(0.0002), 0.02); }

// The incompressible formulation (engine/solve/fractional_step.h: lumped mass, fractional step)
// on the same column. Its lumped mass slows the transient as backward Euler does (the
// consistent mass of the quasi-incompressible step offsets backward Euler's lag instead): at
// h = W/8 and dt = 0.2 ms it is 2.0 % low at half a time constant; at h = W/12 and dt = 0.1 ms
// within 0.92 % (the column's free ends put the finer meshes 0.7 % high at four time constants,
// both formulations alike).
TEST(Viscous, IncompressibleStartupPoiseuilleFollowsTheSeriesSolution) {
  expect_series(run_column(0.0001, "incompressible", kW / 12), 0.01);
}

// The same flow at half the time step: a consistent time integration must give (nearly) the
// same velocities; at t = 0.032 s (4 time constants) what is left of the transient is 2 % of
// the steady velocity, so backward Euler's O(dt) error accounts for ~0.1 % here.
TEST(Viscous, ViscousFlowConvergesAsTheTimeStepShrinks) {
  const RunResult a = run_column(0.0002), b = run_column(0.0001);
  ASSERT_EQ(a.summary.status, RunStatus::kCompleted) << a.summary.message;
  ASSERT_EQ(b.summary.status, RunStatus::kCompleted) << b.summary.message;
  const double t = 0.032;
  const double ua = -a.responses.rows[row_at(a.responses, t)][0];
  const double ub = -b.responses.rows[row_at(b.responses, t)][0];
  const double exact = poiseuille(0.0, t);
  std::printf("centre velocity at t = %.3f s: dt = 0.2 ms %.5f (%+.2f %%), dt = 0.1 ms %.5f (%+.2f %%), exact %.5f\n",
              t, ua, 100 * (ua / exact - 1), ub, 100 * (ub / exact - 1), exact);
  EXPECT_NEAR(ub, ua, 0.01 * exact) << "halving dt moved the solution by more than 1 %";
  EXPECT_NEAR(ub, exact, 0.02 * exact);
}

}  // namespace
}  // namespace pfem
