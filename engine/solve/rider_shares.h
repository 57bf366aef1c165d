#pragma once
// A beam rider's share of the DDM's right-hand side (StepRider; both formulations' DDMs). Its
// velocity rows go to its segment's ends by (1 - s) and s, so their shares move with s: -r ds to
// a's rows and +r ds to b's, r the rider's own rows at the converged state (the water's force on it).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/step_numbering.h"

namespace pfem {

// residuals: per triangle of mesh, its element residual (rv: the corners' x, y rows first).
// rv: a column per parameter, in the step's velocity unknowns.
template <class Residuals>
void add_rider_shares(const StepNumbering& num, const mesh::FluidMesh& mesh, const Residuals& residuals,
                      Eigen::MatrixXd& rv) {
  if (num.riders.empty()) return;
  std::vector<std::array<double, 2>> force(num.riders.size(), {0.0, 0.0});
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e)
    for (int a = 0; a < 3; ++a)
      if (const int i = mesh.triangles[e][a]; num.is_rider(i))
        for (int d = 0; d < 2; ++d) force[num.rider[i]][d] += residuals[e].rv(2 * a + d);
  for (std::size_t r = 0; r < num.riders.size(); ++r) {
    const StepRider& rider = num.riders[r];
    for (int d = 0; d < 2; ++d) {
      const std::vector<int>& of = d == 0 ? num.vx : num.vy;
      for (long k = 0; k < rv.cols(); ++k) {
        if (of[rider.a] >= 0) rv(of[rider.a], k) -= rider.ds[k] * force[r][d];
        if (of[rider.b] >= 0) rv(of[rider.b], k) += rider.ds[k] * force[r][d];
      }
    }
  }
}

}  // namespace pfem
