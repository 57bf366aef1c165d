#include "engine/mesh/remesher.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace pfem::mesh {
namespace {

// The factor on alpha for a triangle whose nodes were all inside the previous mesh (Kratos's PFEM
// widens alpha the same way for triangles without a free-surface node).
constexpr double kInteriorAlphaFactor = 1.25;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Vertex info: the node index.
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
// Face info: 1 when the face passed the alpha test and touches a fluid particle ("kept");
// the constrained face base adds the per-edge constraint flags.
using FaceBase = CGAL::Constrained_triangulation_face_base_2<
    Kernel, CGAL::Triangulation_face_base_with_info_2<std::uint8_t, Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Intersection tag: constraints may meet at nodes (walls sharing a corner node, a beam
// clamped at a wall node) and may pass through nodes lying on them, but must not cross in
// their interiors. This tag handles exactly that with exact predicates and never constructs a
// point, so every vertex stays an input node with a valid index. (Exact_predicates_tag would
// accept crossings by inventing a vertex at a rounded intersection point: a vertex with no
// node index, useless to the solver. Exact_intersections_tag needs an exact kernel: slower.)
// A crossing raises Intersection_of_constraints_exception before the triangulation is
// modified for that sub-segment; remesh() catches it and leaves the rest of the segment out.
using Itag = CGAL::No_constraint_intersection_requiring_constructions_tag;
using Delaunay = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, Itag>;
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
using Point = Kernel::Point_2;
using VertexHandle = Delaunay::Vertex_handle;

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
  if (!(std::isfinite(options.boundary_alpha) && options.boundary_alpha >= 0.0)) {
    throw std::invalid_argument("remesh: boundary_alpha must be finite and >= 0 (got " +
                                std::to_string(options.boundary_alpha) + ")");
  }
  if (!options.vx.empty() || !options.vy.empty()) {
    if (options.vx.size() != x.size() || options.vy.size() != x.size())
      throw std::invalid_argument("remesh: vx and vy must have one entry per node (got " +
                                  std::to_string(options.vx.size()) + " and " + std::to_string(options.vy.size()) +
                                  " for " + std::to_string(x.size()) + " nodes)");
    if (!(std::isfinite(options.dt) && options.dt > 0.0))
      throw std::invalid_argument("remesh: dt must be finite and > 0 with velocities (got " +
                                  std::to_string(options.dt) + ")");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (kind[i] != NodeKind::Removed && (!std::isfinite(x[i]) || !std::isfinite(y[i]))) {
      throw std::invalid_argument("remesh: node " + std::to_string(i) +
                                  " has a non-finite coordinate");
    }
  }
  const auto n = static_cast<std::int64_t>(x.size());
  for (std::size_t c = 0; c < options.constraints.size(); ++c) {
    const auto [a, b] = options.constraints[c];
    if (a < 0 || a >= n || b < 0 || b >= n || a == b) {
      throw std::invalid_argument("remesh: constraint " + std::to_string(c) + " (" +
                                  std::to_string(a) + ", " + std::to_string(b) +
                                  ") needs two different node indices in [0, " +
                                  std::to_string(n) + ")");
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

// Edge e of the kept face f (the edge opposite vertex e) is on the boundary of the kept region
// when the face across it is infinite or not kept. It is a free edge when it is on the
// boundary, is not a constraint (a wall or beam, whatever lies beyond it) and has a fluid end
// (an edge between two wall or structure nodes is a wall).
bool is_free_edge(const Delaunay& tri, Delaunay::Face_handle f, int e,
                  std::span<const NodeKind> kind) {
  const auto across = f->neighbor(e);
  if (!tri.is_infinite(across) && across->info()) return false;
  if (f->is_constrained(e)) return false;
  return kind[f->vertex(Delaunay::ccw(e))->info()] == NodeKind::Fluid ||
         kind[f->vertex(Delaunay::cw(e))->info()] == NodeKind::Fluid;
}

// The sides of the wall and beam lines at their nodes (FluidMesh::sides, corner_side), from the
// constrained edges of the triangulation itself: a node lying on a segment (which splits it) or
// a merged duplicate gets the edges it really has.
class LineSides {
 public:
  explicit LineSides(std::size_t n) : count(n, 1), neighbours_(n), done_(n, 0) {}
  std::vector<std::uint8_t> count;

  // The sides of face f's corners.
  std::array<std::uint8_t, 3> of(Delaunay::Face_handle f, std::span<const NodeKind> kind) {
    std::array<std::uint8_t, 3> side{};
    for (int c = 0; c < 3; ++c) {
      const VertexHandle v = f->vertex(c);
      const std::int32_t i = v->info();
      if (kind[i] != NodeKind::Wall && kind[i] != NodeKind::Structure) continue;
      const std::vector<std::int32_t>& around = neighbours(v);
      if (around.size() < 2) continue;
      // Clockwise around v from f to the first constrained edge: its far end begins the sector.
      Delaunay::Face_handle g = f;
      for (std::size_t step = 0; step <= 4 * around.size() + 64; ++step) {
        const int at = g->index(v), edge = Delaunay::cw(at);  // edge (v, ccw(at)'s vertex)
        if (g->is_constrained(edge)) {
          const std::int32_t start = g->vertex(Delaunay::ccw(at))->info();
          const auto rank = std::lower_bound(around.begin(), around.end(), start) - around.begin();
          side[c] = static_cast<std::uint8_t>(std::min<long>(rank, kMaxPressureSides - 1));
          break;
        }
        g = g->neighbor(edge);
      }
    }
    return side;
  }

 private:
  // v's constrained neighbours, sorted by node index (once per node).
  const std::vector<std::int32_t>& neighbours(VertexHandle v) {
    const std::int32_t i = v->info();
    if (done_[i]) return neighbours_[i];
    done_[i] = 1;
    auto& around = neighbours_[i];
    auto e = v->incident_edges(), end = e;
    do {
      if (e->first->is_constrained(e->second)) {
        const VertexHandle a = e->first->vertex(Delaunay::ccw(e->second)), b = e->first->vertex(Delaunay::cw(e->second));
        around.push_back((a == v ? b : a)->info());
      }
    } while (++e != end);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    count[i] = static_cast<std::uint8_t>(std::clamp<std::size_t>(around.size(), 1, kMaxPressureSides));
    return around;
  }
  std::vector<std::vector<std::int32_t>> neighbours_;
  std::vector<std::uint8_t> done_;
};

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
  {
    PlainDelaunay plain;
    plain.insert(points.begin(), points.end());  // spatially sorted bulk insert
    static_cast<TriangulationBase&>(tri).swap(plain);
  }
  // Constraints matter only when there are faces (dimension 2); they are inserted by vertex
  // handle, so the node -> vertex map is built first (null for Removed nodes).
  const bool constrained = !options.constraints.empty() && tri.dimension() == 2;
  std::vector<VertexHandle> vertex_of(constrained ? n : 0);
  if (tri.number_of_vertices() < points.size()) {
    assign_lowest_duplicate_index(tri, x, y, kind, vertex_of);
  } else if (constrained) {
    for (auto v = tri.finite_vertices_begin(); v != tri.finite_vertices_end(); ++v)
      vertex_of[v->info()] = v;
  }
  if (constrained) insert_constraints(tri, options.constraints, vertex_of);
  LineSides sides(n);

  // Pass 1: alpha test and fluid test per finite face; record kept triangles.
  const double max_radius = options.alpha * options.h;
  const double boundary_radius =
      options.boundary_alpha > 0.0 ? std::min(options.boundary_alpha, options.alpha) * options.h : max_radius;
  const auto was_boundary = [&](std::int32_t i) {
    return static_cast<std::size_t>(i) < options.previous_boundary.size() && options.previous_boundary[i] != 0;
  };
  // A triangle whose three nodes were inside the water at the previous step (in its mesh, none on
  // its boundary) gets a quarter more: air cannot reach there within a step, and at alpha the
  // test read particles drawn apart beside a wall (at a paddle's foot) as a void, whose zero
  // pressure then sucked at the wall (a 42 N jump in a paddle's 41 N force).
  const double interior_radius = kInteriorAlphaFactor * max_radius;
  std::vector<std::uint8_t> was_in(n, 0);
  for (const auto& t : options.previous_triangles)
    for (const std::int32_t i : t)
      if (static_cast<std::size_t>(i) < n) was_in[i] = 1;
  const auto was_inside = [&](std::int32_t i) { return was_in[i] && !was_boundary(i); };
  mesh.triangles.reserve(tri.number_of_faces());
  const bool gap_test = !options.vx.empty();
  const auto boundary_particles = [&](const std::array<std::int32_t, 3>& t) {
    for (const std::int32_t i : t)
      if (kind[i] != NodeKind::Fluid || !was_boundary(i)) return false;
    return true;
  };
  // The previous triangles that a gap test can ask about (corners sorted): a few, at the surface.
  std::set<std::array<std::int32_t, 3>> previous;
  if (gap_test) {
    for (auto t : options.previous_triangles) {
      if (!boundary_particles(t)) continue;
      std::sort(t.begin(), t.end());
      previous.insert(t);
    }
  }
  const auto spans_gap = [&](std::int32_t i0, std::int32_t i1, std::int32_t i2) {
    std::array<std::int32_t, 3> sorted{i0, i1, i2};
    if (!gap_test || !boundary_particles(sorted)) return false;
    std::sort(sorted.begin(), sorted.end());
    return previous.count(sorted) == 0;
  };
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    const bool touches_fluid = kind[i0] == NodeKind::Fluid || kind[i1] == NodeKind::Fluid ||
                               kind[i2] == NodeKind::Fluid;
    const bool kept =
        touches_fluid && (!spans_gap(i0, i1, i2) || moves_as_water({i0, i1, i2}, x, y, options)) &&
        passes_alpha_test(f->vertex(0)->point(), f->vertex(1)->point(),
                                           f->vertex(2)->point(),
                                           was_boundary(i0) && was_boundary(i1) && was_boundary(i2) ? boundary_radius
                                           : was_inside(i0) && was_inside(i1) && was_inside(i2)      ? interior_radius
                                                                                                     : max_radius);
    f->info() = kept ? 1 : 0;
  }

  // Pass 1a: triangles of wall and structure nodes only are water too where they close a
  // pocket of the water: a connected group of them (across edges that are not walls or beams)
  // bounded only by walls, beams and kept triangles, at least one of each (the corner between a
  // floor and a beam standing on it, under water; the sliver between a wall's nodes and the
  // water where the wall line zigzags). Left out, their edges to the water would act
  // as a free surface: the water's pressure would push the beam's first nodes into the corner (a
  // spurious axial force and moment at a submerged beam's base).
  constexpr int kKept = 1, kVisited = 2, kPocket = 3;
  const auto no_particle = [&](Delaunay::Face_handle f) {
    for (int k = 0; k < 3; ++k)
      if (kind[f->vertex(k)->info()] == NodeKind::Fluid) return false;
    return true;
  };
  // Collects into group the connected dropped faces from f that enter() accepts, across edges
  // that are not walls or beams, marking them visited; face(g) sees each, edge(g, k) each edge
  // of theirs that the walk does not cross (a constraint, the infinite face, a kept face, a face
  // enter() refused, or one of the group's own).
  std::vector<Delaunay::Face_handle> group, stack;
  const auto flood = [&](Delaunay::Face_handle f, const auto& enter, const auto& face, const auto& edge) {
    group.clear();
    stack.assign(1, f);
    f->info() = kVisited;
    while (!stack.empty()) {
      const auto g = stack.back();
      stack.pop_back();
      group.push_back(g);
      face(g);
      for (int k = 0; k < 3; ++k) {
        const auto across = g->neighbor(k);
        if (!g->is_constrained(k) && !tri.is_infinite(across) && across->info() == 0 && enter(across)) {
          across->info() = kVisited;
          stack.push_back(across);
        } else {
          edge(g, k);
        }
      }
    }
  };
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (f->info() != 0 || !no_particle(f)) continue;
    bool closed = true, wet = false, walled = false;
    flood(
        f, no_particle,
        [&](Delaunay::Face_handle g) {
          closed = closed && passes_alpha_test(g->vertex(0)->point(), g->vertex(1)->point(),
                                               g->vertex(2)->point(), max_radius);
        },
        [&](Delaunay::Face_handle g, int k) {
          const auto across = g->neighbor(k);
          if (g->is_constrained(k)) walled = true;
          else if (tri.is_infinite(across)) closed = false;
          else if (across->info() == kKept) wet = true;
          else if (across->info() == 0) closed = false;  // a dropped triangle with a particle: open to the air
        });
    for (auto g : group) g->info() = closed && wet && walled ? kPocket : kVisited;
  }
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f)
    f->info() = f->info() == kKept || f->info() == kPocket ? 1 : 0;

