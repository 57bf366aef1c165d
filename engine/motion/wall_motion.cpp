#include "engine/motion/wall_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pfem::motion {

namespace {

Sensitive sinusoid(const Signal& g, double t, const SignalSeed& seed) {
  const double r = g.ramp > 0.0 && t < g.ramp ? 0.5 * (1.0 - std::cos(std::numbers::pi * t / g.ramp)) : 1.0;
  const double w = 2.0 * std::numbers::pi / g.period;
  const double sin_wt = std::sin(w * t), cos_wt = std::cos(w * t);
  return {0.5 * g.stroke * r * sin_wt,
          seed.stroke * 0.5 * r * sin_wt - seed.period * 0.5 * g.stroke * r * cos_wt * w * t / g.period};
}

// Goring's trajectory X(t) = (S/2) tanh(k (c (t - t0) - X)) (the exact solution of
// dX/dt = c eta / (d + eta) with eta the solitary wave's elevation at the paddle), solved by
// Newton (its derivative in X lies in [1, 1 + H/d]), and dX/dH by implicit differentiation.
Sensitive goring_position(const Signal& g, double t, double seed_height) {
  const double H = g.height, d = g.depth;
  const double k = std::sqrt(3.0 * H / (4.0 * d * d * d)), c = std::sqrt(g.gravity * (d + H));
  const double half_stroke = H / (k * d), t0 = (3.8 + H / d) / (k * c);
  const auto theta = [&](double X) { return k * (c * (t - t0) - X); };
  double X = 0.0;
  for (int it = 0; it < 100; ++it) {
    const double th = theta(X), sech2 = 1.0 / (std::cosh(th) * std::cosh(th));
    const double step = (X - half_stroke * std::tanh(th)) / (1.0 + half_stroke * k * sech2);
    X -= step;
    if (std::abs(step) <= 1e-15 * (half_stroke + std::abs(X))) break;
  }
  const double th = theta(X), sech2 = 1.0 / (std::cosh(th) * std::cosh(th));
  const double dk = k / (2.0 * H), dc = g.gravity / (2.0 * c), dhalf = 0.5 / (k * d);
  const double dt0 = (1.0 / d) / (k * c) - t0 * (dk * c + k * dc) / (k * c);
  const double dtheta = dk * (c * (t - t0) - X) + k * (dc * (t - t0) - c * dt0);  // at fixed X
  const double f_h = -dhalf * std::tanh(th) - half_stroke * sech2 * dtheta;
  const double f_x = 1.0 + half_stroke * k * sech2;
  return {X, -seed_height * f_h / f_x};
}

Sensitive solitary(const Signal& g, double t, const SignalSeed& seed) {
  const Sensitive x = goring_position(g, t, seed.height), x0 = goring_position(g, 0.0, seed.height);
  return {x.value - x0.value, x.derivative - x0.derivative};
}

double table_value(const Signal& g, double t) {
  const auto& ts = g.times;
  if (t <= ts.front()) return g.values.front();
  if (t >= ts.back()) return g.values.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()) - 1;
  const double h = ts[i + 1] - ts[i], a = (ts[i + 1] - t) / h, b = 1.0 - a;
  double f = a * g.values[i] + b * g.values[i + 1];
  if (g.cubic) f += ((a * a * a - a) * g.curvatures[i] + (b * b * b - b) * g.curvatures[i + 1]) * h * h / 6.0;
  return f;
}

}  // namespace

void Signal::prepare() {
  curvatures.assign(times.size(), 0.0);
  if (kind != Kind::kTable || !cubic || times.size() < 3) return;
  // Natural spline (zero curvature at the ends): the tridiagonal system by the Thomas algorithm.
  const std::size_t n = times.size();
  std::vector<double> diag(n, 1.0), upper(n, 0.0), rhs(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = times[i] - times[i - 1], h1 = times[i + 1] - times[i];
    const double lower = h0 / 6.0;
    diag[i] = (h0 + h1) / 3.0 - lower * upper[i - 1] / diag[i - 1];
    upper[i] = h1 / 6.0;
    rhs[i] = (values[i + 1] - values[i]) / h1 - (values[i] - values[i - 1]) / h0 - lower * rhs[i - 1] / diag[i - 1];
  }
  for (std::size_t i = n - 1; i-- > 1;) curvatures[i] = (rhs[i] - upper[i] * curvatures[i + 1]) / diag[i];
}

Sensitive Signal::displacement(double t, const SignalSeed& seed) const {
  switch (kind) {
    case Kind::kSinusoid: return sinusoid(*this, t, seed);
    case Kind::kSolitary: return solitary(*this, t, seed);
    case Kind::kTable: {
      const double f = table_value(*this, t);
      return {scale * f, seed.scale * f};
    }
  }
  return {};
}

Placement place(const WallMotion& m, const Sensitive& s, double x0, double y0, double tx, double ty) {
  Placement p;
  if (!m.flap) {
    p.x = x0 + s.value * m.direction_x, p.y = y0 + s.value * m.direction_y;
    p.dx = s.derivative * m.direction_x, p.dy = s.derivative * m.direction_y;
    p.tx = tx, p.ty = ty;
    return p;
  }
  // Turned clockwise by theta = atan(s / arm): the wall crosses the height arm displaced by s.
  const double theta = std::atan(s.value / m.arm);
  const double dtheta = s.derivative * m.arm / (m.arm * m.arm + s.value * s.value);
  const double c = std::cos(theta), n = std::sin(theta);
  const double rx = x0 - m.hinge_x, ry = y0 - m.hinge_y;
  p.x = m.hinge_x + c * rx + n * ry, p.y = m.hinge_y - n * rx + c * ry;
  p.dx = dtheta * (p.y - m.hinge_y), p.dy = -dtheta * (p.x - m.hinge_x);
  p.tx = c * tx + n * ty, p.ty = -n * tx + c * ty;
  p.dtx = dtheta * p.ty, p.dty = -dtheta * p.tx;
  return p;
}

}  // namespace pfem::motion
