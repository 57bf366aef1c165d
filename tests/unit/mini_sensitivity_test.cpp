// The DDM derivatives of one MINI triangle (engine/fluid/mini_sensitivity.*) against central
// finite differences of the element residual built from the closed-form matrices:
//  - the geometric matrices drv/dx, drp/dx (H and T of theory (35)-(36) with the residual's
//    sign) on random triangles, velocities and pressures;
//  - the conditional derivatives with respect to rho, mu, kappa, thickness, alone and combined.
#include "engine/fluid/mini_sensitivity.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>

namespace {

using namespace pfem::fluid;

struct Case {
  std::array<double, 3> x, y;
  FluidConstants f{1000.0, 0.1, 2.15e9};
  double t = 0.012, dt = 1e-3, gx = 0.3, gy = -9.81;
  ElementState s;
};

Case random_case(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Case c;
  do {
    for (int a = 0; a < 3; ++a) c.x[a] = 0.3 + 0.005 * u(rng), c.y[a] = 0.1 + 0.005 * u(rng);
  } while (triangle_geometry(c.x, c.y).A < 5e-6);  // well away from degenerate
  for (int i = 0; i < 8; ++i) c.s.v(i) = u(rng), c.s.vn(i) = u(rng);
  for (int i = 0; i < 3; ++i) c.s.p(i) = 500 * u(rng), c.s.pn(i) = 500 * u(rng);
  return c;
}

// The element residual (rv, rp) stacked in 11 entries.
Eigen::Matrix<double, 11, 1> residual(const Case& c) {
  MiniMatrices m;
  mini_matrices(triangle_geometry(c.x, c.y), c.f, c.t, c.gx, c.gy, m);
  const ElementResidual r = element_residual(m, c.dt, c.s);
  Eigen::Matrix<double, 11, 1> out;
  out << r.rv, r.rp;
  return out;
}

// Largest |a - b| over the largest |b|.
template <typename A, typename B>
double relative_error(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(MiniSensitivity, DirectResidualEqualsTheMatrixProducts) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Case c = random_case(rng);
    const TriangleGeometry g = triangle_geometry(c.x, c.y);
    MiniMatrices m;
    mini_matrices(g, c.f, c.t, c.gx, c.gy, m);
    const ElementResidual r = element_residual(m, c.dt, c.s);
    const DirectResidual direct = element_residual(g, c.f, c.t, c.gx, c.gy, c.dt, c.s);
    // Each term's scale: the residual is a sum of terms much larger than itself.
    const double v_scale = (m.M * ((c.s.v - c.s.vn) / c.dt)).cwiseAbs().maxCoeff() + (m.K * c.s.v).cwiseAbs().maxCoeff() +
                           (m.G * c.s.p).cwiseAbs().maxCoeff() + m.F.cwiseAbs().maxCoeff();
    EXPECT_LT((direct.rv - r.rv).cwiseAbs().maxCoeff(), 1e-14 * v_scale) << "trial " << trial;
    const Vec3 rp_abs =
        m.Mp.cwiseProduct(c.s.p - c.s.pn).cwiseAbs() / c.dt + m.G.cwiseAbs().transpose() * c.s.v.cwiseAbs();
    EXPECT_LT((direct.rp - r.rp).cwiseAbs().maxCoeff(), 1e-14 * rp_abs.maxCoeff()) << "trial " << trial;
    EXPECT_LT(relative_error(direct.rp_abs, rp_abs), 1e-14);
    EXPECT_DOUBLE_EQ(direct.mp, m.Mp(0));
    EXPECT_NEAR(direct.f_squared, m.F.squaredNorm(), 1e-14 * m.F.squaredNorm());
  }
}

