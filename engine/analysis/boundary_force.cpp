#include "engine/analysis/boundary_force.h"

#include <algorithm>
#include <set>
#include <utility>

#include "engine/analysis/dual.h"

namespace pfem {

BoundaryLoad boundary_load(std::span<const std::array<std::int32_t, 2>> segments, const mesh::FluidMesh& mesh,
                           const NodeState& nodes, const fluid::FluidConstants& fluid, double thickness, double ax,
                           double ay, const fluid::FluidSeed* seed, int k) {
  std::set<std::pair<std::int32_t, std::int32_t>> on_boundary;
  for (const auto& [a, b] : segments) on_boundary.insert(std::minmax(a, b));
  for (const auto& [node, a, b] : mesh.riders)  // a rider splits its segment in two
    if (on_boundary.count(std::minmax(a, b)))
      on_boundary.insert(std::minmax(a, node)), on_boundary.insert(std::minmax(node, b));
  const Dual mu{fluid.mu, seed ? seed->mu : 0.0}, t{thickness, seed ? seed->thickness : 0.0};
  const Dual third{1.0 / 3.0, 0.0}, half{0.5, 0.0}, sixth{1.0 / 6.0, 0.0}, two{2.0, 0.0};
  const Dual X0{ax, 0.0}, Y0{ay, 0.0};
  Dual fx, fy, m;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& tri = mesh.triangles[f];
    std::array<int, 3> edge{};  // corner e starts an edge on the boundary
    int count = 0;
    for (int e = 0; e < 3; ++e)
      if ((edge[e] = on_boundary.count(std::minmax(tri[e], tri[(e + 1) % 3])))) ++count;
    if (count == 0) continue;
    std::array<Dual, 3> x, y, vx, vy, p;
    for (int a = 0; a < 3; ++a) {
      x[a] = node_dual(nodes, tri[a], NodeState::kDx, k), y[a] = node_dual(nodes, tri[a], NodeState::kDy, k);
      vx[a] = node_dual(nodes, tri[a], NodeState::kDvx, k), vy[a] = node_dual(nodes, tri[a], NodeState::kDvy, k);
      p[a] = corner_pressure_dual(nodes, mesh, f, a, k);  // the side of this triangle's water
    }
    // P1 velocity gradient: dN_a/dx = (y_{a+1} - y_{a+2}) / D, dN_a/dy = (x_{a+2} - x_{a+1}) / D.
    const Dual D = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    Dual uxx, uxy, uyx, uyy;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const Dual nx = (y[b] - y[c]) / D, ny = (x[c] - x[b]) / D;
      uxx = uxx + vx[a] * nx, uxy = uxy + vx[a] * ny, uyx = uyx + vy[a] * nx, uyy = uyy + vy[a] * ny;
    }
    const Dual trace = third * (uxx + uyy);
    const Dual sxx = two * mu * (uxx - trace), syy = two * mu * (uyy - trace), sxy = mu * (uxy + uyx);
    for (int e = 0; e < 3; ++e) {
      if (!edge[e]) continue;
      const int a = e, b = (e + 1) % 3;
      // The triangle is counter-clockwise: the water's outward normal times the edge's length.
      const Dual nx = y[b] - y[a], ny = x[a] - x[b];
      const Dual px = half * (p[a] + p[b]) * nx, py = half * (p[a] + p[b]) * ny;  // integral of p n
      const Dual sx = sxx * nx + sxy * ny, sy = sxy * nx + syy * ny;              // integral of s n
      fx = fx + t * (px - sx), fy = fy + t * (py - sy);
      // Moments: p is linear along the edge, s constant.
      const Dual wa = two * p[a] + p[b], wb = p[a] + two * p[b];
      const Dual rx = sixth * (wa * (x[a] - X0) + wb * (x[b] - X0)), ry = sixth * (wa * (y[a] - Y0) + wb * (y[b] - Y0));
      const Dual mx = half * (x[a] + x[b]) - X0, my = half * (y[a] + y[b]) - Y0;
      m = m + t * ((rx * ny - ry * nx) - (mx * sy - my * sx));
    }
  }
  return k < 0 ? BoundaryLoad{fx.v, fy.v, m.v} : BoundaryLoad{fx.d, fy.d, m.d};
}

}  // namespace pfem
