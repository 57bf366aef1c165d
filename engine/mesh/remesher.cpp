#include "engine/mesh/remesher.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace pfem::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
// Face info: 1 when the face passed the alpha test and touches a fluid particle ("kept").
using FaceBase = CGAL::Triangulation_face_base_with_info_2<std::uint8_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using Point = Kernel::Point_2;

void validate(std::span<const double> x, std::span<const double> y,
              std::span<const NodeKind> kind, const RemeshOptions& options) {
  if (x.size() != y.size() || x.size() != kind.size()) {
    throw std::invalid_argument("remesh: x, y and kind must have the same size (got " +
                                std::to_string(x.size()) + ", " + std::to_string(y.size()) +
                                ", " + std::to_string(kind.size()) + ")");
  }
  if (x.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument("remesh: too many nodes for 32-bit node indices");
  }
  if (!(std::isfinite(options.h) && options.h > 0.0)) {
    throw std::invalid_argument("remesh: h must be finite and > 0 (got " +
                                std::to_string(options.h) + ")");
  }
  if (!(std::isfinite(options.alpha) && options.alpha > 0.0)) {
    throw std::invalid_argument("remesh: alpha must be finite and > 0 (got " +
                                std::to_string(options.alpha) + ")");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (kind[i] != NodeKind::Removed && (!std::isfinite(x[i]) || !std::isfinite(y[i]))) {
      throw std::invalid_argument("remesh: node " + std::to_string(i) +
                                  " has a non-finite coordinate");
    }
  }
}

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

// CGAL merges coincident points into one vertex, and its range insert leaves on that vertex
// the info of whichever duplicate came last in its spatial-sort order. Make the choice
// deterministic: the vertex carries the lowest input index among the coincident points, so
// every later duplicate ends up in no triangle. Runs only when duplicates were found.
void assign_lowest_duplicate_index(Delaunay& tri, std::span<const double> x,
                                   std::span<const double> y, std::span<const NodeKind> kind) {
  std::vector<std::int32_t> order;
  order.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    if (kind[i] != NodeKind::Removed) order.push_back(static_cast<std::int32_t>(i));
  const auto less = [&](std::int32_t a, std::int32_t b) {
    if (x[a] != x[b]) return x[a] < x[b];
    if (y[a] != y[b]) return y[a] < y[b];
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (auto v = tri.finite_vertices_begin(); v != tri.finite_vertices_end(); ++v) {
    const double px = v->point().x(), py = v->point().y();
    const auto first = std::partition_point(order.begin(), order.end(), [&](std::int32_t a) {
      return x[a] < px || (x[a] == px && y[a] < py);
    });
    v->info() = *first;  // exists: the vertex's point is one of the inputs
  }
}

}  // namespace

FluidMesh remesh(std::span<const double> x, std::span<const double> y,
                 std::span<const NodeKind> kind, const RemeshOptions& options) {
  validate(x, y, kind, options);
  const std::size_t n = x.size();

  FluidMesh mesh;
  mesh.in_mesh.assign(n, 0);
  mesh.free_surface.assign(n, 0);

  std::vector<std::pair<Point, std::int32_t>> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != NodeKind::Removed) points.emplace_back(Point(x[i], y[i]), static_cast<std::int32_t>(i));
  }
  Delaunay tri;
  tri.insert(points.begin(), points.end());  // spatially sorted bulk insert
  if (tri.number_of_vertices() < points.size()) assign_lowest_duplicate_index(tri, x, y, kind);

  // Pass 1: alpha test and fluid test per finite face; record kept triangles.
  const double max_radius = options.alpha * options.h;
  mesh.triangles.reserve(tri.number_of_faces());
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    const bool touches_fluid = kind[i0] == NodeKind::Fluid || kind[i1] == NodeKind::Fluid ||
                               kind[i2] == NodeKind::Fluid;
    const bool kept =
        touches_fluid && passes_alpha_test(f->vertex(0)->point(), f->vertex(1)->point(),
                                           f->vertex(2)->point(), max_radius);
    f->info() = kept ? 1 : 0;
  }

  // Pass 1b: drop "hanging" triangles: two wall/structure nodes and one fluid particle on the
  // boundary, lying above that particle (against gravity). They wet the wall above the
  // waterline, add mass that nothing supports and make the contact line creep up the wall;
  // the same triangle below the particle is a genuine part of the water and is kept.
  std::vector<std::uint8_t> on_boundary(n, 0);
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    for (int e = 0; e < 3; ++e) {
      const auto across = f->neighbor(e);
      if (!tri.is_infinite(across) && across->info()) continue;
      on_boundary[f->vertex(Delaunay::ccw(e))->info()] = 1;
      on_boundary[f->vertex(Delaunay::cw(e))->info()] = 1;
    }
  }
  std::vector<Delaunay::Face_handle> drop;
  const double gx = options.gravity_x, gy = options.gravity_y;
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info() || (gx == 0.0 && gy == 0.0)) continue;
    int fluid = 0, particle = -1;
    double cx = 0.0, cy = 0.0;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = f->vertex(k)->info();
      if (kind[i] == NodeKind::Fluid) ++fluid, particle = i;
      cx += x[i] / 3.0, cy += y[i] / 3.0;
    }
    if (fluid == 1 && on_boundary[particle] && (cx - x[particle]) * gx + (cy - y[particle]) * gy < 0.0)
      drop.push_back(f);
  }
  for (auto f : drop) f->info() = 0;
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    mesh.triangles.push_back({i0, i1, i2});  // CGAL faces are counter-clockwise
    mesh.in_mesh[i0] = mesh.in_mesh[i1] = mesh.in_mesh[i2] = 1;
  }

  // Pass 2: an edge of a kept face is on the boundary when the face across it is infinite
  // or not kept. A boundary edge with a fluid end is a free edge (an edge between two wall or
  // structure nodes is a wall): both its ends get p = 0, wall nodes at the contact line too.
  // A wall node on a free edge must not keep a pressure unknown: its only equation would be the
  // mass balance of one or two triangles above the waterline, a stiff compressible pocket.
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    for (int e = 0; e < 3; ++e) {
      const auto across = f->neighbor(e);
      if (!tri.is_infinite(across) && across->info()) continue;
      // Edge e is opposite vertex e: its ends are vertices ccw(e) and cw(e).
      const std::int32_t a = f->vertex(Delaunay::ccw(e))->info();
      const std::int32_t b = f->vertex(Delaunay::cw(e))->info();
      if (kind[a] == NodeKind::Fluid || kind[b] == NodeKind::Fluid)
        mesh.free_surface[a] = mesh.free_surface[b] = 1;
    }
  }
  return mesh;
}

}  // namespace pfem::mesh
