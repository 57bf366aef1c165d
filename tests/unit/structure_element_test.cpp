// Beam-column elements: the consistent tangent against central finite differences of the
// resisting force (both elements, both transformations, elastic and yielded fiber states),
// rigid-body motions, agreement of the two elements when elastic, mass, bad input.
#include <gtest/gtest.h>

#include "tests/unit/expect_invalid.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine/structure/bilinear_material.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/elastic_beam_column.h"
#include "engine/structure/elastic_material.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/finite_difference.h"

namespace pfem::structure {
namespace {

// Nondimensional steel-like data: eps_y = 5e-3, section 0.2 x 0.3, an inclined 2-long beam.
constexpr double kE0 = 200.0, kFy = 1.0, kHardening = 0.05;
constexpr double kWidth = 0.2, kDepth = 0.3;
const Vec2 kXi(0.3, -0.1);
const Vec2 kXj(0.3 + 2.0 * 0.8, -0.1 + 2.0 * 0.6);  // L0 = 2

std::unique_ptr<BeamColumn2d> make_beam(bool fiber, TransfKind transf, int points = 2) {
  BeamOptions o;
  o.transf = transf;
  o.rho = 7.0;
  if (!fiber)
    return std::make_unique<ElasticBeamColumn2d>(std::array<int, 2>{0, 1}, kXi, kXj,
                                                 ElasticSectionProperties{kE0, 0.06, 4.5e-4}, o);
  const FiberSection section(BilinearMaterial(kFy, kE0, kHardening), {kWidth, kDepth, 10});
  return std::make_unique<DispBeamColumn2d>(std::array<int, 2>{0, 1}, kXi, kXj, section, o, points);
}

// Relative max-norm mismatch between the analytic tangent at u and the central difference of
// the resisting force, both from the element's committed state.
double tangent_mismatch(Element& e, const Vec6& u) {
  e.set_trial_displacement(u);
  const Mat6 K = e.tangent_stiffness();
  auto force = [&e](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    e.set_trial_displacement(Vec6(x));
    return e.resisting_force();
  };
  const Eigen::MatrixXd fd = central_difference_jacobian(force, Eigen::VectorXd(u), 1e-7);
  e.set_trial_displacement(u);
  return (K - fd).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
}

// A general displacement of the end nodes: rigid rotation `theta` about node i plus a
// translation, plus deformation (stretch and end rotations relative to the chord).
Vec6 displacement(double theta, double stretch, double ri, double rj) {
  const Vec2 d0 = kXj - kXi;
  const double c = std::cos(theta), s = std::sin(theta);
  const Vec2 dj = (1.0 + stretch) * Vec2(c * d0(0) - s * d0(1), s * d0(0) + c * d0(1)) - d0;
  const Vec2 t(0.05, -0.02);
  Vec6 u;
  u << t(0), t(1), theta + ri, t(0) + dj(0), t(1) + dj(1), theta + rj;
  return u;
}

int plastic_fibers(const BeamColumn2d& beam) {
  const auto* disp = dynamic_cast<const DispBeamColumn2d*>(&beam);
  if (!disp) return 0;
  int count = 0;
  for (int k = 0; k < disp->num_integration_points(); ++k) {
    const auto& s = dynamic_cast<const FiberSection&>(disp->section(k));
    for (int f = 0; f < s.num_fibers(); ++f)
      count += dynamic_cast<const BilinearMaterial&>(s.fiber_material(f)).is_plastic();
  }
  return count;
}

struct Case {
  bool fiber;
  TransfKind transf;
  const char* name;
};
const Case kCases[] = {{false, TransfKind::kLinear, "elastic/linear"},
                       {false, TransfKind::kCorotational, "elastic/corotational"},
                       {true, TransfKind::kLinear, "disp-fiber/linear"},
                       {true, TransfKind::kCorotational, "disp-fiber/corotational"}};

// Rigid rotation of the test displacements: none for the Linear transformation (which is
// only meant for small rotations), `theta` for the corotational one.
double rigid(const Case& c, double theta) {
  return c.transf == TransfKind::kCorotational ? theta : 0.0;
}

TEST(BeamTangent, MatchesFiniteDifferenceInElasticStates) {
  for (const Case& c : kCases) {
    auto beam = make_beam(c.fiber, c.transf);
    // Small deformation (fibers elastic: |strain| < 5e-3), large rigid rotation if corotational.
    const Vec6 u = displacement(rigid(c, 0.7), 1e-4, 0.004, -0.003);
    EXPECT_LE(tangent_mismatch(*beam, u), 1e-6) << c.name;
    EXPECT_EQ(plastic_fibers(*beam), 0) << c.name;
  }
}

TEST(BeamTangent, MatchesFiniteDifferenceInYieldedStates) {
  for (const Case& c : kCases) {
    for (int points : {2, 3, 5}) {
      auto beam = make_beam(c.fiber, c.transf, points);
      // Yield in bending and tension, commit, unload (elastically), then reverse-yield.
      // (Values chosen so that no fiber sits on a yield kink, where no derivative exists.)
      const Vec6 path[] = {displacement(rigid(c, 0.4), 2.13e-3, 0.0613, -0.0187),
                           displacement(rigid(c, 0.5), 1.71e-3, 0.0512, -0.0093),
                           displacement(rigid(c, 0.3), -3.07e-3, -0.0494, 0.0451)};
      int step = 0;
      for (const Vec6& u : path) {
        ++step;
        EXPECT_LE(tangent_mismatch(*beam, u), 1e-6)
            << c.name << ", " << points << " points, step " << step;
        if (c.fiber && step != 2) {  // step 2 unloads most fibers elastically
          EXPECT_GT(plastic_fibers(*beam), 0) << c.name << " step " << step;
        }
        beam->commit();
      }
    }
  }
}

TEST(BeamTangent, OneAndTenIntegrationPoints) {
  for (int points : {1, 10}) {
    auto beam = make_beam(true, TransfKind::kCorotational, points);
    const Vec6 u = displacement(1.2, 1.5e-3, 0.05, -0.04);
    EXPECT_LE(tangent_mismatch(*beam, u), 1e-6) << points << " points";
  }
}

TEST(CorotationalBeam, RigidBodyMotionGivesNoForce) {
  for (bool fiber : {false, true}) {
    auto beam = make_beam(fiber, TransfKind::kCorotational);
    // Beyond a full turn: the chord-rotation branch follows the nodal rotations.
    for (double theta : {0.3, 2.5, -3.0, 7.0}) {
      beam->set_trial_displacement(displacement(theta, 0.0, 0.0, 0.0));
      EXPECT_LE(beam->resisting_force().norm(), 1e-12) << "theta " << theta;
    }
    // The same deformation superposed on different rigid rotations gives the same basic forces.
    beam->set_trial_displacement(displacement(0.1, 1e-4, 0.002, -0.001));
    const Vec3 q0 = beam->basic_force();
    beam->set_trial_displacement(displacement(0.1 + 2.0 * std::numbers::pi, 1e-4, 0.002, -0.001));
    EXPECT_LE((beam->basic_force() - q0).norm(), 1e-9 * q0.norm());
  }
}

TEST(BeamElements, ElasticDispBeamEqualsElasticBeam) {
  const ElasticSectionProperties p{kE0, 0.06, 4.5e-4};
  for (TransfKind t : {TransfKind::kLinear, TransfKind::kCorotational}) {
    BeamOptions o;
    o.transf = t;
    ElasticBeamColumn2d a({0, 1}, kXi, kXj, p, o);
    DispBeamColumn2d b({0, 1}, kXi, kXj, ElasticSection(p), o);  // 2 points: exact
    const Vec6 u = displacement(0.9, 2e-3, 0.05, -0.07);
    a.set_trial_displacement(u);
    b.set_trial_displacement(u);
    EXPECT_LE((a.resisting_force() - b.resisting_force()).norm(),
              1e-12 * a.resisting_force().norm());
    EXPECT_LE((a.tangent_stiffness() - b.tangent_stiffness()).norm(),
              1e-12 * a.tangent_stiffness().norm());
  }
}

TEST(BeamElements, InitialStiffnessIsTangentAtRest) {
  for (const Case& c : kCases) {
    auto beam = make_beam(c.fiber, c.transf);
    beam->set_trial_displacement(Vec6::Zero());
    EXPECT_LE((beam->initial_stiffness() - beam->tangent_stiffness()).norm(),
              1e-12 * beam->initial_stiffness().norm())
        << c.name;
  }
}

TEST(BeamElements, RevertRestoresTheCommittedForce) {
  auto beam = make_beam(true, TransfKind::kCorotational);
  beam->set_trial_displacement(displacement(0.4, 2e-3, 0.06, -0.02));
  beam->commit();
  const Vec6 committed = beam->resisting_force();
  beam->set_trial_displacement(displacement(0.1, -4e-3, -0.08, 0.05));
  beam->revert_to_last_commit();
  EXPECT_LE((beam->resisting_force() - committed).norm(), 1e-12 * committed.norm());
  auto copy = beam->clone();
  copy->set_trial_displacement(Vec6::Zero());
  EXPECT_LE((beam->resisting_force() - committed).norm(), 1e-12 * committed.norm());
}

TEST(BeamMass, TotalMassAndRotationalInertia) {
  const double m = 7.0 * 0.06, L = 2.0;
  for (MassKind kind : {MassKind::kLumped, MassKind::kConsistent}) {
    BeamOptions o;
    o.rho = 7.0;
    o.mass = kind;
    ElasticBeamColumn2d beam({0, 1}, kXi, kXj, ElasticSectionProperties{kE0, 0.06, 4.5e-4}, o);
    const Mat6& M = beam.mass_matrix();
    // A rigid translation in any direction carries the whole mass m L.
    for (double angle : {0.0, 0.6, 2.0}) {
      Vec6 t;
      t << std::cos(angle), std::sin(angle), 0.0, std::cos(angle), std::sin(angle), 0.0;
      EXPECT_NEAR(t.dot(M * t), m * L, 1e-12) << "angle " << angle;
    }
    EXPECT_LE((M - M.transpose()).norm(), 1e-14);
    EXPECT_EQ(beam.has_lumped_mass(), kind == MassKind::kLumped);
  }
  // Consistent mass: a rigid rotation about the midpoint has inertia m L^3 / 12.
  BeamOptions o;
  o.rho = 7.0;
  o.mass = MassKind::kConsistent;
  ElasticBeamColumn2d beam({0, 1}, kXi, kXj, ElasticSectionProperties{kE0, 0.06, 4.5e-4}, o);
  const Vec2 n(-0.6, 0.8);  // normal to the axis
  Vec6 r;
  r << -n(0) * L / 2, -n(1) * L / 2, 1.0, n(0) * L / 2, n(1) * L / 2, 1.0;
  EXPECT_NEAR(r.dot(beam.mass_matrix() * r), m * L * L * L / 12.0, 1e-12);
}

TEST(BeamElements, InvalidInputNamesTheProblem) {
  const ElasticSectionProperties p{kE0, 0.06, 4.5e-4};
  const ElasticSection section(p);
  for (TransfKind t : {TransfKind::kLinear, TransfKind::kCorotational}) {
    BeamOptions o;
    o.transf = t;
    expect_invalid(
        [&] {
          ElasticBeamColumn2d b({0, 1}, kXi, kXi, p, o);
        },
        "length", "zero-length beam");
    expect_invalid(
        [&] {
          DispBeamColumn2d b({0, 1}, kXj, kXj, section, o);
        },
        "length", "zero-length beam");
  }
  expect_invalid(
      [&] {
        DispBeamColumn2d b({0, 1}, kXi, kXj, section, {}, 0);
      },
      "integration_points", "must be in 1..10");
  expect_invalid(
      [&] {
        DispBeamColumn2d b({0, 1}, kXi, kXj, section, {}, 11);
      },
      "integration_points", "must be in 1..10");
  BeamOptions negative_rho;
  negative_rho.rho = -1.0;
  expect_invalid(
      [&] {
        ElasticBeamColumn2d b({0, 1}, kXi, kXj, p, negative_rho);
      },
      "rho", "must be >= 0");
  expect_invalid(
      [&] {
        ElasticBeamColumn2d b({0, 1}, kXi, kXj, {kE0, 0.06, 0.0});
      },
      "i", "must be > 0");
}

}  // namespace
}  // namespace pfem::structure
