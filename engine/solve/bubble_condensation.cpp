#include "engine/solve/bubble_condensation.h"

#include <Eigen/LU>

namespace pfem {

void element_jacobian(const fluid::MiniMatrices& m, double dt, const fluid::GeometricDerivatives* geometric,
                      fluid::Mat8& a, Eigen::Matrix<double, 3, 6>& q) {
  // Element Jacobian -d(rv, rp)/d(v, p): [a -G; Q Gc_b^T Mp/dt] with a = M/dt + K - dt drv/dx and
  // Q = Gc_c^T - dt/2 drp/dx (the coordinates move with the corner velocities, x = x_n + dt v,
  // and the mass balance's midpoint with half of them). The Newton matrix takes G for Gc and no
  // drv/dx, drp/dx: symmetric, and off the Jacobian by terms of order dt |grad v|.
  const fluid::Mat83& gc = geometric ? m.Gc : m.G;
  a = m.M * (1.0 / dt) + m.K;
  q = gc.block<6, 3>(0, 0).transpose();
  if (geometric) {
    a.leftCols<6>() -= dt * geometric->drv_dx;
    q -= 0.5 * dt * geometric->drp_dx;
  }
}

void condense_element(const fluid::MiniMatrices& m, double dt, const fluid::GeometricDerivatives* geometric,
                      BubbleCondensation& b, CondensedElement& k) {
  const fluid::Mat83& gc = geometric ? m.Gc : m.G;
  fluid::Mat8 a;
  Eigen::Matrix<double, 3, 6> q;
  element_jacobian(m, dt, geometric, a, q);
  b.inv_bb = a.block<2, 2>(6, 6).inverse();
  b.a_bc = a.block<2, 6>(6, 0);
  b.a_cb = a.block<6, 2>(0, 6);
  b.g_b = m.G.block<2, 3>(6, 0);
  b.gc_b = gc.block<2, 3>(6, 0);
  // Element Schur complements with dvb = Abb^-1 (r_b - A_bc dvc + G_b dp):
  // A' = A_cc - A_cb Abb^-1 A_bc, G' = G_c - A_cb Abb^-1 G_b (velocity rows),
  // Q' = Q - Gc_b^T Abb^-1 A_bc, C = Gc_b^T Abb^-1 G_b (pressure rows, negated).
  const Eigen::Matrix<double, 6, 2> acb_inv = b.a_cb * b.inv_bb;
  const Eigen::Matrix<double, 3, 2> gcb_inv = b.gc_b.transpose() * b.inv_bb;
  k.topLeftCorner<6, 6>() = a.block<6, 6>(0, 0) - acb_inv * b.a_bc;
  k.topRightCorner<6, 3>() = acb_inv * b.g_b - m.G.block<6, 3>(0, 0);
  k.bottomLeftCorner<3, 6>() = gcb_inv * b.a_bc - q;
  k.bottomRightCorner<3, 3>() = -(gcb_inv * b.g_b);
}

void solve_condensed(const mesh::FluidMesh& mesh, const StepNumbering& num,
                     std::span<const BubbleCondensation> bubbles, const CondensedSolve& solve,
                     const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp, Eigen::MatrixXd& dv, Eigen::MatrixXd& dp) {
  // Column by column with fixed-size element blocks (small dynamic products cost more than
  // their arithmetic). Right-hand side with the bubble rows condensed in; pressure rows negated.
  const long cols = rv.cols();
  const int ne = static_cast<int>(mesh.triangles.size());
  Eigen::MatrixXd rhs(num.node_velocities + num.pressures, cols);
  rhs.topRows(num.node_velocities) = rv.topRows(num.node_velocities);
  rhs.bottomRows(num.pressures) = -rp;
  Eigen::MatrixXd z(2 * ne, cols);  // Abb^-1 r_b, two rows per element
  for (long c = 0; c < cols; ++c) {
    for (int e = 0; e < ne; ++e) {
      const auto& b = bubbles[e];
      const Eigen::Vector2d ze = b.inv_bb * rv.col(c).segment<2>(num.bubble(e));
      z.col(c).segment<2>(2 * e) = ze;
      const auto& tri = mesh.triangles[e];
      for (int k = 0; k < 3; ++k) {
        for (int d = 0; d < 2; ++d) num.add_to_velocity(tri[k], d, -b.a_cb.row(2 * k + d).dot(ze), rhs.col(c));
        rhs(num.node_velocities + num.corner_p[e][k], c) += b.gc_b.col(k).dot(ze);
      }
    }
  }
  const Eigen::MatrixXd x = solve(rhs);
  dv.resize(num.velocities, cols);
  dv.topRows(num.node_velocities) = x.topRows(num.node_velocities);
  dp = x.bottomRows(num.pressures);
  // Recover each bubble: dvb = Abb^-1 (r_b - A_bc dvc + G_b dp).
  for (long c = 0; c < cols; ++c) {
    for (int e = 0; e < ne; ++e) {
      const auto& b = bubbles[e];
      const auto& tri = mesh.triangles[e];
      Eigen::Matrix<double, 6, 1> dvc;
      Eigen::Vector3d dpe;
      for (int k = 0; k < 3; ++k) {
        for (int d = 0; d < 2; ++d) dvc(2 * k + d) = num.velocity_in(tri[k], d, x.col(c));
        dpe(k) = x(num.node_velocities + num.corner_p[e][k], c);
      }
      dv.col(c).segment<2>(num.bubble(e)) = z.col(c).segment<2>(2 * e) + b.inv_bb * (b.g_b * dpe - b.a_bc * dvc);
    }
  }
}

}  // namespace pfem
