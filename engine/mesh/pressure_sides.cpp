// The sides of the wall and beam lines at their nodes (FluidMesh::sides, corner_side): which of a
// node's pressures each kept triangle's corner takes.
#include "engine/mesh/remesh_passes.h"

#include <algorithm>
#include <utility>

namespace pfem::mesh {
namespace {

// The sides from the constrained edges of the triangulation itself: a node lying on a segment
// (which splits it) or a merged duplicate gets the edges it really has.
class LineSides {
 public:
  LineSides(std::size_t n, std::span<const LineRider> riders)
      : count(n, 1), riders_(riders), rider_of_(n, -1), neighbours_(n), done_(n, 0) {
    for (std::size_t r = 0; r < riders.size(); ++r) rider_of_[riders[r].node] = static_cast<int>(r);
  }
  std::vector<std::uint8_t> count;

  // The sides of face f's corners.
  std::array<std::uint8_t, 3> of(FaceHandle f, std::span<const NodeKind> kind) {
    std::array<std::uint8_t, 3> side{};
    for (int c = 0; c < 3; ++c) {
      const VertexHandle v = f->vertex(c);
      const std::int32_t i = v->info();
      if (kind[i] != NodeKind::Wall && kind[i] != NodeKind::Structure) continue;
      const std::vector<std::int32_t>& around = neighbours(v);
      if (around.size() < 2) continue;
      // Clockwise around v from f to the first constrained edge: its far end begins the sector.
      FaceHandle g = f;
      for (std::size_t step = 0; step <= 4 * around.size() + 64; ++step) {
        const int at = g->index(v), edge = Delaunay::cw(at);  // edge (v, ccw(at)'s vertex)
        if (g->is_constrained(edge)) {
          const std::int32_t start = ranked_as(i, g->vertex(Delaunay::ccw(at))->info());
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
  // The index node i's constrained neighbour j is ranked by: a rider on a segment of i, the
  // segment's far end.
  std::int32_t ranked_as(std::int32_t i, std::int32_t j) const {
    const int r = rider_of_[j];
    if (r < 0) return j;
    const LineRider& rider = riders_[r];
    return i == rider.a ? rider.b : i == rider.b ? rider.a : j;
  }
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
        around.push_back(ranked_as(i, (a == v ? b : a)->info()));
      }
    } while (++e != end);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    count[i] = static_cast<std::uint8_t>(std::clamp<std::size_t>(around.size(), 1, kMaxPressureSides));
    return around;
  }
  std::span<const LineRider> riders_;
  std::vector<int> rider_of_;  // per node: its index in riders_, or -1
  std::vector<std::vector<std::int32_t>> neighbours_;
  std::vector<std::uint8_t> done_;
};

}  // namespace

void assign_pressure_sides(const Delaunay& tri, std::span<const NodeKind> kind, std::span<const LineRider> riders,
                           FluidMesh& mesh) {
  LineSides sides(kind.size(), riders);
  for (auto f = tri.finite_faces_begin(); f != tri.finite_faces_end(); ++f)
    if (f->info()) mesh.corner_side.push_back(sides.of(f, kind));
  mesh.sides = std::move(sides.count);
}

}  // namespace pfem::mesh
