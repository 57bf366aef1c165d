// The faces remesh() keeps on their own: the alpha test (widened inside the previous water,
// narrowed across gaps between free surfaces), the fluid-particle rule and the gap-closing rule.
#include "engine/mesh/remesh_passes.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace pfem::mesh {
namespace {

// The factor on alpha for a triangle whose nodes were all inside the previous mesh (Kratos's PFEM
// widens alpha the same way for triangles without a free-surface node).
constexpr double kInteriorAlphaFactor = 1.25;

// Whether the corners i of a triangle move as water does (RemeshOptions::previous_triangles):
// the divergence of their linear velocity field against its rate of strain.
bool moves_as_water(const std::array<std::int32_t, 3>& i, std::span<const double> x, std::span<const double> y,
                    const RemeshOptions& options) {
  const double D = (x[i[1]] - x[i[0]]) * (y[i[2]] - y[i[0]]) - (x[i[2]] - x[i[0]]) * (y[i[1]] - y[i[0]]);
  if (!(D > 0.0)) return false;  // fails the alpha test anyway
  double uxx = 0.0, uxy = 0.0, uyx = 0.0, uyy = 0.0;
  for (int a = 0; a < 3; ++a) {
    const std::int32_t b = i[(a + 1) % 3], c = i[(a + 2) % 3];
    const double nx = (y[b] - y[c]) / D, ny = (x[c] - x[b]) / D;  // grad of corner a's shape function
    uxx += options.vx[i[a]] * nx, uxy += options.vx[i[a]] * ny;
    uyx += options.vy[i[a]] * nx, uyy += options.vy[i[a]] * ny;
  }
  const double div = uxx + uyy, shear = 0.5 * (uxy + uyx);
  const double strain = std::sqrt(uxx * uxx + uyy * uyy + 2.0 * shear * shear);
  // A relative area change below 1e-6 a step is still water whatever the ratio (round-off).
  return std::abs(div) <= 0.5 * strain || std::abs(div) * options.dt <= 1e-6 || div * options.dt <= -1.0;
}

}  // namespace

// The alpha test: circumradius R = a*b*c / (4*area) <= max_radius. Computed in double from
// edge vectors relative to one corner (less cancellation than absolute coordinates). A face
// whose double-precision signed area is not positive (collinear or nearly so) has an
// infinite radius and fails; this also guarantees every kept triangle is CCW in double.
bool passes_alpha_test(const Point& p0, const Point& p1, const Point& p2, double max_radius) {
  const double ux = p1.x() - p0.x(), uy = p1.y() - p0.y();
  const double vx = p2.x() - p0.x(), vy = p2.y() - p0.y();
  const double cross = ux * vy - uy * vx;  // = 2 * signed area
  if (!(cross > 0.0)) return false;
  const double wx = p2.x() - p1.x(), wy = p2.y() - p1.y();
  const double abc = std::sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy) * (wx * wx + wy * wy));
  return abc <= 2.0 * cross * max_radius;  // R = abc / (2 * cross)
}

// The alpha test, the fluid test and, across a gap between free surfaces, the gap rule per
// finite face: kept (info 1) or dropped (0).
void keep_alpha_faces(Delaunay& tri, std::span<const double> x, std::span<const double> y,
                      std::span<const NodeKind> kind, const RemeshOptions& options, const PreviousMesh& previous) {
  const double max_radius = options.alpha * options.h;
  const double boundary_radius =
      options.boundary_alpha > 0.0 ? std::min(options.boundary_alpha, options.alpha) * options.h : max_radius;
  // A triangle whose three nodes were inside the water at the previous step (in its mesh, none on
  // its boundary) gets a quarter more: air cannot reach there within a step, and at alpha the
  // test read particles drawn apart beside a wall (at a paddle's foot) as a void, whose zero
  // pressure then sucked at the wall (a 42 N jump in a paddle's 41 N force).
  const double interior_radius = kInteriorAlphaFactor * max_radius;
  const bool gap_test = !options.vx.empty();
  const auto boundary_particles = [&](const std::array<std::int32_t, 3>& t) {
    for (const std::int32_t i : t)
      if (kind[i] != NodeKind::Fluid || !previous.was_boundary(i)) return false;
    return true;
  };
  // The previous triangles that a gap test can ask about (corners sorted): a few, at the surface.
  std::set<std::array<std::int32_t, 3>> previous_at_surface;
  if (gap_test) {
    for (auto t : options.previous_triangles) {
      if (!boundary_particles(t)) continue;
      std::sort(t.begin(), t.end());
      previous_at_surface.insert(t);
    }
  }
  const auto spans_gap = [&](std::int32_t i0, std::int32_t i1, std::int32_t i2) {
    std::array<std::int32_t, 3> sorted{i0, i1, i2};
    if (!gap_test || !boundary_particles(sorted)) return false;
    std::sort(sorted.begin(), sorted.end());
    return previous_at_surface.count(sorted) == 0;
  };
  const auto radius = [&](std::int32_t i0, std::int32_t i1, std::int32_t i2) {
    if (previous.was_boundary(i0) && previous.was_boundary(i1) && previous.was_boundary(i2)) return boundary_radius;
    if (previous.was_inside(i0) && previous.was_inside(i1) && previous.was_inside(i2)) return interior_radius;
    return max_radius;
  };
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    const bool touches_fluid = kind[i0] == NodeKind::Fluid || kind[i1] == NodeKind::Fluid ||
                               kind[i2] == NodeKind::Fluid;
    const bool kept =
        touches_fluid && (!spans_gap(i0, i1, i2) || moves_as_water({i0, i1, i2}, x, y, options)) &&
        passes_alpha_test(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(), radius(i0, i1, i2));
    f->info() = kept ? 1 : 0;
  }
}

}  // namespace pfem::mesh
