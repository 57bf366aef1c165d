// The constrained Delaunay triangulation of the nodes (remesh()'s first pass): bulk insertion,
// coincident nodes merged onto the lowest index, then the wall and beam segments as constraints.
#include "engine/mesh/remesh_passes.h"

#include <CGAL/Delaunay_triangulation_2.h>

#include <algorithm>
#include <type_traits>
#include <utility>

namespace pfem::mesh {
namespace {

// The points are inserted into a plain Delaunay triangulation over the same data structure
// (its hole-based insertion is about 1.5x faster than the constrained one's edge flips),
// which is then moved into the constrained triangulation: both derive from the same
// Triangulation_2<Kernel, Tds>, which holds all their state (traits, data structure, infinite
// vertex), and a Delaunay triangulation without constraints is a valid constrained one.
using PlainDelaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using TriangulationBase = CGAL::Triangulation_2<Kernel, Tds>;
// (The constrained triangulation adds only a virtual-table pointer.)
static_assert(std::is_base_of_v<TriangulationBase, Delaunay> &&
                  std::is_base_of_v<TriangulationBase, PlainDelaunay> &&
                  sizeof(PlainDelaunay) == sizeof(TriangulationBase) &&
                  sizeof(Delaunay) <= sizeof(TriangulationBase) + sizeof(void*),
              "Triangulation_2::swap() must move all the state (did CGAL change?)");

// CGAL merges coincident points into one vertex, and its range insert leaves on that vertex
// the info of whichever duplicate came last in its spatial-sort order. Make the choice
// deterministic: the vertex carries the lowest input index among the coincident points, so
// every later duplicate ends up in no triangle. Runs only when duplicates were found. When
// vertex_of is not empty, it also maps every coincident node to the shared vertex.
void assign_lowest_duplicate_index(Delaunay& tri, std::span<const double> x,
                                   std::span<const double> y, std::span<const NodeKind> kind,
                                   std::vector<VertexHandle>& vertex_of) {
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
    if (vertex_of.empty()) continue;
    for (auto it = first; it != order.end() && x[*it] == px && y[*it] == py; ++it)
      vertex_of[*it] = v;
  }
}

// Forces the constraint segments into the triangulation by vertex handles (no point
// location). vertex_of[i]: the vertex of node i, null for Removed nodes.
void insert_constraints(Delaunay& tri, std::span<const std::array<std::int32_t, 2>> constraints,
                        const std::vector<VertexHandle>& vertex_of) {
  for (const auto& [a, b] : constraints) {
    const VertexHandle va = vertex_of[a], vb = vertex_of[b];
    if (va == VertexHandle() || vb == VertexHandle() || va == vb) continue;
    try {
      tri.insert_constraint(va, vb);
    } catch (const Delaunay::Intersection_of_constraints_exception&) {
      // Crosses an earlier constraint: the caller's geometry is inconsistent. The parts
      // already inserted (up to a node lying on the segment) stay; the triangulation is valid.
    }
  }
}

}  // namespace

bool triangulate_nodes(std::span<const double> x, std::span<const double> y, std::span<const NodeKind> kind,
                       std::span<const std::array<std::int32_t, 2>> constraints, Delaunay& tri) {
  const std::size_t n = x.size();
  std::vector<std::pair<Point, std::int32_t>> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (kind[i] != NodeKind::Removed) points.emplace_back(Point(x[i], y[i]), static_cast<std::int32_t>(i));
  }
  {
    PlainDelaunay plain;
    plain.insert(points.begin(), points.end());  // spatially sorted bulk insert
    static_cast<TriangulationBase&>(tri).swap(plain);
  }
  // Constraints matter only when there are faces (dimension 2); they are inserted by vertex
  // handle, so the node -> vertex map is built first (null for Removed nodes).
  const bool constrained = !constraints.empty() && tri.dimension() == 2;
  std::vector<VertexHandle> vertex_of(constrained ? n : 0);
  if (tri.number_of_vertices() < points.size()) {
    assign_lowest_duplicate_index(tri, x, y, kind, vertex_of);
  } else if (constrained) {
    for (auto v = tri.finite_vertices_begin(); v != tri.finite_vertices_end(); ++v)
      vertex_of[v->info()] = v;
  }
  if (constrained) insert_constraints(tri, constraints, vertex_of);
  return constrained;
}

}  // namespace pfem::mesh
