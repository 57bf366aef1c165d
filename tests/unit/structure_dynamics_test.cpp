// Free vibration of a cantilever (the paper's soft beam: L = 0.1 m, E = 1 MPa, 12 mm square,
// rho_s = 2500) against the Euler-Bernoulli first period
//   T1 = 2 pi / ((beta1 L)^2 sqrt(EI / (m L^4))),  beta1 L = 1.8751040687
// by a generalized eigen-solve of K and M (consistent and lumped mass) and by the
// velocity-based backward-Euler dynamics; Rayleigh mass-proportional damping's decay.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <vector>

#include "engine/structure/dynamic_solver.h"
#include "engine/structure/free_dofs.h"
#include "engine/structure/static_solver.h"
#include "engine/structure/structure_model.h"

namespace pfem::structure {
namespace {

constexpr double kL = 0.1, kE = 1.0e6, kB = 0.012, kRho = 2500.0;
constexpr double kA = kB * kB, kI = kB * kB * kB * kB / 12.0;
constexpr double kBeta1L = 1.8751040687;

double euler_bernoulli_t1() {
  const double m = kRho * kA;
  return 2.0 * std::numbers::pi / (kBeta1L * kBeta1L * std::sqrt(kE * kI / (m * std::pow(kL, 4))));
}

// Vertical cantilever (as the tank's right wall), clamped at the bottom node 0.
StructureModel cantilever(int n, MassKind mass, TransfKind transf = TransfKind::kLinear) {
  StructureModel model;
  for (int k = 0; k <= n; ++k) model.add_node(0.1, kL * k / n);
  model.fix(0, true, true, true);
  BeamOptions o;
  o.transf = transf;
  o.mass = mass;
  o.rho = kRho;
  for (int k = 0; k < n; ++k) model.add_elastic_beam(k, k + 1, {kE, kA, kI}, o);
  return model;
}

Eigen::MatrixXd dense(const FreeDofs& dofs, const std::function<void(const AddEntry&)>& fill) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(dofs.size(), dofs.size());
  fill([&](int i, int j, double v) {
    if (dofs.equation(i) >= 0 && dofs.equation(j) >= 0) A(dofs.equation(i), dofs.equation(j)) += v;
  });
  return A;
}

// Largest eigenvalue of K^-1 M = 1/omega1^2, through K = L L^T (M may be singular: lumped
// mass has no rotational inertia).
double first_period_eigen(const StructureModel& model) {
  const FreeDofs dofs(model);
  const Eigen::MatrixXd K = dense(dofs, [&](const AddEntry& a) { model.add_tangent(a); });
  const Eigen::MatrixXd M = dense(dofs, [&](const AddEntry& a) { model.add_mass(a); });
  const Eigen::LLT<Eigen::MatrixXd> llt(K);
  const Eigen::MatrixXd X = llt.matrixL().solve(M);
  const Eigen::MatrixXd S = llt.matrixL().solve(X.transpose());  // L^-1 M L^-T
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S, Eigen::EigenvaluesOnly);
  return 2.0 * std::numbers::pi * std::sqrt(eig.eigenvalues().maxCoeff());
}

TEST(CantileverVibration, FirstPeriodFromEigenSolve) {
  const double T1 = euler_bernoulli_t1();
  EXPECT_NEAR(T1, 0.25794, 1e-4);  // the paper's beam: about 0.258 s
  const double consistent = first_period_eigen(cantilever(10, MassKind::kConsistent));
  const double lumped = first_period_eigen(cantilever(20, MassKind::kLumped));
  EXPECT_NEAR(consistent / T1, 1.0, 0.02);
  EXPECT_NEAR(lumped / T1, 1.0, 0.02);
  RecordProperty("T1_closed_form", std::to_string(T1));
  RecordProperty("T1_consistent_10", std::to_string(consistent));
  RecordProperty("T1_lumped_20", std::to_string(lumped));
}

// Release from a small static tip deflection and integrate; returns the tip displacement
// history (one entry per step, including t = 0).
std::vector<double> free_vibration(StructureModel& model, int n, double dt, int steps) {
  const double P = 1e-4 * 3.0 * kE * kI / (kL * kL * kL);  // delta/L = 1e-4: linear range
  model.set_nodal_load(n, P, 0.0);
  EXPECT_TRUE(solve_static(model).converged);
  model.set_nodal_load(n, 0.0, 0.0);
  DynamicOptions options;
  options.dt = dt;
  DynamicSolver solver(model, options);
  std::vector<double> tip{model.committed_displacement()(3 * n)};
  for (int k = 0; k < steps; ++k) {
    const SolveSummary s = solver.step();
    EXPECT_TRUE(s.converged) << s.message;
    if (!s.converged) break;
    EXPECT_LE(s.newton_iterations, 3);  // linear problem, exact tangent: one correction
    tip.push_back(model.committed_displacement()(3 * n));
  }
  return tip;
}

// Times at which the history crosses zero downwards (from + to -), linearly interpolated.
std::vector<double> downward_crossings(const std::vector<double>& x, double dt) {
  std::vector<double> t;
  for (std::size_t k = 1; k < x.size(); ++k)
    if (x[k - 1] > 0.0 && x[k] <= 0.0) t.push_back(dt * (k - 1 + x[k - 1] / (x[k - 1] - x[k])));
  return t;
}

TEST(CantileverVibration, FirstPeriodFromBackwardEulerDynamics) {
  const double T1 = euler_bernoulli_t1();
  const double dt = T1 / 400.0;  // backward-Euler period elongation ~ (omega dt)^2 / 3 = 8e-5
  for (TransfKind transf : {TransfKind::kLinear, TransfKind::kCorotational}) {
    for (MassKind mass : {MassKind::kLumped, MassKind::kConsistent}) {
      const int n = 20;
      StructureModel model = cantilever(n, mass, transf);
      const std::vector<double> tip = free_vibration(model, n, dt, 1000);
      const std::vector<double> crossings = downward_crossings(tip, dt);
      ASSERT_GE(crossings.size(), 2u);
      const double period = crossings[1] - crossings[0];
      EXPECT_NEAR(period / T1, 1.0, 0.02)
          << (mass == MassKind::kLumped ? "lumped" : "consistent") << " mass, period " << period;
    }
  }
}

// Mass-proportional damping C = a0 M gives mode 1 the damping ratio a0 / (2 omega1): after one
// period the amplitude ratio of the damped to the undamped run is exp(-2 pi zeta).
TEST(CantileverVibration, RayleighMassDampingDecay) {
  const double T1 = euler_bernoulli_t1();
  const double omega = 2.0 * std::numbers::pi / T1;
  const double zeta = 0.02;
  const double dt = T1 / 400.0;
  const int n = 10;
  StructureModel undamped = cantilever(n, MassKind::kConsistent);
  StructureModel damped = cantilever(n, MassKind::kConsistent);
  damped.set_rayleigh({2.0 * zeta * omega, 0.0});
  const std::vector<double> a = free_vibration(undamped, n, dt, 400);
  const std::vector<double> b = free_vibration(damped, n, dt, 400);
  const double ratio = b.back() / a.back();  // both near the start position after one period
  EXPECT_NEAR(-std::log(ratio) / (2.0 * std::numbers::pi), zeta, 0.05 * zeta);
}

}  // namespace
}  // namespace pfem::structure
