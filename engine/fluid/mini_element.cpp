#include "engine/fluid/mini_element.h"

namespace pfem::fluid {

TriangleGeometry triangle_geometry(const std::array<double, 3>& x, const std::array<double, 3>& y) {
  TriangleGeometry g;
  // (53) rearranged relative to corner 1: the same value, but its rounding depends on the
  // element's size only, not on its distance from the origin.
  g.A = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  g.c = {y[1] - y[2], y[2] - y[0], y[0] - y[1]};
  g.d = {x[2] - x[1], x[0] - x[2], x[1] - x[0]};
  g.Am = g.A, g.cm = g.c, g.dm = g.d;
  return g;
}

void continuity_at_midpoint(TriangleGeometry& g, const std::array<double, 3>& xn, const std::array<double, 3>& yn) {
  const TriangleGeometry n = triangle_geometry(xn, yn);
  // c, d are linear in the coordinates; A is quadratic, so it is computed at the midpoint.
  for (int a = 0; a < 3; ++a) g.cm[a] = 0.5 * (g.c[a] + n.c[a]), g.dm[a] = 0.5 * (g.d[a] + n.d[a]);
  g.Am = g.cm[1] * g.dm[2] - g.cm[2] * g.dm[1];  // (x2 - x1)(y3 - y1) - (x3 - x1)(y2 - y1) at the midpoint
}

TriangleGeometry step_geometry(const std::array<double, 3>& xn, const std::array<double, 3>& yn,
                               const std::array<double, 3>& vx, const std::array<double, 3>& vy, double dt) {
  std::array<double, 3> x, y;
  for (int a = 0; a < 3; ++a) x[a] = xn[a] + dt * vx[a], y[a] = yn[a] + dt * vy[a];
  TriangleGeometry g = triangle_geometry(x, y);
  continuity_at_midpoint(g, xn, yn);
  return g;
}

void mini_matrices(const TriangleGeometry& g, const FluidConstants& f, double t, double bx,
                   double by, MiniMatrices& out) {
  const double A = g.A;
  const auto& c = g.c;
  const auto& d = g.d;

  // Mass (56)-(57): the same scalar on the x and y dofs.
  out.M.setZero();
  const double m_aa = f.rho * A / 12.0 * t, m_ab = f.rho * A / 24.0 * t;
  const double m_a4 = 3.0 * f.rho * A / 40.0 * t, m_44 = 81.0 * f.rho * A / 560.0 * t;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const double m = (a == b) ? m_aa : m_ab;
      out.M(2 * a, 2 * b) = m;
      out.M(2 * a + 1, 2 * b + 1) = m;
    }
    out.M(2 * a, 6) = out.M(6, 2 * a) = m_a4;
    out.M(2 * a + 1, 7) = out.M(7, 2 * a + 1) = m_a4;
  }
  out.M(6, 6) = out.M(7, 7) = m_44;

  // Viscous (58)-(60); corner-bubble coupling vanishes (59).
  out.K.setZero();
  const double k = f.mu / (6.0 * A) * t;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      out.K(2 * a, 2 * b) = k * (4.0 * c[a] * c[b] + 3.0 * d[a] * d[b]);
      out.K(2 * a, 2 * b + 1) = k * (3.0 * d[a] * c[b] - 2.0 * c[a] * d[b]);
      out.K(2 * a + 1, 2 * b) = k * (3.0 * c[a] * d[b] - 2.0 * d[a] * c[b]);
      out.K(2 * a + 1, 2 * b + 1) = k * (4.0 * d[a] * d[b] + 3.0 * c[a] * c[b]);
    }
  }
  const double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double cd = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
  const double k4 = 27.0 * f.mu / (40.0 * A) * t;
  out.K(6, 6) = k4 * (4.0 * cc + 3.0 * dd);
  out.K(6, 7) = out.K(7, 6) = k4 * cd;
  out.K(7, 7) = k4 * (4.0 * dd + 3.0 * cc);

  // Gradient (61): G_ab = [c_a, d_a]/6, G_4b = -9/40 [c_b, d_b].
  const auto gradient = [t](const std::array<double, 3>& gc, const std::array<double, 3>& gd, Mat83& G) {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        G(2 * a, b) = gc[a] / 6.0 * t;
        G(2 * a + 1, b) = gd[a] / 6.0 * t;
      }
    }
    for (int b = 0; b < 3; ++b) {
      G(6, b) = -9.0 / 40.0 * gc[b] * t;
      G(7, b) = -9.0 / 40.0 * gd[b] * t;
    }
  };
  gradient(c, d, out.G);
  gradient(g.cm, g.dm, out.Gc);

  // Body force (62) and lumped pressure mass (63).
  const double fc = f.rho * A / 6.0 * t, f4 = 9.0 * f.rho * A / 40.0 * t;
  for (int a = 0; a < 3; ++a) {
    out.F(2 * a) = fc * bx;
    out.F(2 * a + 1) = fc * by;
  }
  out.F(6) = f4 * bx;
  out.F(7) = f4 * by;
  out.Mp.setConstant(g.Am / (6.0 * f.kappa) * t);
}

}  // namespace pfem::fluid
