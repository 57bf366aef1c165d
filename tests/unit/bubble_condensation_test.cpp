// The bubble condensed per element (engine/solve/bubble_condensation.*) against the system with
// the bubbles kept as unknowns: on a small mesh with a fixed wall node, the condensed matrices
// assembled and solved by solve_condensed give the same velocities (bubbles recovered) and
// pressures as a dense solve of the full Jacobian, for the symmetric Newton matrix and for the
// exact Jacobian with random geometric derivatives.
#include "engine/solve/bubble_condensation.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>
#include <vector>

namespace pfem {
namespace {

TEST(BubbleCondensation, SolvesAsTheSystemWithBubbles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  NodeState nodes;
  nodes.add(0.0, 0.0, mesh::NodeKind::Fluid);
  nodes.add(0.01, 0.0, mesh::NodeKind::Fluid);
  nodes.add(0.0, 0.01, mesh::NodeKind::Fluid);
  nodes.add(0.012, 0.011, mesh::NodeKind::Wall);
  mesh::FluidMesh mesh;
  mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  mesh.in_mesh = {1, 1, 1, 1};
  const StepNumbering num = number_unknowns(mesh, nodes, {}, nullptr, {});
  const double dt = 1e-3;
  for (const bool geometric : {false, true}) {
    const int nv = num.velocities, nc = num.node_velocities + num.pressures;
    Eigen::MatrixXd full = Eigen::MatrixXd::Zero(nv + num.pressures, nv + num.pressures);
    Eigen::MatrixXd condensed = Eigen::MatrixXd::Zero(nc, nc);
    std::vector<BubbleCondensation> bubbles(mesh.triangles.size());
    Eigen::VectorXd mp = Eigen::VectorXd::Zero(num.pressures);
    for (int e = 0; e < 2; ++e) {
      const auto& tri = mesh.triangles[e];
      std::array<double, 3> x, y;
      for (int a = 0; a < 3; ++a) x[a] = nodes.x[tri[a]], y[a] = nodes.y[tri[a]];
      fluid::MiniMatrices m;
      fluid::mini_matrices(fluid::triangle_geometry(x, y), {1000.0, 0.1, 2.15e9}, 0.01, 0.0, -9.81, m);
      fluid::GeometricDerivatives g;
      g.drv_dx.setZero();
      g.drp_dx.setZero();
      if (geometric) {
        for (int r = 0; r < 8; ++r)
          for (int c = 0; c < 6; ++c) g.drv_dx(r, c) = 1e3 * u(rng);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 6; ++c) g.drp_dx(r, c) = 1e-6 * u(rng);
      }
      // The full element Jacobian [a -G; Q Gc_b^T] (+ Mp/dt below) in the unknowns with bubbles.
      fluid::Mat8 a;
      Eigen::Matrix<double, 3, 6> q;
      element_jacobian(m, dt, geometric ? &g : nullptr, a, q);
      const fluid::Mat83& gc = geometric ? m.Gc : m.G;
      const auto dof = num.element_velocities(tri, e);
      for (int r = 0; r < 8; ++r) {
        if (dof[r] < 0) continue;
        for (int c = 0; c < 8; ++c)
          if (dof[c] >= 0) full(dof[r], dof[c]) += a(r, c);
        for (int k = 0; k < 3; ++k) full(dof[r], nv + num.corner_p[e][k]) -= m.G(r, k);
      }
      for (int k = 0; k < 3; ++k) {
        const int row = nv + num.corner_p[e][k];
        for (int c = 0; c < 6; ++c)
          if (dof[c] >= 0) full(row, dof[c]) += q(k, c);
        for (int c = 6; c < 8; ++c) full(row, dof[c]) += gc(c, k);
        mp[num.corner_p[e][k]] += m.Mp(k);
      }
      CondensedElement k;
      condense_element(m, dt, geometric ? &g : nullptr, bubbles[e], k);
      const auto cu = num.condensed_unknowns(tri, e);
      for (int r = 0; r < 9; ++r)
        for (int c = 0; c < 9; ++c)
          if (cu[r] >= 0 && cu[c] >= 0) condensed(cu[r], cu[c]) += k(r, c);
    }
    for (int p = 0; p < num.pressures; ++p) {
      full(nv + p, nv + p) += mp[p] / dt;
      condensed(num.node_velocities + p, num.node_velocities + p) -= mp[p] / dt;  // pressure rows negated
    }
    Eigen::MatrixXd rv(nv, 2), rp(num.pressures, 2);
    for (int c = 0; c < 2; ++c) {
      for (int r = 0; r < nv; ++r) rv(r, c) = u(rng);
      for (int r = 0; r < num.pressures; ++r) rp(r, c) = 1e-6 * u(rng);
    }
    Eigen::MatrixXd rhs(nv + num.pressures, 2);
    rhs << rv, rp;
    const Eigen::MatrixXd expected = full.fullPivLu().solve(rhs);
    Eigen::MatrixXd dv, dp;
    const auto lu = condensed.fullPivLu();
    solve_condensed(mesh, num, bubbles, [&](const Eigen::MatrixXd& b) { return Eigen::MatrixXd(lu.solve(b)); }, rv, rp,
                    dv, dp);
    EXPECT_LT((dv - expected.topRows(nv)).norm(), 1e-9 * expected.topRows(nv).norm()) << geometric;
    EXPECT_LT((dp - expected.bottomRows(num.pressures)).norm(), 1e-9 * expected.bottomRows(num.pressures).norm())
        << geometric;
  }
}

}  // namespace
}  // namespace pfem
