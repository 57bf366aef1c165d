// The incompressible fractional step's MINI triangle (engine/fluid/mini_lumped.*): its lumped
// mass against the closed forms, and its DDM derivatives (the geometric matrices and the
// conditional derivatives) against central finite differences of its residual.
#include "engine/fluid/mini_lumped.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <limits>
#include <random>

namespace {

using namespace pfem::fluid;

constexpr double kNoBulkModulus = std::numeric_limits<double>::infinity();

struct Element {
  std::array<double, 3> x, y;
  FluidConstants fluid{998.0, 0.3, kNoBulkModulus};
  double thickness = 0.02, dt = 2e-3, gx = -0.5, gy = -9.81;
  ElementState state;
};

Element random_element(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Element el;
  do {
    for (int a = 0; a < 3; ++a) el.x[a] = -0.2 + 0.004 * u(rng), el.y[a] = 0.05 + 0.004 * u(rng);
  } while (triangle_geometry(el.x, el.y).A < 4e-6);
  for (int i = 0; i < 8; ++i) el.state.v(i) = 0.5 * u(rng), el.state.vn(i) = i < 6 ? 0.5 * u(rng) : 0.0;
  for (int i = 0; i < 3; ++i) el.state.p(i) = 800 * u(rng), el.state.pn(i) = 800 * u(rng);
  return el;
}

// The element's matrices at its geometry.
MiniMatrices matrices(const Element& el) {
  MiniMatrices m;
  mini_matrices(triangle_geometry(el.x, el.y), el.fluid, el.thickness, el.gx, el.gy, m);
  return m;
}

// (rv, rp) of the lumped element, stacked.
Eigen::Matrix<double, 11, 1> residual(const Element& el) {
  const MiniMatrices m = matrices(el);
  const ElementResidual r = lumped_residual(m, lumped_mass(m), el.dt, el.state);
  return (Eigen::Matrix<double, 11, 1>() << r.rv, r.rp).finished();
}

// |a - b| / |b| (2-norms).
double mismatch(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

TEST(MiniLumped, CornersCarryTheTrianglesMassInThirdsAndTheBubbleItsOwn) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    const Element el = random_element(rng);
    const TriangleGeometry g = triangle_geometry(el.x, el.y);
    const MiniMatrices m = matrices(el);
    const Vec8 ml = lumped_mass(m);
    const double mass = el.fluid.rho * el.thickness * g.A / 2;  // A is twice the area
    for (int r = 0; r < 6; ++r) EXPECT_NEAR(ml(r), mass / 3, 1e-14 * mass);
    // M_44 = 81 rho A / 560 t (the paper's (57)).
    EXPECT_NEAR(ml(6), 81.0 / 560.0 * el.fluid.rho * g.A * el.thickness, 1e-14 * mass);
    EXPECT_EQ(ml(6), ml(7));
    // No bulk modulus: the mass balance is -Gc^T v alone.
    const ElementResidual r = lumped_residual(m, ml, el.dt, el.state);
    EXPECT_LT((r.rp + m.Gc.transpose() * el.state.v).norm(),
              1e-14 * (m.Gc.cwiseAbs().transpose() * el.state.v.cwiseAbs()).norm());
  }
}

TEST(MiniLumped, GeometricDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 30; ++trial) {
    const Element el = random_element(rng);
    const MiniMatrices m = matrices(el);
    GeometricDerivatives d;
    lumped_geometric_derivatives(triangle_geometry(el.x, el.y), m, lumped_mass(m), el.fluid.mu, el.thickness, el.dt,
                                 el.state, d);
    const double h = 1e-8;  // 2.5e-6 of the element's size
    for (int col = 0; col < 6; ++col) {
      Element plus = el, minus = el;
      (col % 2 == 0 ? plus.x : plus.y)[col / 2] += h;
      (col % 2 == 0 ? minus.x : minus.y)[col / 2] -= h;
      const Eigen::Matrix<double, 11, 1> fd = (residual(plus) - residual(minus)) / (2 * h);
      // Momentum and mass rows have their own units: each on its own.
      EXPECT_LT(mismatch(d.drv_dx.col(col), fd.head<8>()), 1e-7) << "trial " << trial << ", column " << col;
      EXPECT_LT(mismatch(d.drp_dx.col(col), fd.tail<3>()), 1e-7) << "trial " << trial << ", column " << col;
    }
  }
}

// lumped_conditional_derivative for `seed` against the residual's central difference when
// `perturb` moves the constants by +-step.
void expect_conditional(const Element& el, const FluidSeed& seed, const std::function<void(Element&, double)>& perturb,
                        double step) {
  const MiniMatrices m = matrices(el);
  const ElementResidual d = lumped_conditional_derivative(triangle_geometry(el.x, el.y), m, lumped_mass(m), el.fluid,
                                                          el.thickness, el.dt, el.state, seed);
  Element plus = el, minus = el;
  perturb(plus, step), perturb(minus, -step);
  const Eigen::Matrix<double, 11, 1> fd = (residual(plus) - residual(minus)) / (2 * step);
  EXPECT_LT(mismatch(d.rv, fd.head<8>()), 1e-7);
  if (fd.tail<3>().norm() > 0)
    EXPECT_LT(mismatch(d.rp, fd.tail<3>()), 1e-7);
  else
    EXPECT_EQ(d.rp.norm(), 0.0);
}

TEST(MiniLumped, ConditionalDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(4);
  const Element el = random_element(rng);
  expect_conditional(
      el, {1, 0, 0, 0}, [](Element& e, double h) { e.fluid.rho += h; }, 1e-3);
  expect_conditional(
      el, {0, 1, 0, 0}, [](Element& e, double h) { e.fluid.mu += h; }, 1e-7);
  expect_conditional(
      el, {0, 0, 0, 1}, [](Element& e, double h) { e.thickness += h; }, 1e-8);
  expect_conditional(
      el, {3, 0, 0, 1}, [](Element& e, double h) { e.thickness += h, e.fluid.rho += 3 * h; }, 1e-8);
  // The bulk modulus is no parameter of this element: its seed changes nothing.
  const MiniMatrices m = matrices(el);
  const ElementResidual d = lumped_conditional_derivative(triangle_geometry(el.x, el.y), m, lumped_mass(m), el.fluid,
                                                          el.thickness, el.dt, el.state, {0, 0, 1, 0});
  EXPECT_EQ(d.rv.norm() + d.rp.norm(), 0.0);
}

}  // namespace
