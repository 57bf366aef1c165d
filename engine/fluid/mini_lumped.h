#pragma once
// The MINI triangle of the incompressible fractional step (theory §8). A fractional step needs
// a diagonal mass, so that its pressure Poisson matrix G^T M^-1 G stays sparse (Zhu & Scott,
// "Improved fractional step method for simulating fluid-structure interaction using the PFEM",
// IJNME 99, 2014; OpenSees's incompressible PFEMElement2D lumps its mass the same way): each
// corner takes the row sum of the corner block of M (rho t A / 6, the linear triangle's lumped
// mass), the bubble keeps its own M_44, and the corner-bubble coupling M_a4 is dropped. There is
// no bulk modulus: the mass balance is rp = -Gc^T v, div v = 0 at the step's midpoint geometry
// (continuity_at_midpoint), so a converged step keeps every element's area as the
// quasi-incompressible step does. Decoupled from the corners in M, the bubble carries nothing
// from step to step (its v_n is 0): it is the element's pressure stabilisation, its Schur
// complement G_b^T (M_44/dt + K_44)^-1 G_b in the Poisson matrix (as OpenSees condenses it).
//
// The matrices come from mini_matrices with kappa = infinity (Mp = 0); the derivatives from
// mini_sensitivity's, corrected for the lumping: M and M_L are both proportional to A.
#include "engine/fluid/mini_sensitivity.h"

namespace pfem::fluid {

// The lumped mass per velocity dof (x y of each corner, then the bubble's).
Vec8 lumped_mass(const MiniMatrices& m);

// rv = F - M_L (v - vn)/dt - K v + G p and rp = -Gc^T v, for matrices m without bulk modulus.
ElementResidual lumped_residual(const MiniMatrices& m, const Vec8& ml, double dt, const ElementState& s);

// drv/dx (end geometry) and drp/dx (midpoint geometry) of lumped_residual, as
// geometric_derivatives gives them for the consistent mass.
void lumped_geometric_derivatives(const TriangleGeometry& g, const MiniMatrices& m, const Vec8& ml, double mu,
                                  double thickness, double dt, const ElementState& s, GeometricDerivatives& out);

// The conditional derivative of lumped_residual for one parameter's seed (M_L too is
// proportional to rho and to the thickness).
ElementResidual lumped_conditional_derivative(const TriangleGeometry& g, const MiniMatrices& m, const Vec8& ml,
                                              const FluidConstants& f, double thickness, double dt,
                                              const ElementState& s, const FluidSeed& seed);

}  // namespace pfem::fluid
