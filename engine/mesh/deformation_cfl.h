#pragma once
// The deformation limit of a step (a CFL condition on the mesh): a step is halved before it is
// attempted while a triangle would collapse within it at the velocities of t_n.
//
// With its corners moving at constant velocities v, a triangle's area after a time s is
// A(s) = A (1 + s div v + s^2 det grad v) = A det(I + s grad v), exact for the linear motion.
// The step's first Newton iterate moves every node by dt v_n, so a triangle whose area ratio
// reaches 0 within dt (a particle running into the edge of its neighbours, a jet meeting the
// pool: the remesher keeps such a triangle when its gap closes within the step) starts Newton
// inverted, where the element's terms are singular (K ~ 1/A): the step then fails to converge
// or converges with the triangle inverted, which is no solution either, and is halved after
// its iterations. On the elastic-obstacle dam break to 1 s, 353 of the 376 failed attempts
// started so (the triangle that inverted was the collapsing one), against 116 of the 1376 that
// converged. The limit is no tuned number: a substep in which a triangle would lose its whole
// area is too long for the flow it is asked to resolve.
#include <span>

#include "engine/mesh/remesher.h"

namespace pfem::mesh {

// The smallest area ratio det(I + s grad v) of a triangle of mesh over 0 <= s <= dt, with the
// nodes at (x, y) moving at (vx, vy): 1 for no triangle, <= 0 where one collapses within dt.
double smallest_area_ratio(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                           std::span<const double> vx, std::span<const double> vy, double dt);

// Whether a triangle collapses within dt (its smallest area ratio not above 0).
bool collapses_within(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                      std::span<const double> vx, std::span<const double> vy, double dt);

}  // namespace pfem::mesh
