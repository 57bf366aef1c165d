#include "engine/fluid/mini_sensitivity.h"

#include <cmath>

namespace pfem::fluid {

ElementResidual element_residual(const MiniMatrices& m, double dt, const ElementState& s) {
  // Coefficient-based products: for 8x8 blocks Eigen's general matrix-vector kernel costs more
  // than the arithmetic (this runs for every element at every Newton iteration).
  return {m.F - m.M.lazyProduct((s.v - s.vn) / dt) - m.K.lazyProduct(s.v) + m.G.lazyProduct(s.p),
          -m.Mp.cwiseProduct(s.p - s.pn) / dt - m.Gc.transpose().lazyProduct(s.v)};
}

DirectResidual element_residual(const TriangleGeometry& g, const FluidConstants& f, double t, double bx, double by,
                                double dt, const ElementState& s) {
  // The products of mini_matrices' closed forms (56)-(63) written out: M has four distinct
  // entries, K v and G^T v go through the sums of c_b, d_b times the corner velocities.
  const double A = g.A;
  const auto& c = g.c;
  const auto& d = g.d;
  const Vec8& v = s.v;
  const Vec8 w = (v - s.vn) / dt;
  const double m_aa = f.rho * A / 12.0 * t, m_ab = f.rho * A / 24.0 * t;
  const double m_a4 = 3.0 * f.rho * A / 40.0 * t, m_44 = 81.0 * f.rho * A / 560.0 * t;
  const double k = f.mu / (6.0 * A) * t, k4 = 27.0 * f.mu / (40.0 * A) * t;
  const double fc = f.rho * A / 6.0 * t, f4 = 9.0 * f.rho * A / 40.0 * t;
  const double wx = w(0) + w(2) + w(4), wy = w(1) + w(3) + w(5);
  double scx = 0, sdx = 0, scy = 0, sdy = 0, cc = 0, dd = 0, cd = 0, cp = 0, dp = 0, abs_corner = 0;
  double div = 0;  // the mass balance's c_m . vx + d_m . vy
  for (int b = 0; b < 3; ++b) {
    scx += c[b] * v(2 * b), sdx += d[b] * v(2 * b);
    scy += c[b] * v(2 * b + 1), sdy += d[b] * v(2 * b + 1);
    cc += c[b] * c[b], dd += d[b] * d[b], cd += c[b] * d[b];
    cp += c[b] * s.p(b), dp += d[b] * s.p(b);
    div += g.cm[b] * v(2 * b) + g.dm[b] * v(2 * b + 1);
    abs_corner += std::abs(g.cm[b]) * std::abs(v(2 * b)) + std::abs(g.dm[b]) * std::abs(v(2 * b + 1));
  }
  const double p_sum = s.p.sum();
  DirectResidual r;
  for (int a = 0; a < 3; ++a) {
    const double mw_x = (m_aa - m_ab) * w(2 * a) + m_ab * wx + m_a4 * w(6);
    const double mw_y = (m_aa - m_ab) * w(2 * a + 1) + m_ab * wy + m_a4 * w(7);
    const double kv_x = k * (4.0 * c[a] * scx + 3.0 * d[a] * sdx + 3.0 * d[a] * scy - 2.0 * c[a] * sdy);
    const double kv_y = k * (3.0 * c[a] * sdx - 2.0 * d[a] * scx + 4.0 * d[a] * sdy + 3.0 * c[a] * scy);
    r.rv(2 * a) = fc * bx - mw_x - kv_x + c[a] / 6.0 * t * p_sum;
    r.rv(2 * a + 1) = fc * by - mw_y - kv_y + d[a] / 6.0 * t * p_sum;
  }
  r.rv(6) = f4 * bx - (m_a4 * wx + m_44 * w(6)) - k4 * ((4.0 * cc + 3.0 * dd) * v(6) + cd * v(7)) - 9.0 / 40.0 * t * cp;
  r.rv(7) = f4 * by - (m_a4 * wy + m_44 * w(7)) - k4 * (cd * v(6) + (4.0 * dd + 3.0 * cc) * v(7)) - 9.0 / 40.0 * t * dp;
  r.mp = g.Am / (6.0 * f.kappa) * t;
  for (int b = 0; b < 3; ++b) {
    const double gtv = t / 6.0 * div - 9.0 / 40.0 * t * (g.cm[b] * v(6) + g.dm[b] * v(7));
    const double mp_dp = r.mp * (s.p(b) - s.pn(b)) / dt;
    r.rp(b) = -mp_dp - gtv;
    r.rp_abs(b) = std::abs(mp_dp) + t / 6.0 * abs_corner +
                  9.0 / 40.0 * t * (std::abs(g.cm[b]) * std::abs(v(6)) + std::abs(g.dm[b]) * std::abs(v(7)));
  }
  r.f_squared = (3.0 * fc * fc + f4 * f4) * (bx * bx + by * by);
  return r;
}

void geometric_derivatives(const TriangleGeometry& g, const MiniMatrices& m, double mu, double t, double dt,
                           const ElementState& s, GeometricDerivatives& out) {
  const double A = g.A;
  const auto& c = g.c;
  const auto& d = g.d;
  const Vec8& v = s.v;
  // d/dA: M, F and Mp are proportional to A, K to 1/A; G does not depend on A.
  const Vec8 drv_dA = (m.F - m.M * ((v - s.vn) / dt) + m.K * v) / A;
  const Vec3 drp_dA = -m.Mp.cwiseProduct(s.p - s.pn) / (dt * g.Am);  // at the midpoint

  // d/dc_e, d/dd_e of -K v + G p (rows) and of -G^T v, from (58)-(61).
  Mat83 drv_dc, drv_dd;
  Eigen::Matrix3d drp_dc, drp_dd;
  const double k = mu * t / (6.0 * A), k4 = 27.0 * mu * t / (40.0 * A);
  double sxc = 0, sxd = 0, syc = 0, syd = 0;  // sums of c_b, d_b times v_bx, v_by
  for (int b = 0; b < 3; ++b) {
    sxc += c[b] * v(2 * b), sxd += d[b] * v(2 * b);
    syc += c[b] * v(2 * b + 1), syd += d[b] * v(2 * b + 1);
  }
  const double psum = s.p.sum(), vbx = v(6), vby = v(7);
  for (int e = 0; e < 3; ++e) {
    const double vex = v(2 * e), vey = v(2 * e + 1);
    for (int a = 0; a < 3; ++a) {
      const double same = a == e ? 1.0 : 0.0;
      drv_dc(2 * a, e) = -k * (4 * same * sxc + 4 * c[a] * vex - 2 * same * syd + 3 * d[a] * vey) + same * t / 6 * psum;
      drv_dd(2 * a, e) = -k * (3 * same * sxd + 3 * d[a] * vex + 3 * same * syc - 2 * c[a] * vey);
      drv_dc(2 * a + 1, e) = -k * (3 * same * sxd - 2 * d[a] * vex + 3 * same * syc + 3 * c[a] * vey);
      drv_dd(2 * a + 1, e) = -k * (3 * c[a] * vex - 2 * same * sxc + 4 * same * syd + 4 * d[a] * vey) + same * t / 6 * psum;
      drp_dc(a, e) = -(t / 6 * vex - same * 9 * t / 40 * vbx);
      drp_dd(a, e) = -(t / 6 * vey - same * 9 * t / 40 * vby);
    }
    drv_dc(6, e) = -k4 * (8 * c[e] * vbx + d[e] * vby) - 9 * t / 40 * s.p(e);
    drv_dc(7, e) = -k4 * (d[e] * vbx + 6 * c[e] * vby);
    drv_dd(6, e) = -k4 * (6 * d[e] * vbx + c[e] * vby);
    drv_dd(7, e) = -k4 * (c[e] * vbx + 8 * d[e] * vby) - 9 * t / 40 * s.p(e);
  }

  // Chain rule to the corner coordinates.
  for (int a = 0; a < 3; ++a) {
    const int next = (a + 1) % 3, prev = (a + 2) % 3;
    out.drv_dx.col(2 * a) = c[a] * drv_dA + drv_dd.col(next) - drv_dd.col(prev);
    out.drv_dx.col(2 * a + 1) = d[a] * drv_dA + drv_dc.col(prev) - drv_dc.col(next);
    out.drp_dx.col(2 * a) = g.cm[a] * drp_dA + drp_dd.col(next) - drp_dd.col(prev);
    out.drp_dx.col(2 * a + 1) = g.dm[a] * drp_dA + drp_dc.col(prev) - drp_dc.col(next);
  }
}

ScaledTerms scaled_terms(const TriangleGeometry& g, const MiniMatrices& m, const FluidConstants& f, double thickness,
                         double dt, const ElementState& s, const FluidSeed& moved) {
  ScaledTerms t;
  if (moved.rho != 0.0) t.inertia_body = m.F - m.M.lazyProduct((s.v - s.vn) / dt);
  if (moved.kappa != 0.0) t.compressibility = -m.Mp.cwiseProduct(s.p - s.pn) / dt;
  if (moved.mu != 0.0 && f.mu > 0.0) {
    t.viscous = m.K.lazyProduct(s.v);
  } else if (moved.mu != 0.0) {
    MiniMatrices unit;
    mini_matrices(g, {f.rho, 1.0, f.kappa}, thickness, 0.0, 0.0, unit);
    t.viscous = unit.K * s.v;
  }
  if (moved.thickness != 0.0) t.residual = element_residual(m, dt, s);
  return t;
}

ElementResidual conditional_derivative(const ScaledTerms& t, const FluidConstants& f, double thickness,
                                       const FluidSeed& seed) {
  ElementResidual out{Vec8::Zero(), Vec3::Zero()};
  if (seed.thickness != 0.0) {
    const double share = seed.thickness / thickness;
    out = {share * t.residual.rv, share * t.residual.rp};
  }
  if (seed.rho != 0.0) out.rv += seed.rho / f.rho * t.inertia_body;
  if (seed.kappa != 0.0) out.rp -= seed.kappa / f.kappa * t.compressibility;
  if (seed.mu != 0.0) out.rv -= (f.mu > 0.0 ? seed.mu / f.mu : seed.mu) * t.viscous;
  return out;
}

}  // namespace pfem::fluid
