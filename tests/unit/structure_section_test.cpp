// Sections: the fiber section's elastic moment-curvature against E b d^3/12 (with the midpoint
// rule's exact discretisation error), its plastic moment against Fy b d^2/4, its tangent
// against finite differences in yielded states, the trial/commit protocol, bad input.
#include <gtest/gtest.h>

#include "tests/unit/expect_invalid.h"

#include <stdexcept>
#include <string>

#include "engine/structure/bilinear_material.h"
#include "engine/structure/elastic_material.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/finite_difference.h"

namespace pfem::structure {
namespace {

constexpr double kWidth = 0.2, kDepth = 0.3, kE = 2.0e5;

TEST(FiberSection, ElasticMomentCurvatureIsEIWithMidpointError) {
  const double EI = kE * kWidth * kDepth * kDepth * kDepth / 12.0;
  for (int n : {1, 2, 5, 10, 20, 50}) {
    FiberSection s(ElasticMaterial(kE), {kWidth, kDepth, n});
    const double kappa = 1e-3;
    s.set_trial_deformation(Vec2(0.0, kappa));
    const double EI_n = EI * (1.0 - 1.0 / (n * n));  // midpoint rule, exact
    EXPECT_NEAR(s.resultant()(1) / kappa, EI_n, 1e-12 * EI) << n << " fibers";
    EXPECT_NEAR(s.tangent()(1, 1), EI_n, 1e-12 * EI) << n << " fibers";
    EXPECT_NEAR(s.resultant()(0), 0.0, 1e-12 * EI) << n << " fibers";
    if (n >= 10) {
      EXPECT_LE(std::abs(s.tangent()(1, 1) / EI - 1.0), 0.01 + 1e-12) << n;
    }
    // Axial: EA exact for any n, no coupling in a symmetric elastic section.
    s.set_trial_deformation(Vec2(1e-4, 0.0));
    EXPECT_NEAR(s.resultant()(0), kE * kWidth * kDepth * 1e-4, 1e-9);
    EXPECT_NEAR(s.tangent()(0, 1), 0.0, 1e-12 * EI);
  }
}

TEST(FiberSection, PlasticMomentIsFyBD2Over4) {
  const double fy = 250.0;
  const double Mp = fy * kWidth * kDepth * kDepth / 4.0;
  for (int n : {10, 20, 9}) {
    FiberSection s(BilinearMaterial(fy, kE, 0.0), {kWidth, kDepth, n});
    // The innermost fiber (|y| >= d/(2n), or y = 0 for odd n) must be far past yield.
    const double kappa = 100.0 * (fy / kE) * 2.0 * n / kDepth;
    s.set_trial_deformation(Vec2(0.0, kappa));
    // Midpoint rule: exact for even n, Mp (1 - 1/n^2) for odd n (the middle fiber carries no
    // moment).
    const double Mp_n = (n % 2 == 0) ? Mp : Mp * (1.0 - 1.0 / (n * n));
    EXPECT_NEAR(s.resultant()(1), Mp_n, 1e-9 * Mp) << n << " fibers";
    EXPECT_NEAR(s.resultant()(0), 0.0, 1e-9 * fy * kWidth * kDepth);
    EXPECT_NEAR(s.tangent()(1, 1), 0.0, 1e-12 * kE * kWidth * kDepth * kDepth * kDepth);
  }
}

Eigen::MatrixXd section_fd(FiberSection& s, const Vec2& e) {
  auto f = [&s](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    s.set_trial_deformation(Vec2(x(0), x(1)));
    return s.resultant();
  };
  Eigen::MatrixXd J = central_difference_jacobian(f, Eigen::VectorXd(e), 1e-10);
  s.set_trial_deformation(e);
  return J;
}

TEST(FiberSection, TangentMatchesFiniteDifferenceInYieldedStates) {
  FiberSection s(BilinearMaterial(250.0, kE, 0.02), {kWidth, kDepth, 10});
  const double ey = 250.0 / kE;
  const Vec2 states[] = {{0.3 * ey, 4.0 * ey / kDepth},
                         {-0.2 * ey, -9.0 * ey / kDepth},
                         {0.1 * ey, 2.3 * ey / kDepth}};
  for (const Vec2& e : states) {
    s.set_trial_deformation(e);
    const Mat2 k = s.tangent();
    const Eigen::MatrixXd fd = section_fd(s, e);
    EXPECT_LE((k - fd).cwiseAbs().maxCoeff(), 1e-6 * k.cwiseAbs().maxCoeff())
        << "at " << e.transpose() << "\nanalytic\n"
        << k << "\nfd\n"
        << fd;
    s.commit();  // the next state starts from a yielded history
  }
  int plastic = 0;
  for (int k = 0; k < s.num_fibers(); ++k)
    plastic += dynamic_cast<const BilinearMaterial&>(s.fiber_material(k)).is_plastic();
  EXPECT_GT(plastic, 0);
  EXPECT_LT(plastic, s.num_fibers());
}

TEST(FiberSection, RevertAndCloneKeepTheCommittedState) {
  FiberSection s(BilinearMaterial(250.0, kE, 0.02), {kWidth, kDepth, 10});
  s.set_trial_deformation(Vec2(1e-3, 0.05));
  s.commit();
  const Vec2 committed = s.resultant();
  s.set_trial_deformation(Vec2(-2e-3, -0.1));
  s.revert_to_last_commit();
  EXPECT_NEAR((s.resultant() - committed).norm(), 0.0, 1e-9 * committed.norm());
  auto copy = s.clone();
  copy->set_trial_deformation(Vec2(-2e-3, -0.1));
  EXPECT_NEAR((s.resultant() - committed).norm(), 0.0, 1e-9 * committed.norm());
  EXPECT_DOUBLE_EQ(s.area(), kWidth * kDepth);
}

TEST(ElasticSection, ResultantsAreEAAndEI) {
  ElasticSection s({kE, 0.06, 4.5e-4});
  s.set_trial_deformation(Vec2(1e-3, 2e-2));
  EXPECT_DOUBLE_EQ(s.resultant()(0), kE * 0.06 * 1e-3);
  EXPECT_DOUBLE_EQ(s.resultant()(1), kE * 4.5e-4 * 2e-2);
}

TEST(Sections, InvalidInputNamesTheProblem) {
  const ElasticMaterial m(kE);
  expect_invalid([&] { FiberSection s(m, {kWidth, kDepth, 0}); }, "fibers", "must be >= 1");
  expect_invalid([&] { FiberSection s(m, {0.0, kDepth, 10}); }, "width", "must be > 0");
  expect_invalid([&] { FiberSection s(m, {kWidth, -kDepth, 10}); }, "depth", "must be > 0");
  expect_invalid([] { ElasticSection s({0.0, 1.0, 1.0}); }, "e", "must be > 0");
  expect_invalid([] { ElasticSection s({1.0, 0.0, 1.0}); }, "a", "must be > 0");
  expect_invalid([] { ElasticSection s({1.0, 1.0, -1.0}); }, "i", "must be > 0");
}

}  // namespace
}  // namespace pfem::structure
