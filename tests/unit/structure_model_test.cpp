// StructureModel: the assembled tangent against finite differences of the assembled resisting
// force (a yielded corotational portal frame), mass and damping assembly, the trial/commit
// protocol, deep copies, the velocity-based residual's tangent, and bad input.
#include "engine/structure/structure_model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

#include "engine/structure/bilinear_material.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/dynamic_solver.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/finite_difference.h"

namespace pfem::structure {
namespace {

// Portal frame: columns of displacement-based fiber beams (the paper's obstacle material,
// nondimensionalised), an elastic beam on top; corotational throughout; clamped feet.
StructureModel portal_frame(MassKind mass = MassKind::kLumped) {
  StructureModel m;
  const int a = m.add_node(0.0, 0.0), b = m.add_node(0.0, 1.5), c = m.add_node(0.0, 3.0);
  const int d = m.add_node(2.0, 3.0), e = m.add_node(2.0, 1.5), f = m.add_node(2.0, 0.0);
  m.fix(a, true, true, true);
  m.fix(f, true, true, true);
  BeamOptions o;
  o.transf = TransfKind::kCorotational;
  o.mass = mass;
  o.rho = 3.0;
  const FiberSection column(BilinearMaterial(1.0, 200.0, 0.02), {0.2, 0.3, 10});
  m.add_disp_beam(a, b, column, o);
  m.add_disp_beam(b, c, column, o, 3);
  m.add_elastic_beam(c, d, {200.0, 0.06, 4.5e-4}, o);
  m.add_disp_beam(d, e, column, o);
  m.add_disp_beam(e, f, column, o, 3);
  m.add_nodal_mass(c, 0.5, 0.5, 0.0);
  return m;
}

Eigen::MatrixXd dense(int n, const std::function<void(const AddEntry&)>& fill) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  fill([&A](int i, int j, double v) { A(i, j) += v; });
  return A;
}

// A sway displacement that yields the column fibers.
Eigen::VectorXd sway(const StructureModel& m, double amplitude) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.num_dofs());
  const double ux[] = {0.0, 0.45, 1.0, 1.0, 0.47, 0.0};
  for (int n = 0; n < 6; ++n) {
    if (n == 0 || n == 5) continue;
    u(3 * n) = amplitude * ux[n];
    u(3 * n + 1) = -0.013 * amplitude * n;
    u(3 * n + 2) = -0.31 * amplitude * (n == 1 || n == 4 ? 1.0 : 0.37);
  }
  return u;
}

int plastic_fibers(const StructureModel& m) {
  int count = 0;
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto* beam = dynamic_cast<const DispBeamColumn2d*>(&m.element(e));
    if (!beam) continue;
    for (int k = 0; k < beam->num_integration_points(); ++k) {
      const auto& s = dynamic_cast<const FiberSection&>(beam->section(k));
      for (int f = 0; f < s.num_fibers(); ++f)
        count += dynamic_cast<const BilinearMaterial&>(s.fiber_material(f)).is_plastic();
    }
  }
  return count;
}

