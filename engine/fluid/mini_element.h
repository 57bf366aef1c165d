#pragma once
// MINI triangle (P1 + cubic bubble velocity, P1 pressure) in closed form: theory §3,
// the paper's Appendix 1. Plain kernels: coordinates in, local matrices out.
//
// Local velocity dofs: (v1x v1y v2x v2y v3x v3y vbx vby), the bubble (node 4) last.
// Local pressure dofs: (p1 p2 p3). Every matrix includes the out-of-plane thickness t.
#include <Eigen/Core>
#include <array>

namespace pfem::fluid {

using Vec3 = Eigen::Matrix<double, 3, 1>;
using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;
using Mat83 = Eigen::Matrix<double, 8, 3>;

// A is TWICE the signed area (53); c_a = y_b - y_c, d_a = x_c - x_b cyclically (54).
// Am, cm, dm: the same at the geometry where the mass balance is taken (see
// continuity_at_midpoint); triangle_geometry sets them equal to A, c, d.
struct TriangleGeometry {
  double A = 0.0;
  std::array<double, 3> c{}, d{};
  double Am = 0.0;
  std::array<double, 3> cm{}, dm{};
};

TriangleGeometry triangle_geometry(const std::array<double, 3>& x, const std::array<double, 3>& y);

// The mass balance of a step from x_n to x = x_n + dt v taken at the midpoint geometry
// (x_n + x)/2: twice the area is quadratic in the corner coordinates, so its change over the
// step is exactly dt (c_m . vx + d_m . vy) with the midpoint's c, d, and a converged
// incompressible step keeps every element's area to round-off. Taken at x (backward Euler) it
// is off by dt^2 det(grad v) A per step: water lost or made wherever the flow turns or strains
// (3 % of the dam break's area in 0.5 s). The momentum balance stays at x.
void continuity_at_midpoint(TriangleGeometry& g, const std::array<double, 3>& xn, const std::array<double, 3>& yn);

// A step's geometry from corners at xn, yn moving at vx, vy: at x = x_n + dt v, with the mass
// balance's at the midpoint (continuity_at_midpoint).
TriangleGeometry step_geometry(const std::array<double, 3>& xn, const std::array<double, 3>& yn,
                               const std::array<double, 3>& vx, const std::array<double, 3>& vy, double dt);

struct FluidConstants {
  double rho = 0.0;
  double mu = 0.0;
  double kappa = 0.0;
};

// The element's matrices at one geometry (theory (56)-(63)).
struct MiniMatrices {
  Mat8 M;    // consistent mass, rho * integral Nv^T Nv
  Mat8 K;    // viscous, integral B^T D B with D = mu * deviatoric matrix
  Mat83 G;   // integral B^T m Np (momentum balance, at A, c, d)
  Mat83 Gc;  // the same at Am, cm, dm: G^T v in the mass balance
  Vec8 F;    // body force rho * integral Nv^T b
  Vec3 Mp;   // lumped pressure mass, Am/(6 kappa) per corner
};

// Mass, viscous, gradient, body-force and pressure-mass matrices of one MINI triangle.
void mini_matrices(const TriangleGeometry& g, const FluidConstants& f, double thickness,
                   double bx, double by, MiniMatrices& out);

}  // namespace pfem::fluid
