#include "engine/fluid/mini_lumped.h"

namespace pfem::fluid {

namespace {
// (M - M_L) (v - vn)/dt: what the lumped residual adds to the consistent one.
Vec8 lumping_difference(const MiniMatrices& m, const Vec8& ml, double dt, const ElementState& s) {
  const Vec8 w = (s.v - s.vn) / dt;
  return m.M * w - ml.cwiseProduct(w);
}
}  // namespace

Vec8 lumped_mass(const MiniMatrices& m) {
  Vec8 ml;
  for (int r = 0; r < 6; ++r) ml(r) = m.M.block<1, 6>(r, 0).sum();
  ml(6) = m.M(6, 6), ml(7) = m.M(7, 7);
  return ml;
}

ElementResidual lumped_residual(const MiniMatrices& m, const Vec8& ml, double dt, const ElementState& s) {
  ElementResidual r = element_residual(m, dt, s);
  r.rv += lumping_difference(m, ml, dt, s);
  return r;
}

void lumped_geometric_derivatives(const TriangleGeometry& g, const MiniMatrices& m, const Vec8& ml, double mu,
                                  double thickness, double dt, const ElementState& s, GeometricDerivatives& out) {
  geometric_derivatives(g, m, mu, thickness, dt, s, out);
  // The difference is proportional to A, whose derivatives are dA/dx_a = c_a, dA/dy_a = d_a.
  const Vec8 per_area = lumping_difference(m, ml, dt, s) / g.A;
  for (int a = 0; a < 3; ++a) {
    out.drv_dx.col(2 * a) += g.c[a] * per_area;
    out.drv_dx.col(2 * a + 1) += g.d[a] * per_area;
  }
}

ElementResidual lumped_conditional_derivative(const TriangleGeometry& g, const MiniMatrices& m, const Vec8& ml,
                                              const FluidConstants& f, double thickness, double dt,
                                              const ElementState& s, const FluidSeed& seed) {
  ElementResidual d = conditional_derivative(scaled_terms(g, m, f, thickness, dt, s, seed), f, thickness, seed);
  d.rv += (seed.rho / f.rho + seed.thickness / thickness) * lumping_difference(m, ml, dt, s);
  return d;
}

}  // namespace pfem::fluid
