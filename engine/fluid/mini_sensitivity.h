#pragma once
// Derivatives of one MINI triangle's residual for the DDM (theory §5, the paper's Appendix 2).
//
// The element residual at velocities v (corners, then bubble), pressures p and their values
// vn, pn at t_n:
//   rv = F - M (v - vn)/dt - K v + G p        rp = -Mp (p - pn)/dt - Gc^T v
// (Gc, Mp at the midpoint geometry of the step, see continuity_at_midpoint)
// Its derivatives with respect to the corner coordinates (x1 y1 x2 y2 x3 y3), v and p held
// fixed, are the geometric matrices of (35)-(36) with the residual's sign: H = -drv/dx,
// T = -drp/dx. They follow from the closed forms by the chain rule through A, c_a, d_a:
// dA/dx_a = c_a, dA/dy_a = d_a, d_b = x_{b+2} - x_{b+1}, c_b = y_{b+1} - y_{b+2} (cyclic).
#include "engine/fluid/mini_element.h"

namespace pfem::fluid {

using Mat86 = Eigen::Matrix<double, 8, 6>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

// The element's unknowns at the iterate and at t_n.
struct ElementState {
  Vec8 v, vn;
  Vec3 p, pn;
};

struct ElementResidual {
  Vec8 rv;
  Vec3 rp;
};

ElementResidual element_residual(const MiniMatrices& m, double dt, const ElementState& s);

// The same residual straight from the geometry, without forming the matrices (every Newton
// iteration needs the residual, the matrices only when the Newton matrix is refactorised), with
// the magnitudes of rp's terms summed (|Mp (p - pn)|/dt + |G|^T |v|: their round-off scale), the
// pressure mass of each corner (Mp is the same for the three) and the squared norm of F.
struct DirectResidual {
  Vec8 rv;
  Vec3 rp, rp_abs;
  double mp = 0.0, f_squared = 0.0;
};
DirectResidual element_residual(const TriangleGeometry& g, const FluidConstants& f, double thickness, double bx,
                                double by, double dt, const ElementState& s);

// drv/dx and drp/dx at the geometry g whose matrices are m (mu and the thickness t enter K):
// rv's with respect to the corners at the step's end x, rp's with respect to the corners at
// the midpoint (x_n + x)/2 of its mass balance (TriangleGeometry::Am, cm, dm). Both are the
// derivatives with respect to x_n at fixed v; with respect to v they take dt and dt/2.
struct GeometricDerivatives {
  Mat86 drv_dx;
  Mat36 drp_dx;
};
void geometric_derivatives(const TriangleGeometry& g, const MiniMatrices& m, double mu, double thickness,
                           double dt, const ElementState& s, GeometricDerivatives& out);

// How much each fluid constant changes with one parameter (dconstant/dtheta): the parameter's
// "seed". A parameter may move several constants at once (thickness with a section width).
struct FluidSeed {
  double rho = 0.0, mu = 0.0, kappa = 0.0, thickness = 0.0;
  bool any() const { return rho != 0.0 || mu != 0.0 || kappa != 0.0 || thickness != 0.0; }
};

// The residual's terms that the fluid constants scale, at fixed geometry, velocities and
// pressures: M, F are proportional to rho, K to mu, Mp to 1/kappa and every term to the
// thickness. The same for every parameter, so computed once per element, each only where a
// parameter moves its constant (a non-zero entry of `moved`, e.g. the sum of the seeds' |.|).
struct ScaledTerms {
  Vec8 inertia_body;         // F - M (v - vn)/dt
  Vec3 compressibility;      // -Mp (p - pn)/dt
  Vec8 viscous;              // K v, or at mu = 0 (where K vanishes) K v of a unit viscosity
  ElementResidual residual;  // the whole residual
};
ScaledTerms scaled_terms(const TriangleGeometry& g, const MiniMatrices& m, const FluidConstants& f, double thickness,
                         double dt, const ElementState& s, const FluidSeed& moved);

// The residual's derivative with respect to the parameter at fixed geometry, velocities and
// pressures (the conditional derivative), from the element's scaled terms.
ElementResidual conditional_derivative(const ScaledTerms& terms, const FluidConstants& f, double thickness,
                                       const FluidSeed& seed);

}  // namespace pfem::fluid