  // Pass 1c: a void against a beam inside water that was wet all round at the previous step is
  // water too: a connected group of dropped triangles (across edges that are not walls or beams)
  // with a particle and a structure node, enclosed by kept triangles, walls and beams, whose
  // nodes were all in the previous mesh and none on its boundary. Air cannot get there within a
  // step: it is the alpha test's reading of the particles drawn apart in the wake of the beam's
  // edge, or of one taken out beside it. Left out, it is a free surface for a step along the
  // beam's wet side, where the water's pressure then drops to zero: the force on a submerged
  // plate in a wave flume jumped by up to 13 N in a step on its 2-4 N wave force. An air pocket
  // that the water closes over keeps its surface particles' flags and stays air. (Voids in open
  // water or at a fixed wall get only the wider interior alpha of pass 1: where water drains in a
  // film thinner than h, they are the film's real breaking up, and filling them whole made water.)
  if (!options.previous_boundary.empty() && !options.previous_triangles.empty()) {
    const auto any = [](Delaunay::Face_handle) { return true; };
    for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
      if (f->info() != 0) continue;
      bool enclosed = true, particle = false, beam = false;
      flood(
          f, any,
          [&](Delaunay::Face_handle g) {
            for (int k = 0; k < 3; ++k) {
              const std::int32_t i = g->vertex(k)->info();
              enclosed = enclosed && was_inside(i);
              particle = particle || kind[i] == NodeKind::Fluid;
              beam = beam || kind[i] == NodeKind::Structure;
            }
            // A face flat in double precision (collinear nodes) cannot be an element.
            enclosed = enclosed && passes_alpha_test(g->vertex(0)->point(), g->vertex(1)->point(),
                                                     g->vertex(2)->point(), std::numeric_limits<double>::infinity());
          },
          [&](Delaunay::Face_handle g, int k) {
            if (!g->is_constrained(k) && tri.is_infinite(g->neighbor(k))) enclosed = false;
          });
      for (auto g : group) g->info() = enclosed && particle && beam ? kPocket : kVisited;
    }
    for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f)
      f->info() = f->info() == kKept || f->info() == kPocket ? 1 : 0;
  }

  // Pass 1b: drop "hanging" triangles above the waterline at a wall: a wall/structure node that
  // is higher (against gravity) than every particle of its triangle by more than a tenth of h,
  // in a triangle open to the air along an edge at that node: one particle on the free surface
  // with two wall nodes wholly at or above it, or two particles with one wall node above both.
  // They wet the wall above the water, add mass that nothing supports and make the contact line
  // creep up the wall (still water then flows at the walls). A triangle whose wall edge reaches
  // below its particle is kept: it is the water at the contact line, or a jet climbing the wall
  // that must stay attached to it. Dropping one can open the next (the particle under it is
  // now on the surface): repeated until none is left.
  const double g_norm = std::hypot(options.gravity_x, options.gravity_y);
  const auto height_over = [&](std::int32_t i, std::int32_t j) {  // of node i above node j
    return -((x[i] - x[j]) * options.gravity_x + (y[i] - y[j]) * options.gravity_y) / g_norm;
  };
  std::vector<Delaunay::Face_handle> drop;
  for (int round = 0; g_norm > 0.0 && (round == 0 || !drop.empty()); ++round) {
    drop.clear();
    for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
      if (!f->info()) continue;
      int fluid = 0;
      for (int k = 0; k < 3; ++k) fluid += kind[f->vertex(k)->info()] == NodeKind::Fluid;
      if (fluid == 0 || fluid == 3) continue;
      bool hanging = true, open = false;
      for (int w = 0; w < 3 && hanging; ++w) {
        const std::int32_t wall = f->vertex(w)->info();
        if (kind[wall] == NodeKind::Fluid) continue;
        for (int k = 0; k < 3; ++k) {
          const std::int32_t i = f->vertex(k)->info();
          if (kind[i] != NodeKind::Fluid) continue;
          // One particle: both wall nodes at or above it; two: the wall node above both.
          if (fluid == 1 ? height_over(wall, i) < -0.1 * options.h : height_over(wall, i) <= 0.1 * options.h)
            hanging = false;
        }
        // The edges at the wall node are those opposite the other two vertices.
        open = open || is_free_edge(tri, f, Delaunay::ccw(w), kind) || is_free_edge(tri, f, Delaunay::cw(w), kind);
      }
      if (hanging && open) drop.push_back(f);
    }
    for (auto f : drop) f->info() = 0;
  }
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    const std::int32_t i0 = f->vertex(0)->info();
    const std::int32_t i1 = f->vertex(1)->info();
    const std::int32_t i2 = f->vertex(2)->info();
    mesh.triangles.push_back({i0, i1, i2});  // CGAL faces are counter-clockwise
    mesh.in_mesh[i0] = mesh.in_mesh[i1] = mesh.in_mesh[i2] = 1;
    if (constrained) mesh.corner_side.push_back(sides.of(f, kind));
  }
  if (constrained) mesh.sides = std::move(sides.count);

  // Pass 2: both ends of a free edge (see is_free_edge) are on the free surface, wall nodes at
  // the contact line too. A constraint edge is never free: the triangle on its other side was
  // evaluated on its own (no triangle crosses a constraint).
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (!f->info()) continue;
    for (int e = 0; e < 3; ++e) {
      if (!is_free_edge(tri, f, e, kind)) continue;
      // Edge e is opposite vertex e: its ends are vertices ccw(e) and cw(e).
      const std::int32_t a = f->vertex(Delaunay::ccw(e))->info(), b = f->vertex(Delaunay::cw(e))->info();
      mesh.free_surface[a] = mesh.free_surface[b] = 1;
      if (kind[a] == NodeKind::Fluid && kind[b] == NodeKind::Wall) mesh.contact_edges.push_back({a, b});
      if (kind[b] == NodeKind::Fluid && kind[a] == NodeKind::Wall) mesh.contact_edges.push_back({b, a});
    }
  }
  return mesh;
}

}  // namespace pfem::mesh
