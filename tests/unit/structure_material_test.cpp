// Uniaxial materials: the bilinear kinematic-hardening path at hand-computed points, its
// consistent tangent against finite differences, the trial/commit protocol, bad input.
#include <gtest/gtest.h>

#include "tests/unit/expect_invalid.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/structure/bilinear_material.h"
#include "engine/structure/elastic_material.h"

namespace pfem::structure {
namespace {

constexpr double kFy = 250.0, kE0 = 2.0e5, kB = 0.1;  // eps_y = 1.25e-3, b E0 = 2e4

double fd_tangent(UniaxialMaterial& m, double strain, double h = 1e-9) {
  m.set_trial_strain(strain + h);
  const double sp = m.stress();
  m.set_trial_strain(strain - h);
  const double sm = m.stress();
  m.set_trial_strain(strain);
  return (sp - sm) / (2.0 * h);
}

TEST(ElasticMaterial, StressIsEStrain) {
  ElasticMaterial m(210e9);
  m.set_trial_strain(1e-3);
  EXPECT_DOUBLE_EQ(m.stress(), 210e6);
  EXPECT_DOUBLE_EQ(m.tangent(), 210e9);
}

// Cyclic path, each point committed. Hand computation with H = b E0 / (1 - b) = 22222.2:
//   eps 0.001   elastic                      sigma =  200
//   eps 0.005   yield at 250, then b E0      sigma =  250 + 2e4 * 0.00375 = 325, alpha = 75
//   eps 0.0035  elastic unloading            sigma =  325 - 2e5 * 0.0015  = 25
//   eps 0.0025  reverse yield at alpha - Fy  sigma = -175 (reached elastically, 500 = 2 Fy below
//   325) eps 0.0     reverse hardening            sigma = -175 - 2e4 * 0.0025  = -225, alpha = 25
//   eps 0.002   elastic reloading            sigma = -225 + 2e5 * 0.002   = 175
//   eps 0.004   yield again at alpha + Fy = 275 (eps 0.0025), then 275 + 2e4 * 0.0015 = 305
TEST(BilinearMaterial, CyclicPathAtHandComputedPoints) {
  BilinearMaterial m(kFy, kE0, kB);
  struct Point {
    double strain, stress, tangent;
    bool plastic;
  };
  const Point path[] = {{0.001, 200.0, kE0, false},    {0.005, 325.0, kB * kE0, true},
                        {0.0035, 25.0, kE0, false},    {0.0025, -175.0, kE0, false},
                        {0.0, -225.0, kB * kE0, true}, {0.002, 175.0, kE0, false},
                        {0.004, 305.0, kB * kE0, true}};
  for (const Point& p : path) {
    m.set_trial_strain(p.strain);
    EXPECT_NEAR(m.stress(), p.stress, 1e-9) << "strain " << p.strain;
    EXPECT_NEAR(m.tangent(), p.tangent, 1e-9) << "strain " << p.strain;
    EXPECT_EQ(m.is_plastic(), p.plastic) << "strain " << p.strain;
    m.commit();
  }
  // Back stress after the last step: alpha = sigma - Fy = 55; plastic strain = eps - sigma/E0.
  EXPECT_NEAR(m.committed_history().back_stress, 55.0, 1e-9);
  EXPECT_NEAR(m.committed_history().plastic_strain, 0.004 - 305.0 / kE0, 1e-15);
}

TEST(BilinearMaterial, YieldStartsExactlyAtFy) {
  BilinearMaterial m(kFy, kE0, kB);
  m.set_trial_strain(kFy / kE0);
  EXPECT_NEAR(m.stress(), kFy, 1e-12);
  EXPECT_FALSE(m.is_plastic());
  m.set_trial_strain(kFy / kE0 * 1.001);
  EXPECT_TRUE(m.is_plastic());
  EXPECT_NEAR(m.stress(), kFy + kB * kE0 * kFy / kE0 * 0.001, 1e-9);
}

TEST(BilinearMaterial, PerfectlyPlasticHoldsFy) {
  BilinearMaterial m(kFy, kE0, 0.0);
  m.set_trial_strain(0.01);
  EXPECT_NEAR(m.stress(), kFy, 1e-12 * kFy);
  EXPECT_DOUBLE_EQ(m.tangent(), 0.0);
  m.commit();
  m.set_trial_strain(-0.01);
  EXPECT_NEAR(m.stress(), -kFy, 1e-12 * kFy);
}

TEST(BilinearMaterial, ConsistentTangentMatchesFiniteDifference) {
  BilinearMaterial m(kFy, kE0, kB);
  // Visit trial states from several committed histories, away from the yield kinks.
  const double committed_path[] = {0.0, 0.004, -0.003, 0.0015};
  const double probes[] = {-0.006, -0.002, 0.0004, 0.0031, 0.007};
  for (double c : committed_path) {
    m.set_trial_strain(c);
    m.commit();
    for (double e : probes) {
      m.set_trial_strain(e);
      const double analytic = m.tangent();
      const double numeric = fd_tangent(m, e);
      EXPECT_NEAR(analytic, numeric, 1e-6 * kE0) << "committed " << c << " strain " << e;
    }
  }
}

TEST(BilinearMaterial, TrialStatesStartFromTheCommittedState) {
  BilinearMaterial m(kFy, kE0, kB);
  m.set_trial_strain(0.005);  // plastic trial, not committed
  m.set_trial_strain(0.001);  // elastic from the virgin state again
  EXPECT_NEAR(m.stress(), 200.0, 1e-9);
  m.set_trial_strain(0.005);
  m.commit();
  m.set_trial_strain(-0.01);
  m.revert_to_last_commit();
  EXPECT_NEAR(m.stress(), 325.0, 1e-9);
  EXPECT_NEAR(m.strain(), 0.005, 0);
  auto copy = m.clone();  // the clone carries the history
  copy->set_trial_strain(0.0035);
  EXPECT_NEAR(copy->stress(), 25.0, 1e-9);
}

TEST(Materials, InvalidInputNamesTheProblem) {
  expect_invalid([] { ElasticMaterial m(0.0); }, "e", "must be > 0");
  expect_invalid([] { BilinearMaterial m(-1.0, kE0, kB); }, "fy", "must be > 0");
  expect_invalid([] { BilinearMaterial m(kFy, 0.0, kB); }, "e0", "must be > 0");
  expect_invalid([] { BilinearMaterial m(kFy, kE0, 1.0); }, "hardening_ratio", "[0, 1)");
  expect_invalid([] { BilinearMaterial m(kFy, kE0, -0.01); }, "hardening_ratio", "[0, 1)");
  expect_invalid([] { BilinearMaterial m(std::nan(""), kE0, kB); }, "fy", "must be > 0");
}

}  // namespace
}  // namespace pfem::structure
