// Dropped faces that remesh() keeps all the same: groups of them closed in by walls, beams and
// kept faces (a pocket of wall and structure nodes under water; a void against a beam inside the
// previous step's water).
#include "engine/mesh/remesh_passes.h"

#include <limits>

namespace pfem::mesh {
namespace {

// Face marks while the groups are walked.
constexpr int kKept = 1, kVisited = 2, kPocket = 3;

// Collects into group() the connected dropped faces from f that enter() accepts, across edges
// that are not walls or beams, marking them visited; face(g) sees each, edge(g, k) each edge
// of theirs that the walk does not cross (a constraint, the infinite face, a kept face, a face
// enter() refused, or one of the group's own).
class FaceFlood {
 public:
  explicit FaceFlood(const Delaunay& tri) : tri_(tri) {}

  template <class Enter, class Face, class Edge>
  const std::vector<FaceHandle>& operator()(FaceHandle f, const Enter& enter, const Face& face, const Edge& edge) {
    group_.clear();
    stack_.assign(1, f);
    f->info() = kVisited;
    while (!stack_.empty()) {
      const auto g = stack_.back();
      stack_.pop_back();
      group_.push_back(g);
      face(g);
      for (int k = 0; k < 3; ++k) {
        const auto across = g->neighbor(k);
        if (!g->is_constrained(k) && !tri_.is_infinite(across) && across->info() == 0 && enter(across)) {
          across->info() = kVisited;
          stack_.push_back(across);
        } else {
          edge(g, k);
        }
      }
    }
    return group_;
  }

 private:
  const Delaunay& tri_;
  std::vector<FaceHandle> group_, stack_;
};

// The pockets found become kept faces, the other visited faces dropped ones again.
void keep_pockets(Delaunay& tri) {
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f)
    f->info() = f->info() == kKept || f->info() == kPocket ? 1 : 0;
}

}  // namespace

// Triangles of wall and structure nodes only are water too where they close a pocket of the
// water: a connected group of them (across edges that are not walls or beams) bounded only by
// walls, beams and kept triangles, at least one of each (the corner between a floor and a beam
// standing on it, under water; the sliver between a wall's nodes and the water where the wall
// line zigzags). Left out, their edges to the water would act as a free surface: the water's
// pressure would push the beam's first nodes into the corner (a spurious axial force and moment
// at a submerged beam's base).
void keep_wall_pockets(Delaunay& tri, std::span<const NodeKind> kind, const RemeshOptions& options) {
  const double max_radius = options.alpha * options.h;
  const auto no_particle = [&](FaceHandle f) {
    for (int k = 0; k < 3; ++k)
      if (kind[f->vertex(k)->info()] == NodeKind::Fluid) return false;
    return true;
  };
  FaceFlood flood(tri);
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (f->info() != 0 || !no_particle(f)) continue;
    bool closed = true, wet = false, walled = false;
    const auto& group = flood(
        f, no_particle,
        [&](FaceHandle g) {
          closed = closed && passes_alpha_test(g->vertex(0)->point(), g->vertex(1)->point(),
                                               g->vertex(2)->point(), max_radius);
        },
        [&](FaceHandle g, int k) {
          const auto across = g->neighbor(k);
          if (g->is_constrained(k)) walled = true;
          else if (tri.is_infinite(across)) closed = false;
          else if (across->info() == kKept) wet = true;
          else if (across->info() == 0) closed = false;  // a dropped triangle with a particle: open to the air
        });
    for (auto g : group) g->info() = closed && wet && walled ? kPocket : kVisited;
  }
  keep_pockets(tri);
}

// A void against a beam inside water that was wet all round at the previous step is water too:
// a connected group of dropped triangles (across edges that are not walls or beams) with a
// particle and a structure node, enclosed by kept triangles, walls and beams, whose nodes were
// all in the previous mesh and none on its boundary. Air cannot get there within a step: it is
// the alpha test's reading of the particles drawn apart in the wake of the beam's edge, or of
// one taken out beside it. Left out, it is a free surface for a step along the beam's wet side,
// where the water's pressure then drops to zero: the force on a submerged plate in a wave flume
// jumped by up to 13 N in a step on its 2-4 N wave force. An air pocket that the water closes
// over keeps its surface particles' flags and stays air. (Voids in open water or at a fixed wall
// get only the wider interior alpha of keep_alpha_faces(): where water drains in a film thinner
// than h, they are the film's real breaking up, and filling them whole made water.)
void keep_voids_at_beams(Delaunay& tri, std::span<const NodeKind> kind, const RemeshOptions& options,
                         const PreviousMesh& previous) {
  if (options.previous_boundary.empty() || options.previous_triangles.empty()) return;
  const auto any = [](FaceHandle) { return true; };
  FaceFlood flood(tri);
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f) {
    if (f->info() != 0) continue;
    bool enclosed = true, particle = false, beam = false;
    const auto& group = flood(
        f, any,
        [&](FaceHandle g) {
          for (int k = 0; k < 3; ++k) {
            const std::int32_t i = g->vertex(k)->info();
            enclosed = enclosed && previous.was_inside(i);
            particle = particle || kind[i] == NodeKind::Fluid;
            beam = beam || kind[i] == NodeKind::Structure;
          }
          // A face flat in double precision (collinear nodes) cannot be an element.
          enclosed = enclosed && passes_alpha_test(g->vertex(0)->point(), g->vertex(1)->point(),
                                                   g->vertex(2)->point(), std::numeric_limits<double>::infinity());
        },
        [&](FaceHandle g, int k) {
          if (!g->is_constrained(k) && tri.is_infinite(g->neighbor(k))) enclosed = false;
        });
    for (auto g : group) g->info() = enclosed && particle && beam ? kPocket : kVisited;
  }
  keep_pockets(tri);
}

}  // namespace pfem::mesh