TEST(MiniSensitivity, GeometricDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Case c = random_case(rng);
    MiniMatrices m;
    const TriangleGeometry g = triangle_geometry(c.x, c.y);
    mini_matrices(g, c.f, c.t, c.gx, c.gy, m);
    GeometricDerivatives d;
    geometric_derivatives(g, m, c.f.mu, c.t, c.dt, c.s, d);
    Eigen::Matrix<double, 11, 6> exact, fd;
    exact << d.drv_dx, d.drp_dx;
    const double h = 1e-8;  // 2e-6 of the element size
    for (int col = 0; col < 6; ++col) {
      Case plus = c, minus = c;
      auto& cp = col % 2 == 0 ? plus.x : plus.y;
      auto& cm = col % 2 == 0 ? minus.x : minus.y;
      cp[col / 2] += h, cm[col / 2] -= h;
      fd.col(col) = (residual(plus) - residual(minus)) / (2 * h);
    }
    // Velocity rows and pressure rows have different units: check each block on its own.
    EXPECT_LT(relative_error(exact.topRows(8), fd.topRows(8)), 1e-7) << "trial " << trial;
    EXPECT_LT(relative_error(exact.bottomRows(3), fd.bottomRows(3)), 1e-7) << "trial " << trial;
  }
}

TEST(MiniSensitivity, GeometricDerivativesAreNotTrivial) {
  // Each piece of the residual moves with the geometry: zero out all but one and the matrix is
  // still non-zero (guards against a derivative that vanishes for a whole term).
  std::mt19937 rng(11);
  Case c = random_case(rng);
  MiniMatrices m;
  const TriangleGeometry g = triangle_geometry(c.x, c.y);
  mini_matrices(g, c.f, c.t, c.gx, c.gy, m);
  GeometricDerivatives d;
  c.s.p.setZero(), c.s.pn.setZero();
  geometric_derivatives(g, m, c.f.mu, c.t, c.dt, c.s, d);
  EXPECT_GT(d.drv_dx.norm(), 0.0);
  EXPECT_GT(d.drp_dx.norm(), 0.0);
}

// The residual with one fluid constant or the thickness changed by h.
using Perturb = std::function<void(Case&, double)>;

void check_conditional(const Case& c, const FluidSeed& seed, const Perturb& perturb, double h) {
  MiniMatrices m;
  const TriangleGeometry g = triangle_geometry(c.x, c.y);
  mini_matrices(g, c.f, c.t, c.gx, c.gy, m);
  const ElementResidual r = conditional_derivative(scaled_terms(g, m, c.f, c.t, c.dt, c.s, seed), c.f, c.t, seed);
  Eigen::Matrix<double, 11, 1> exact;
  exact << r.rv, r.rp;
  Case plus = c, minus = c;
  perturb(plus, h), perturb(minus, -h);
  const Eigen::Matrix<double, 11, 1> fd = (residual(plus) - residual(minus)) / (2 * h);
  ASSERT_GT(fd.norm(), 0.0);
  // Velocity rows and pressure rows on their own; a block that does not move must stay zero.
  const auto check_block = [](const Eigen::VectorXd& e, const Eigen::VectorXd& f) {
    if (f.norm() > 0) EXPECT_LT(relative_error(e, f), 1e-7);
    else EXPECT_EQ(e.norm(), 0.0);
  };
  check_block(exact.head(8), fd.head(8));
  check_block(exact.tail(3), fd.tail(3));
}

TEST(MiniSensitivity, ConditionalDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(3);
  const Case c = random_case(rng);
  check_conditional(c, {1, 0, 0, 0}, [](Case& k, double h) { k.f.rho += h; }, 1e-3);
  check_conditional(c, {0, 1, 0, 0}, [](Case& k, double h) { k.f.mu += h; }, 1e-7);
  // Mp pdot / kappa is ~1e-6 of G^T v here: difference it alone (v = 0), free of cancellation.
  Case still = c;
  still.s.v.setZero();
  check_conditional(still, {0, 0, 1, 0}, [](Case& k, double h) { k.f.kappa += h; }, 1e5);
  check_conditional(c, {0, 0, 0, 1}, [](Case& k, double h) { k.t += h; }, 1e-8);
  // One parameter moving two constants: thickness and density together, at rates 1 and 2.
  check_conditional(c, {2, 0, 0, 1}, [](Case& k, double h) { k.t += h, k.f.rho += 2 * h; }, 1e-8);
}

TEST(MiniSensitivity, ViscosityDerivativeAtZeroViscosity) {
  std::mt19937 rng(5);
  Case c = random_case(rng);
  c.f.mu = 0.0;
  check_conditional(c, {0, 1, 0, 0}, [](Case& k, double h) { k.f.mu += h; }, 1e-7);
}

}  // namespace