TEST(StructureModel, AssembledTangentMatchesFiniteDifference) {
  StructureModel m = portal_frame();
  // Yield, unload elastically, reverse-yield; each state committed.
  const Eigen::VectorXd path[] = {sway(m, 0.08), sway(m, 0.05), sway(m, -0.061)};
  for (int step = 0; step < 3; ++step) {
    const Eigen::VectorXd& u = path[step];
    m.set_trial_displacement(u);
    const Eigen::MatrixXd K = dense(m.num_dofs(), [&](const AddEntry& a) { m.add_tangent(a); });
    auto force = [&m](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      m.set_trial_displacement(x);
      return m.resisting_force();
    };
    const Eigen::MatrixXd fd = central_difference_jacobian(force, u, 1e-7);
    m.set_trial_displacement(u);
    EXPECT_LE((K - fd).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
    if (step != 1) {  // step 1 unloads elastically
      EXPECT_GT(plastic_fibers(m), 0) << "step " << step;
    }
    m.commit();
  }
}

TEST(StructureModel, MassAndDampingAssembly) {
  for (MassKind kind : {MassKind::kLumped, MassKind::kConsistent}) {
    StructureModel m = portal_frame(kind);
    const int n = m.num_dofs();
    const Eigen::MatrixXd M = dense(n, [&](const AddEntry& a) { m.add_mass(a); });
    // Total mass: rho * A * length for every member + the nodal mass.
    const double total = 3.0 * (0.06 * 6.0 + 0.06 * 2.0) + 0.5;
    Eigen::VectorXd ex = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < m.num_nodes(); ++k) ex(3 * k) = 1.0;
    EXPECT_NEAR(ex.dot(M * ex), total, 1e-12);
    const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    EXPECT_LE((m.mass_times(a) - M * a).norm(), 1e-12 * (M * a).norm());
    EXPECT_EQ(m.mass_is_lumped(), kind == MassKind::kLumped);
    if (kind == MassKind::kLumped) {
      EXPECT_LE((m.lumped_mass() - M.diagonal()).norm(), 1e-14);
      EXPECT_LE((M - Eigen::MatrixXd(M.diagonal().asDiagonal())).norm(), 0.0);
    } else {
      EXPECT_THROW(m.lumped_mass(), std::logic_error);
    }
    // C = a0 M + a1 K0, K0 the initial stiffness (also after yielding).
    m.set_rayleigh({0.3, 0.002});
    m.set_trial_displacement(sway(m, 0.08));
    const Eigen::MatrixXd K0 = dense(n, [&](const AddEntry& e) { m.add_initial_stiffness(e); });
    const Eigen::MatrixXd C = dense(n, [&](const AddEntry& e) { m.add_damping(e); });
    EXPECT_LE((C - (0.3 * M + 0.002 * K0)).norm(), 1e-12 * C.norm());
    EXPECT_LE((m.damping_times(a) - C * a).norm(), 1e-12 * (C * a).norm());
  }
}

// The structure's velocity-form residual r(v) = F - M (v - vn)/dt - C v - Fs(un + dt v) has
// the tangent -(M/dt + C + dt dFs/du), the block the lead adds to the monolithic KTvv.
TEST(StructureModel, VelocityResidualTangent) {
  StructureModel m = portal_frame(MassKind::kConsistent);
  m.set_rayleigh({0.3, 0.002});
  const int n = m.num_dofs();
  const double dt = 0.01;
  const Eigen::VectorXd un = sway(m, 0.05), vn = sway(m, 0.4);
  const Eigen::VectorXd v = sway(m, 1.3);
  m.set_trial_displacement(un);
  m.commit();
  auto residual = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    m.set_trial_displacement(un + dt * x);
    return m.external_load() - m.mass_times(x - vn) / dt - m.damping_times(x) - m.resisting_force();
  };
  const Eigen::MatrixXd fd = central_difference_jacobian(residual, v, 1e-6);
  m.set_trial_displacement(un + dt * v);
  const Eigen::MatrixXd KT = dense(n, [&](const AddEntry& a) {
    m.add_mass(a, 1.0 / dt);
    m.add_damping(a);
    m.add_tangent(a, dt);
  });
  EXPECT_LE((KT + fd).cwiseAbs().maxCoeff(), 1e-6 * KT.cwiseAbs().maxCoeff());
}

TEST(StructureModel, RevertAndCopy) {
  StructureModel m = portal_frame();
  m.set_trial_displacement(sway(m, 0.08));
  m.commit();
  const Eigen::VectorXd committed = m.resisting_force();
  StructureModel copy(m);
  m.set_trial_displacement(sway(m, -0.1));
  m.revert_to_last_commit();
  EXPECT_LE((m.resisting_force() - committed).norm(), 1e-12 * committed.norm());
  EXPECT_EQ(m.trial_displacement(), m.committed_displacement());
  copy.set_trial_displacement(sway(m, -0.1));  // the copy's elements are its own
  EXPECT_LE((m.resisting_force() - committed).norm(), 1e-12 * committed.norm());
  copy.revert_to_last_commit();
  EXPECT_LE((copy.resisting_force() - committed).norm(), 1e-12 * committed.norm());
}

TEST(StructureModel, InvalidInputNamesTheProblem) {
  StructureModel m;
  m.add_node(0.0, 0.0);
  m.add_node(1.0, 0.0);
  try {
    m.add_elastic_beam(0, 2, {1.0, 1.0, 1.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "nodes: node 2 does not exist (2 nodes)");
  }
  EXPECT_THROW(m.fix(-1, true, true, true), std::invalid_argument);
  EXPECT_THROW(m.set_trial_displacement(Eigen::VectorXd::Zero(5)), std::invalid_argument);
  EXPECT_THROW(m.set_rayleigh({-1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(DynamicSolver(m, DynamicOptions{}), std::invalid_argument);  // dt = 0
}

}  // namespace
}  // namespace pfem::structure
