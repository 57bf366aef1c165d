// Unit tests of the particle spacing control between steps (engine/mesh/particle_spacing.h):
// which edges get a new particle, which particles are taken out.
#include "engine/mesh/particle_spacing.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace {

using pfem::mesh::FluidMesh;
using pfem::mesh::NodeKind;
using Edge = std::array<std::int32_t, 2>;

// Two triangles (0, 1, 2) and (1, 3, 2) on the rectangle [0, w] x [0, 0.5]: edges 0-1 and 2-3
// of length w, the diagonal 1-2 longer, the sides 0-2 and 1-3 of 0.5.
struct Quad {
  std::vector<double> x, y;
  std::vector<NodeKind> kind{NodeKind::Fluid, NodeKind::Fluid, NodeKind::Fluid, NodeKind::Fluid};
  FluidMesh mesh;

  explicit Quad(double w) : x{0.0, w, 0.0, w}, y{0.0, 0.0, 0.5, 0.5} {
    mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
    mesh.in_mesh.assign(4, 1);
    mesh.free_surface.assign(4, 0);
  }
  std::vector<std::array<std::int32_t, 2>> walls;  // wall segments
  std::vector<Edge> split(double surface_length, double interior_length, double clearance = 0.0) const {
    std::vector<Edge> out;
    for (const auto& e : pfem::mesh::edges_to_split(mesh, x, y, kind, surface_length, interior_length, {walls, clearance}))
      out.push_back({e.a, e.b});
    return out;
  }
};

TEST(ParticleSpacing, InteriorEdgesAreSplitOnlyBeyondTheInteriorLength) {
  const Quad inside(1.8);  // longest edge, the diagonal: 1.868
  EXPECT_TRUE(inside.split(1.6, 2.0).empty());
  // 0-1 and 3-2; the diagonal shares their nodes (each node ends at most one split edge)
  EXPECT_EQ(inside.split(1.6, 1.6), (std::vector<Edge>{{0, 1}, {3, 2}}));

  const Quad stretched(2.1);
  EXPECT_EQ(stretched.split(1.6, 2.0), (std::vector<Edge>{{0, 1}, {3, 2}}));
}

TEST(ParticleSpacing, EdgesTouchingTheSurfaceUseTheSurfaceLength) {
  Quad q(1.8);
  q.mesh.free_surface[0] = 1;  // 0-1 (1.8) touches the surface; 2-3 (1.8) is inside
  EXPECT_EQ(q.split(1.6, 2.0), (std::vector<Edge>{{0, 1}}));
  q.mesh.free_surface[1] = 1;  // 0-1 now runs along the surface: as long as an interior edge may be
  EXPECT_EQ(q.split(1.6, 2.0), (std::vector<Edge>{{1, 2}}));
  EXPECT_EQ(q.split(2.0, 1.7), (std::vector<Edge>{{0, 1}, {3, 2}}));
}

// Of the edges between two surface particles, those in one triangle are the surface's own (their
// new particle is on the surface); the diagonal between both triangles is a chord through the water.
TEST(ParticleSpacing, EdgesBetweenSurfaceParticlesTellTheSurfaceFromAChord) {
  Quad q(2.1);  // every node on the surface: 0-1 and 3-2 of 2.1, the diagonal 1-2 of 2.16
  q.mesh.free_surface.assign(4, 1);
  const auto edges = pfem::mesh::edges_to_split(q.mesh, q.x, q.y, q.kind, 1.6, 2.0, {});
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ((Edge{edges[0].a, edges[0].b}), (Edge{0, 1}));
  EXPECT_TRUE(edges[0].on_surface);
  EXPECT_EQ((Edge{edges[1].a, edges[1].b}), (Edge{3, 2}));
  EXPECT_TRUE(edges[1].on_surface);
  q.x[1] = q.x[3] = 1.9;  // 0-1 and 3-2 of 1.9 stay whole; the diagonal (1.96) goes beyond 1.9
  const auto chord = pfem::mesh::edges_to_split(q.mesh, q.x, q.y, q.kind, 1.6, 1.9, {});
  ASSERT_EQ(chord.size(), 1u);
  EXPECT_EQ((Edge{chord[0].a, chord[0].b}), (Edge{1, 2}));
  EXPECT_FALSE(chord[0].on_surface);
}

// 0 and 2 on a wall along x = 0 (the segment 0-2), particles 1 and 3 at x = 2.5: the edges 1-0
// (2.5), 1-2 (2.55) and 3-2 (2.5) have their middles 1.25 from the wall.
TEST(ParticleSpacing, EdgesToWallNodesAreSplitWhereTheirMiddleIsClearOfTheWall) {
  Quad q(2.5);
  q.kind[0] = q.kind[2] = NodeKind::Wall;
  q.walls = {{0, 2}};
  // the particle first; 1-0 takes 1 before 1-2 comes
  EXPECT_EQ(q.split(1.6, 2.0, 1.2), (std::vector<Edge>{{1, 0}, {3, 2}}));
  EXPECT_TRUE(q.split(1.6, 2.0, 1.3).empty());  // the middles 1.25 from the wall: too near
  EXPECT_TRUE(q.split(1.6, 2.6, 1.2).empty());  // no edge longer than 2.6
  q.mesh.free_surface[3] = 1;                   // 3 on the surface: its edge to the wall stays whole
  EXPECT_EQ(q.split(1.6, 2.0, 1.2), (std::vector<Edge>{{1, 0}}));
  q.mesh.free_surface[3] = 0;
  q.walls.clear();                              // no segment tells where the wall runs
  EXPECT_TRUE(q.split(1.6, 2.0, 1.2).empty());
  // A second wall piece at node 2 along the diagonal 2-1: the middle of 3-2 is 0.245 from it.
  q.walls = {{0, 2}, {2, 1}};
  EXPECT_EQ(q.split(1.6, 2.0, 1.2), (std::vector<Edge>{{1, 0}}));
}

TEST(ParticleSpacing, CloseParticlesAreRemovedHigherIndexOrNextToAWall) {
  Quad q(1.0);
  q.y[2] = 0.1;  // 0-2 closer than 0.2: of two particles the higher index goes
  auto kind = q.kind;
  EXPECT_EQ(pfem::mesh::remove_close_particles(q.mesh, q.x, q.y, kind, 0.2), 1);
  EXPECT_EQ(kind, (std::vector<NodeKind>{NodeKind::Fluid, NodeKind::Fluid, NodeKind::Removed, NodeKind::Fluid}));

  kind = q.kind;
  kind[2] = NodeKind::Wall;  // next to a wall node the particle goes, whatever its index
  EXPECT_EQ(pfem::mesh::remove_close_particles(q.mesh, q.x, q.y, kind, 0.2), 1);
  EXPECT_EQ(kind[0], NodeKind::Removed);

  kind = q.kind;
  EXPECT_EQ(pfem::mesh::remove_close_particles(q.mesh, q.x, q.y, kind, 0.05), 0);
}

}  // namespace
