#include "engine/mesh/deformation_cfl.h"

#include <algorithm>

namespace pfem::mesh {

double smallest_area_ratio(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                           std::span<const double> vx, std::span<const double> vy, double dt) {
  double smallest = 1.0;
  for (const auto& t : mesh.triangles) {
    // Edges from corner 0 and their rates: twice the area at s is (e1 + s d1) x (e2 + s d2).
    const double e1x = x[t[1]] - x[t[0]], e1y = y[t[1]] - y[t[0]];
    const double e2x = x[t[2]] - x[t[0]], e2y = y[t[2]] - y[t[0]];
    const double d1x = vx[t[1]] - vx[t[0]], d1y = vy[t[1]] - vy[t[0]];
    const double d2x = vx[t[2]] - vx[t[0]], d2y = vy[t[2]] - vy[t[0]];
    const double area2 = e1x * e2y - e1y * e2x;
    if (!(area2 > 0.0)) continue;  // a flat triangle has no area to lose
    const double a = (e1x * d2y - e1y * d2x + d1x * e2y - d1y * e2x) / area2;  // div v
    const double b = (d1x * d2y - d1y * d2x) / area2;                          // det grad v
    // 1 + a s + b s^2 is smallest at an end of [0, dt] or at its vertex inside.
    double ratio = 1.0 + dt * (a + b * dt);
    const double vertex = b > 0.0 ? -a / (2.0 * b) : 0.0;
    if (vertex > 0.0 && vertex < dt) ratio = std::min(ratio, 1.0 - a * a / (4.0 * b));
    smallest = std::min(smallest, ratio);
  }
  return smallest;
}

bool collapses_within(const FluidMesh& mesh, std::span<const double> x, std::span<const double> y,
                      std::span<const double> vx, std::span<const double> vy, double dt) {
  return !(smallest_area_ratio(mesh, x, y, vx, vy, dt) > 0.0);
}

}  // namespace pfem::mesh
