// The wavemakers' signals and rigid motions (engine/motion): Goring's trajectory against the ODE
// it solves, the spline through its table, the flap's line at the height of its arm, and every
// derivative the DDM takes from them against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "engine/motion/wall_motion.h"

namespace pfem::motion {
namespace {

Signal solitary(double height, double depth) {
  Signal g;
  g.kind = Signal::Kind::kSolitary;
  g.height = height, g.depth = depth, g.gravity = 9.81;
  return g;
}

// Central difference of f at x with relative step 1e-6.
double central(const std::function<double(double)>& f, double x) {
  const double e = 1e-6 * std::max(1.0, std::abs(x));
  return (f(x + e) - f(x - e)) / (2.0 * e);
}

TEST(WallMotion, GoringsTrajectorySolvesItsOde) {
  const double H = 0.03, d = 0.1, g = 9.81;
  const Signal s = solitary(H, d);
  const double k = std::sqrt(3 * H / (4 * d * d * d)), c = std::sqrt(g * (d + H)), t0 = (3.8 + H / d) / (k * c);
  const double X0 = s.displacement(0.0, {}).value;
  EXPECT_EQ(X0, 0.0);
  for (double t = 0.1; t < 2.0 * t0; t += 0.1) {
    // X(t) = s(t) + X(0) with X(0) = (S/2) tanh(k (c (0 - t0) - X(0))) ~ -S/2.
    const auto position = [&](double time) { return s.displacement(time, {}).value; };
    const double half = H / (k * d);
    double X_start = -half;
    for (int i = 0; i < 200; ++i) X_start = half * std::tanh(k * (c * (0.0 - t0) - X_start));
    const double X = position(t) + X_start;
    const double eta = H / std::pow(std::cosh(k * (c * (t - t0) - X)), 2);
    const double velocity = central(position, t);
    EXPECT_NEAR(velocity, c * eta / (d + eta), 1e-6 * c) << "t = " << t;
  }
  // The whole stroke S = 2 H / (k d) = sqrt(16 H d / 3), less the tails beyond 3.8 / (k c).
  const double stroke = std::sqrt(16.0 * H * d / 3.0);
  EXPECT_NEAR(s.displacement(2.0 * t0, {}).value, stroke, 2e-3 * stroke);
}

TEST(WallMotion, SignalDerivativesMatchCentralDifferences) {
  Signal sine;
  sine.stroke = 0.04, sine.period = 1.3, sine.ramp = 2.0;
  for (const double t : {0.37, 1.9, 3.3}) {
    const auto by_stroke = [&](double v) { Signal g = sine; g.stroke = v; return g.displacement(t, {}).value; };
    const auto by_period = [&](double v) { Signal g = sine; g.period = v; return g.displacement(t, {}).value; };
    EXPECT_NEAR(sine.displacement(t, {.stroke = 1.0}).derivative, central(by_stroke, sine.stroke), 1e-8);
    EXPECT_NEAR(sine.displacement(t, {.period = 1.0}).derivative, central(by_period, sine.period), 1e-8);
  }
  const Signal wave = solitary(0.03, 0.1);
  for (const double t : {0.2, 0.6, 1.1}) {
    const auto by_height = [&](double v) { return solitary(v, 0.1).displacement(t, {}).value; };
    EXPECT_NEAR(wave.displacement(t, {.height = 1.0}).derivative, central(by_height, 0.03), 1e-7) << "t = " << t;
  }
  Signal table;
  table.kind = Signal::Kind::kTable;
  table.times = {0.0, 0.5, 1.0, 2.0}, table.values = {0.0, 0.02, -0.01, 0.0}, table.scale = 1.5, table.cubic = true;
  table.prepare();
  EXPECT_DOUBLE_EQ(table.displacement(0.8, {.scale = 1.0}).derivative, table.displacement(0.8, {}).value / 1.5);
}

TEST(WallMotion, TablesInterpolateTheirPoints) {
  Signal g;
  g.kind = Signal::Kind::kTable;
  g.times = {0.0, 0.4, 1.0, 1.5, 2.5}, g.values = {0.0, 0.03, -0.02, 0.01, 0.0};
  g.prepare();
  EXPECT_DOUBLE_EQ(g.displacement(0.2, {}).value, 0.015);   // linear: the middle of the first piece
  EXPECT_DOUBLE_EQ(g.displacement(-1.0, {}).value, 0.0);    // held before the table
  EXPECT_DOUBLE_EQ(g.displacement(9.0, {}).value, 0.0);     // and after it
  g.cubic = true;
  g.prepare();
  const auto s = [&](double t) { return g.displacement(t, {}).value; };
  for (std::size_t i = 0; i < g.times.size(); ++i) EXPECT_NEAR(s(g.times[i]), g.values[i], 1e-15);
  // C1 at the inner knots (one-sided slopes agree), curvature 0 at the ends (a natural spline).
  const double e = 1e-5;
  for (std::size_t i = 1; i + 1 < g.times.size(); ++i) {
    const double t = g.times[i];
    EXPECT_NEAR((s(t) - s(t - e)) / e, (s(t + e) - s(t)) / e, 1e-3) << "knot " << i;
  }
  EXPECT_NEAR((s(2 * e) - 2 * s(e) + s(0)) / (e * e), 0.0, 1e-2);
}

TEST(WallMotion, AFlapCrossesTheHeightOfItsArmDisplacedByTheSignal) {
  WallMotion m;
  m.flap = true;
  m.hinge_x = 0.1, m.hinge_y = 0.02, m.arm = 0.3;
  const Sensitive s{0.05, 1.0};
  // Two points of the vertical wall x = 0.1: their images span a line that crosses y = 0.32 at x = 0.15.
  const Placement a = place(m, s, 0.1, 0.02), b = place(m, s, 0.1, 0.5, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(a.x, 0.1);
  EXPECT_DOUBLE_EQ(a.y, 0.02);
  const double along = (0.32 - a.y) / b.ty;
  EXPECT_NEAR(a.x + along * b.tx, 0.15, 1e-15);
  EXPECT_NEAR(std::hypot(b.x - a.x, b.y - a.y), 0.48, 1e-15);  // rigid
  const auto x_of = [&](double v) { return place(m, {v, 0.0}, 0.1, 0.5).x; };
  const auto ty_of = [&](double v) { return place(m, {v, 0.0}, 0.1, 0.5, 0.0, 1.0).ty; };
  EXPECT_NEAR(b.dx, central(x_of, 0.05), 1e-9);
  EXPECT_NEAR(b.dty, central(ty_of, 0.05), 1e-9);
  WallMotion piston;
  piston.direction_x = 0.6, piston.direction_y = 0.8;
  const Placement p = place(piston, {0.05, 2.0}, 1.0, 1.0);
  EXPECT_DOUBLE_EQ(p.x, 1.03);
  EXPECT_DOUBLE_EQ(p.dy, 1.6);
}

}  // namespace
}  // namespace pfem::motion
