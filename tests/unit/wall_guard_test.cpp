// The wall guard's geometry against closed-form answers: segments that cross, touch or miss; a
// beam that moves within the step, tested where it was and where it ends (not in between);
// which particles by a wall are to be removed; and the free fall of particles outside the mesh,
// x = x0 + dt v0 + dt^2 g (semi-implicit Euler), stopped where a wall is in the way.
#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <vector>

#include "engine/solve/wall_guard.h"

namespace pfem {
namespace {

using mesh::NodeKind;

std::pair<double, double> xy(Point2 p) { return {p.x, p.y}; }

// A node's sensitivities of x, y, vx, vy to parameter 0.
using Sensitivities = std::array<double, 4>;
Sensitivities motion_sensitivity(const NodeState& nodes, int i) {
  const double* d = nodes.sensitivity(i, 0);
  return {d[NodeState::kDx], d[NodeState::kDy], d[NodeState::kDvx], d[NodeState::kDvy]};
}

// Both argument orders of segments_cross, which must agree.
bool cross(Point2 p, Point2 q, Point2 a, Point2 b) {
  const bool pq_ab = segments_cross(p, q, a, b);
  EXPECT_EQ(pq_ab, segments_cross(a, b, p, q));
  EXPECT_EQ(pq_ab, segments_cross(q, p, b, a));
  return pq_ab;
}

TEST(WallGuard, SegmentsCrossTouchOrMiss) {
  EXPECT_TRUE(cross({0, 0}, {2, 2}, {0, 2}, {2, 0}));   // an X
  EXPECT_TRUE(cross({1, 0}, {1, 1}, {0, 0}, {2, 0}));   // one end on the other segment (a T)
  EXPECT_TRUE(cross({0, 0}, {1, 1}, {1, 1}, {2, 0}));   // a shared end point
  EXPECT_TRUE(cross({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // collinear and overlapping
  EXPECT_TRUE(cross({0, 0}, {1, 0}, {1, 0}, {3, 0}));   // collinear, end to end
  EXPECT_FALSE(cross({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear, apart on their line
  EXPECT_FALSE(cross({0, 1}, {2, 1}, {0, 0}, {2, 0}));  // parallel
  EXPECT_FALSE(cross({1, 1e-3}, {1, 1}, {0, 0}, {2, 0}));  // stops just short
  // The boxes overlap but the lines meet at (3, 3), beyond both segments.
  EXPECT_FALSE(cross({0, 0}, {2, 2}, {1.5, 0}, {2, 1}));
}

TEST(WallGuard, MoveAgainstAFixedWall) {
  const std::vector<WallPiece> floor{{{0, 0}, {1, 0}, {0, 0}, {1, 0}}};
  EXPECT_TRUE(crosses_wall(floor, {0.5, 0.1}, {0.5, -0.1}));   // through it
  EXPECT_TRUE(crosses_wall(floor, {0.5, 0.1}, {0.5, 0.0}));    // ends on it
  EXPECT_TRUE(crosses_wall(floor, {1.0, 0.1}, {1.0, -0.1}));   // through its end node
  EXPECT_FALSE(crosses_wall(floor, {0.5, 0.1}, {0.5, 0.05}));  // stops short
  EXPECT_FALSE(crosses_wall(floor, {1.5, 0.1}, {1.5, -0.1}));  // past its end
  EXPECT_FALSE(crosses_wall({}, {0.5, 0.1}, {0.5, -0.1}));     // no walls
}

TEST(WallGuard, ABeamMovingWithinTheStepIsTestedAtBothEnds) {
  // A vertical beam piece at x = 1 at t_n that the step takes to x = 2.
  const std::vector<WallPiece> beam{{{1, 0}, {1, 1}, {2, 0}, {2, 1}}};
  EXPECT_TRUE(crosses_wall(beam, {0.5, 0.5}, {1.2, 0.5}));   // crosses where it was
  EXPECT_TRUE(crosses_wall(beam, {1.8, 0.5}, {2.5, 0.5}));   // crosses where it ends
  EXPECT_TRUE(crosses_wall(beam, {1.5, 0.5}, {2.0, 0.5}));   // ends on its end position
  EXPECT_FALSE(crosses_wall(beam, {1.5, 0.5}, {1.6, 0.5}));  // swept over only: not seen
  EXPECT_FALSE(crosses_wall(beam, {0.5, 1.5}, {2.5, 1.5}));  // above it at both ends
}

TEST(WallGuard, PiecesTakeTheirNodesAtBothEnds) {
  const std::vector<double> x0{0, 1, 5}, y0{0, 0, 5}, x1{0, 1.5, 5}, y1{0, 0.25, 5};
  const std::vector<std::array<std::int32_t, 2>> pieces{{0, 1}, {1, 2}};
  const std::vector<WallPiece> walls = wall_pieces(pieces, {x0, y0, x1, y1});
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(xy(walls[0].a0), xy({0, 0}));
  EXPECT_EQ(xy(walls[0].b0), xy({1, 0}));
  EXPECT_EQ(xy(walls[0].a1), xy({0, 0}));
  EXPECT_EQ(xy(walls[0].b1), xy({1.5, 0.25}));
  EXPECT_EQ(xy(walls[1].a0), xy({1, 0}));
  EXPECT_EQ(xy(walls[1].b0), xy({5, 5}));
  EXPECT_EQ(xy(walls[1].a1), xy({1.5, 0.25}));
  EXPECT_EQ(xy(walls[1].b1), xy({5, 5}));
}

TEST(WallGuard, ParticlesByAWallWhoseMoveCrossesItAreRemoved) {
  // Floor nodes 0, 1 and a structure node 5; fluid particles 2, 3, 4, 6.
  const std::vector<NodeKind> kind{NodeKind::Wall,  NodeKind::Wall,      NodeKind::Fluid, NodeKind::Fluid,
                                   NodeKind::Fluid, NodeKind::Structure, NodeKind::Fluid};
  const std::vector<double> x0{0, 1, 0.5, 0.5, 0.8, 3, 2.5}, y0{0, 0, 0.2, 0.5, 0.5, 0, 0.2};
  std::vector<double> x1 = x0, y1 = y0;
  y1[2] = -0.1;  // through the floor
  y1[3] = -0.5;  // through it too, but in no triangle with a wall node: not tested
  y1[6] = -0.1;  // next to the structure node, and ends below the floor's line past its end
  const std::vector<std::array<std::int32_t, 3>> triangles{{0, 1, 2}, {2, 4, 3}, {4, 5, 6}};
  const StepEnds ends{x0, y0, x1, y1};
  const std::vector<std::array<std::int32_t, 2>> pieces{{0, 1}};
  const std::vector<WallPiece> walls = wall_pieces(pieces, ends);
  EXPECT_EQ(particles_crossing_walls(triangles, kind, ends, walls), (std::vector<std::uint8_t>{0, 0, 1, 0, 0, 0, 0}));

  // Particle 6 is tested by the structure node: a floor as long as its path is crossed.
  const std::vector<std::array<std::int32_t, 2>> long_floor{{0, 5}};
  EXPECT_EQ(particles_crossing_walls(triangles, kind, ends, wall_pieces(long_floor, ends)),
            (std::vector<std::uint8_t>{0, 0, 1, 0, 0, 0, 1}));
}

TEST(WallGuard, FreeFallIsSemiImplicitEuler) {
  // dt, g and v0 exact in binary: v = v0 + dt g = (1, -4), x = x0 + dt v0 + dt^2 g = (1.5, 0).
  const double dt = 0.5;
  const FreeFall f = fall_freely({1, 2}, {1, 0}, {0, -8}, dt, {});
  EXPECT_FALSE(f.hit);
  EXPECT_EQ(xy(f.v), xy({1, -4}));
  EXPECT_EQ(xy(f.x), xy({1.5, 0}));

  // A step of a PFEM run: the same closed form up to rounding.
  const double h = 1e-3, x0 = 0.3, y0 = 0.7, vx0 = 0.4, vy0 = -1.1, gx = 0.0, gy = -9.81;
  const FreeFall g = fall_freely({x0, y0}, {vx0, vy0}, {gx, gy}, h, {});
  EXPECT_NEAR(g.v.y, vy0 + h * gy, 1e-15);
  EXPECT_NEAR(g.x.x, x0 + h * vx0 + h * h * gx, 1e-15);
  EXPECT_NEAR(g.x.y, y0 + h * vy0 + h * h * gy, 1e-15);
}

TEST(WallGuard, AFallingParticleStopsAtAWallInItsWay) {
  // The fall of FreeFallIsSemiImplicitEuler, from (1, 2) to (1.5, 0).
  const auto fall_onto = [](double floor_y) {
    const std::vector<WallPiece> floor{{{-10, floor_y}, {10, floor_y}, {-10, floor_y}, {10, floor_y}}};
    return fall_freely({1, 2}, {1, 0}, {0, -8}, 0.5, floor);
  };
  for (const double floor_y : {0.5, 0.0}) {  // in its way, and where it would land
    const FreeFall f = fall_onto(floor_y);
    EXPECT_TRUE(f.hit) << floor_y;
    EXPECT_EQ(xy(f.x), xy({1, 2}));
    EXPECT_EQ(xy(f.v), xy({0, 0}));
  }
  const FreeFall below = fall_onto(-0.5);
  EXPECT_FALSE(below.hit);
  EXPECT_EQ(below.x.y, 0.0);
}

TEST(WallGuard, OnlyFluidParticlesOutsideTheMeshFallAndTheirSensitivitiesFollow) {
  NodeState nodes;
  nodes.add(0, 0, NodeKind::Wall);
  nodes.add(1, 0, NodeKind::Fluid, 1.0, 0.0);  // in the mesh: the step moves it, not the guard
  nodes.add(1, 2, NodeKind::Fluid, 1.0, 0.0);  // falls to (1.5, 0)
  nodes.add(4, 2, NodeKind::Fluid, 1.0, 0.0);  // would fall through the roof at y = 1
  nodes.add(6, 2, NodeKind::Removed, 1.0, 0.0);
  nodes.set_num_params(1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    double* d = nodes.sensitivity(i, 0);
    d[NodeState::kDx] = 1.0, d[NodeState::kDy] = 2.0, d[NodeState::kDvx] = 4.0, d[NodeState::kDvy] = 8.0;
  }
  const std::vector<std::uint8_t> in_mesh{1, 1, 0, 0, 0};
  const std::vector<WallPiece> roof{{{3, 1}, {5, 1}, {3, 1}, {5, 1}}};
  move_free_particles(in_mesh, roof, {0, -8}, 0.5, nodes);

  EXPECT_EQ(nodes.x, (std::vector<double>{0, 1, 1.5, 4, 6}));
  EXPECT_EQ(nodes.y, (std::vector<double>{0, 0, 0, 2, 2}));
  EXPECT_EQ(nodes.vx, (std::vector<double>{0, 1, 1, 0, 1}));
  EXPECT_EQ(nodes.vy, (std::vector<double>{0, 0, -4, 0, 0}));
  // Sensitivities (dx, dy, dvx, dvy): dx += dt dv where it falls; dv = 0 where it sticks.
  EXPECT_EQ(motion_sensitivity(nodes, 2), (Sensitivities{3, 6, 4, 8}));
  EXPECT_EQ(motion_sensitivity(nodes, 3), (Sensitivities{1, 2, 0, 0}));
  for (const int untouched : {0, 1, 4}) EXPECT_EQ(motion_sensitivity(nodes, untouched), (Sensitivities{1, 2, 4, 8}));
}

}  // namespace
}  // namespace pfem
