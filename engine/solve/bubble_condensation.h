#pragma once
// The bubble of a MINI triangle eliminated inside its element (engine/solve/fluid_step.h): each
// bubble row involves only its own triangle's unknowns, so an element's Newton matrix (or the
// exact Jacobian, for the DDM) condenses exactly to its corner velocities and pressures; a
// right-hand side's bubble rows are condensed in before the solve and the bubbles recovered
// after it.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <span>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/step_numbering.h"

namespace pfem {

// Per element, from a condensed factorisation: the bubble block inverse and
// its couplings to the corner velocities (bubble row a_bc, corner rows a_cb) and pressures.
struct BubbleCondensation {
  Eigen::Matrix2d inv_bb;
  Eigen::Matrix<double, 2, 6> a_bc;
  Eigen::Matrix<double, 6, 2> a_cb;
  Eigen::Matrix<double, 2, 3> g_b;   // bubble rows of G (momentum)
  Eigen::Matrix<double, 2, 3> gc_b;  // ... of the mass balance's Gc (G in the Newton matrix)
};

// An element's Jacobian -d(rv, rp)/d(v, p) in its velocity columns from its matrices m: the
// velocity rows a (corners, then bubble) and the pressure rows q of the corner columns (see
// condense_element).
void element_jacobian(const fluid::MiniMatrices& m, double dt, const fluid::GeometricDerivatives* geometric,
                      fluid::Mat8& a, Eigen::Matrix<double, 3, 6>& q);

// An element's bubble-condensed matrix in its corner unknowns (velocities x0 y0 x1 y1 x2 y2,
// then pressures 0 1 2; pressure rows negated) and its condensation; with the geometric
// derivatives (the DDM) the exact Jacobian, dt H and dt T included, otherwise symmetric.
using CondensedElement = Eigen::Matrix<double, 9, 9>;
void condense_element(const fluid::MiniMatrices& m, double dt, const fluid::GeometricDerivatives* geometric,
                      BubbleCondensation& b, CondensedElement& k);

// The entries of a triangle's condensed element k that a beam rider's velocity takes part in
// (StepRider), in the unknowns of its segment's ends: put(row, col, value) for each, both orders
// (the entries between the triangle's own unknowns are the callers'). A symmetric store adds
// those with row >= col: an unordered pair comes once, and a diagonal entry whole.
template <class Put>
void put_rider_entries(const StepNumbering& num, const std::array<std::int32_t, 3>& tri, int e,
                       const CondensedElement& k, Put&& put) {
  const std::array<VelocityTerms, 9> t = num.condensed_terms(tri, e);
  std::array<bool, 9> rider{};
  for (int c = 0; c < 6; ++c) rider[c] = num.is_rider(tri[c / 2]);
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) {
      if (rider[r] || rider[c]) put_term_pairs(t[r], t[c], k(r, c), put);
    }
}

// Solves the condensed system held by `solve` (in the condensed unknowns: node velocities, then
// pressures) for right-hand sides in the full unknowns (velocity rows rv, bubbles included, and
// pressure rows rp; one column each), returning the solutions dv (bubbles recovered) and dp.
using CondensedSolve = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;
void solve_condensed(const mesh::FluidMesh& mesh, const StepNumbering& num,
                     std::span<const BubbleCondensation> bubbles, const CondensedSolve& solve,
                     const Eigen::MatrixXd& rv, const Eigen::MatrixXd& rp, Eigen::MatrixXd& dv, Eigen::MatrixXd& dp);

}  // namespace pfem
