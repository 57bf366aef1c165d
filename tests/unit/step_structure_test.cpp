// The structure's part of a step on a cantilever with a tip mass, against closed forms: the
// weight of the tip mass in its residual at rest (none without self-weight), the rotation rate of
// t_n in the initial iterate, and its Newton block M/dt + dt K (EA/L, 12 EI/L^3, 4 EI/L, 6 EI/L^2).
#include "engine/solve/step_structure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

namespace pfem {
namespace {

constexpr double kL = 0.5, kE = 200.0, kA = 0.06, kI = 4.5e-4, kMass = 2.0, kDt = 1e-3, kG = -9.81;

struct Cantilever {
  structure::StructureModel model;
  NodeState nodes;
  mesh::FluidMesh mesh;
  StructureCoupling coupling;
  StepNumbering num;
  Cantilever() {
    model.add_node(0.0, 0.0);
    model.add_node(kL, 0.0);
    model.fix(0, true, true, true);
    model.add_elastic_beam(0, 1, {kE, kA, kI});
    model.add_nodal_mass(1, kMass, kMass);
    nodes.add(0.0, 0.0, mesh::NodeKind::Structure);
    nodes.add(kL, 0.0, mesh::NodeKind::Structure);
    mesh.in_mesh = {1, 1};
    coupling.model = &model;
    coupling.node = {0, 1};
    num = number_unknowns(mesh, nodes, {}, &model, coupling.node);
  }
};

TEST(StepStructure, TheTipMassWeighsOnItsRowAtRest) {
  Cantilever c;
  ASSERT_EQ(c.num.node_velocities, 3);  // the tip's x, y and rotation rate
  StepStructure part;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3), rv = Eigen::VectorXd::Zero(3);
  part.begin(c.coupling, c.num, kDt, 0.0, kG, c.nodes, v);
  const double scale = part.add_residual(v, rv);
  EXPECT_DOUBLE_EQ(rv[c.num.vy[1]], kMass * kG);
  EXPECT_EQ(rv[c.num.vx[1]], 0.0);
  EXPECT_EQ(rv[c.num.structure[5]], 0.0);
  EXPECT_DOUBLE_EQ(scale, kMass * std::abs(kG));  // the inertia term (M times -g), alone

  c.coupling.self_weight = false;
  rv.setZero();
  part.begin(c.coupling, c.num, kDt, 0.0, kG, c.nodes, v);
  EXPECT_EQ(part.add_residual(v, rv), 0.0);
  EXPECT_EQ(rv.norm(), 0.0);
}

TEST(StepStructure, TheRotationRateOfTnStartsTheIterate) {
  Cantilever c;
  c.nodes.wz[1] = 0.3;
  StepStructure part;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3);
  part.begin(c.coupling, c.num, kDt, 0.0, kG, c.nodes, v);
  EXPECT_EQ(v[c.num.structure[5]], 0.3);
  // Moving at that rate, the tip's inertia is M (w - w_n)/dt = 0: only its stiffness resists.
  Eigen::VectorXd rv = Eigen::VectorXd::Zero(3);
  c.coupling.self_weight = false;
  part.add_residual(v, rv);
  // The tip rotated by dt w: the moment 4 EI/L dt w and the shear 6 EI/L^2 dt w resist it.
  EXPECT_NEAR(std::abs(rv[c.num.structure[5]]), 4 * kE * kI / kL * kDt * 0.3, 1e-12);
  EXPECT_NEAR(std::abs(rv[c.num.vy[1]]), 6 * kE * kI / (kL * kL) * kDt * 0.3, 1e-12);
}

TEST(StepStructure, ItsNewtonBlockIsMassOverDtPlusDtTimesTheStiffness) {
  Cantilever c;
  StepStructure part;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3), rv = Eigen::VectorXd::Zero(3);
  part.begin(c.coupling, c.num, kDt, 0.0, kG, c.nodes, v);
  part.add_residual(v, rv);  // the trial state the tangent is taken at
  std::map<std::pair<int, int>, double> k;
  for (const auto& t : part.tangent_lower()) {
    EXPECT_GE(t.row(), t.col());
    k[{t.row(), t.col()}] += t.value();
  }
  const int x = c.num.vx[1], y = c.num.vy[1], r = c.num.structure[5];
  const auto entry = [&k](int a, int b) {
    const auto it = k.find({std::max(a, b), std::min(a, b)});
    return it == k.end() ? 0.0 : it->second;
  };
  EXPECT_NEAR(entry(x, x), kMass / kDt + kDt * kE * kA / kL, 1e-9);
  EXPECT_NEAR(entry(y, y), kMass / kDt + kDt * 12 * kE * kI / (kL * kL * kL), 1e-9);
  EXPECT_NEAR(entry(r, r), kDt * 4 * kE * kI / kL, 1e-12);
  EXPECT_NEAR(std::abs(entry(y, r)), kDt * 6 * kE * kI / (kL * kL), 1e-12);
  EXPECT_EQ(entry(x, y), 0.0);  // axial and bending uncoupled in a straight beam
}

}  // namespace
}  // namespace pfem
