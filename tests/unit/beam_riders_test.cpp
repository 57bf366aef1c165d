// Beam riders (engine/mesh/beam_riders.h): where the free surface meets a beam between two of its
// nodes, a node on the segment level with the contact particle, which splits the segment for the
// remeshing (RemeshOptions::riders).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "engine/mesh/beam_riders.h"
#include "engine/mesh/remesher.h"

namespace pfem::mesh {
namespace {

constexpr double kH = 0.01;
constexpr std::array<double, 2> kLevel{1.0, 0.0};  // square to gravity (0, -g)

TEST(BeamRiders, TheLevelPointOfASlopedSegment) {
  double s = 0.0;
  // From (0, 0) to (1, 2): the point at height 0.5 is a quarter of the way.
  ASSERT_TRUE(level_fraction({0.0, 0.0}, {1.0, 2.0}, {0.3, 0.5}, kLevel, s));
  EXPECT_NEAR(s, 0.25, 1e-15);
  // Gravity along (1, -1): the level runs along (1, 1)/sqrt 2; the segment (0, 0)-(0, 1) meets
  // that line through (0.3, 0.5) at height 0.2.
  const double r = std::sqrt(0.5);
  ASSERT_TRUE(level_fraction({0.0, 0.0}, {0.0, 1.0}, {0.3, 0.5}, {r, r}, s));
  EXPECT_NEAR(s, 0.2, 1e-15);
  EXPECT_FALSE(level_fraction({0.0, 0.0}, {1.0, 0.0}, {0.3, 0.5}, kLevel, s));  // a level segment
}

TEST(BeamRiders, TheLevelFractionsDerivativeMatchesCentralDifferences) {
  const std::array<double, 2> a{0.1, -0.05}, b{0.13, 0.2}, p{0.05, 0.07}, l{0.96, -0.28};
  const std::array<double, 2> da{0.3, -0.7}, db{-0.4, 0.2}, dp{0.9, 0.5};
  const auto s_at = [&](double eps) {
    double s = 0.0;
    EXPECT_TRUE(level_fraction({a[0] + eps * da[0], a[1] + eps * da[1]}, {b[0] + eps * db[0], b[1] + eps * db[1]},
                               {p[0] + eps * dp[0], p[1] + eps * dp[1]}, l, s));
    return s;
  };
  const double eps = 1e-6, fd = (s_at(eps) - s_at(-eps)) / (2 * eps);
  const double ds = level_fraction_derivative(a, b, s_at(0.0), da, db, dp, l);
  EXPECT_NEAR(ds, fd, 1e-8 * std::abs(fd));
  EXPECT_GT(std::abs(ds), 0.1);
}

// Water three particles wide against a vertical beam at x = 4 h (nodes every 0.71 h from the
// floor, where a wall node is its base), a wall down the left side and along the floor (nodes
// every h); rows every h up to `surface`.
struct Scene {
  std::vector<double> x, y;
  std::vector<NodeKind> kind;
  std::vector<std::array<std::int32_t, 2>> walls, segments;
  std::vector<std::vector<int>> segments_of;
  std::int32_t first_rider = 0;
};
constexpr double kSpacing = 0.71 * kH;

Scene scene(double surface) {
  Scene s;
  const auto add = [&](double px, double py, NodeKind k) {
    s.x.push_back(px), s.y.push_back(py), s.kind.push_back(k);
    return static_cast<std::int32_t>(s.x.size()) - 1;
  };
  std::int32_t previous = -1;
  for (int j = 6; j >= 0; --j) {  // down the side wall
    const std::int32_t n = add(0.0, j * kH, NodeKind::Wall);
    if (previous >= 0) s.walls.push_back({previous, n});
    previous = n;
  }
  for (int i = 1; i <= 4; ++i) {  // along the floor to the beam's base
    const std::int32_t n = add(i * kH, 0.0, NodeKind::Wall);
    s.walls.push_back({previous, n});
    previous = n;
  }
  for (int j = 1; j <= 8; ++j) {
    const std::int32_t n = add(4 * kH, j * kSpacing, NodeKind::Structure);
    s.segments.push_back({previous, n});
    previous = n;
  }
  for (double py = 0.6 * kH; py < surface - 0.5 * kH; py += kH)
    for (const double px : {kH, 2 * kH, 3 * kH}) add(px, py, NodeKind::Fluid);
  for (const double px : {kH, 2 * kH, 3 * kH}) add(px, surface, NodeKind::Fluid);
  s.segments_of.assign(s.x.size(), {});
  for (std::size_t j = 0; j < s.segments.size(); ++j)
    for (const std::int32_t end : s.segments[j]) s.segments_of[end].push_back(static_cast<int>(j));
  s.first_rider = static_cast<std::int32_t>(s.x.size());
  for (std::size_t j = 0; j < s.segments.size(); ++j) add(0.0, 0.0, NodeKind::Removed);
  return s;
}

RemeshOptions options(const Scene& s) {
  RemeshOptions o{kH, 1.2, 0.0, -9.81, s.walls};
  o.constraints.insert(o.constraints.end(), s.segments.begin(), s.segments.end());
  return o;
}

// The scene remeshed with the rider of segment j placed on the beam at height y.
FluidMesh remesh_with_rider(Scene& s, int j, double y) {
  const std::int32_t rider = s.first_rider + j;
  s.kind[rider] = NodeKind::Structure;
  s.x[rider] = 4 * kH, s.y[rider] = y;
  const std::vector<LineRider> riders{{rider, s.segments[j][0], s.segments[j][1]}};
  RemeshOptions with = options(s);
  with.riders = riders;
  return remesh(s.x, s.y, s.kind, with);
}

TEST(BeamRiders, ARiderGoesOnTheSegmentLevelWithTheSurfaceAndEndsIt) {
  // The surface at 3.2 h: between the beam's nodes at 4 (2.84 h) and 5 spacings (3.55 h).
  Scene s = scene(3.2 * kH);
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, options(s));
  const auto places = place_riders(mesh, s.x, s.y, s.segments, s.segments_of, s.first_rider, kLevel, kH);
  ASSERT_EQ(places.size(), 1u);
  EXPECT_EQ(places[0].segment, 4);  // from the node at 4 spacings to that at 5
  EXPECT_EQ(s.x[places[0].particle], 3 * kH);
  EXPECT_NEAR(places[0].s, (3.2 * kH - 4 * kSpacing) / kSpacing, 1e-12);

  // Placed, the rider splits its segment: the surface now ends at it, level.
  const std::int32_t rider = s.first_rider + places[0].segment;
  const auto [a, b] = s.segments[places[0].segment];
  const FluidMesh split = remesh_with_rider(s, places[0].segment, 3.2 * kH);
  ASSERT_EQ(split.riders.size(), 1u);
  EXPECT_TRUE(split.in_mesh[rider]);
  EXPECT_TRUE(split.free_surface[rider]);
  bool ends_at_rider = false;
  for (const auto& [particle, node] : split.contact_edges)
    if (s.x[particle] == 3 * kH) ends_at_rider = ends_at_rider || node == rider;
  EXPECT_TRUE(ends_at_rider);
  for (const auto& t : split.triangles)  // no triangle spans the segment's old ends
    EXPECT_FALSE((t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b));

  // From the rider's own contact edge it stays on its segment (the next step).
  const auto again = place_riders(split, s.x, s.y, s.segments, s.segments_of, s.first_rider, kLevel, kH);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].segment, 4);
}

TEST(BeamRiders, ASurfaceNearANodeTakesNoRider) {
  // 0.005 of a spacing above the node at 4 spacings: within kRiderMargin, the node covers it.
  Scene s = scene(4.005 * kSpacing);
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, options(s));
  ASSERT_FALSE(mesh.contact_edges.empty());
  EXPECT_TRUE(place_riders(mesh, s.x, s.y, s.segments, s.segments_of, s.first_rider, kLevel, kH).empty());
}

TEST(BeamRiders, TwoContactsClaimingASegmentLeaveItToTheNearer) {
  Scene s = scene(3.2 * kH);
  FluidMesh previous;
  for (const auto& [px, py] : {std::array{2.5 * kH, 3.3 * kH}, std::array{3.6 * kH, 3.1 * kH}}) {
    s.x.push_back(px), s.y.push_back(py), s.kind.push_back(NodeKind::Fluid);
    previous.contact_edges.push_back({static_cast<std::int32_t>(s.x.size()) - 1, 15});  // the node at 5 spacings
  }
  for (const bool reversed : {false, true}) {
    FluidMesh order = previous;
    if (reversed) std::swap(order.contact_edges[0], order.contact_edges[1]);
    const auto places = place_riders(order, s.x, s.y, s.segments, s.segments_of, s.first_rider, kLevel, kH);
    ASSERT_EQ(places.size(), 1u);
    EXPECT_EQ(places[0].segment, 4);
    EXPECT_NEAR(places[0].s, (3.1 * kH - 4 * kSpacing) / kSpacing, 1e-12);  // the particle 0.4 h away
  }
}

// A rider stands for the far end of its segment when its ends' pressure sides are ranked: a beam
// with water on both sides gives the triangles on each side of its nodes the same side with the
// rider as without it.
TEST(BeamRiders, TheSegmentsEndsKeepTheRanksOfTheirSides) {
  Scene s = scene(3.2 * kH);
  for (double py = 0.6 * kH; py < 3.3 * kH; py += kH)  // water on the right of the beam too
    for (const double px : {5 * kH, 6 * kH}) s.x.push_back(px), s.y.push_back(py), s.kind.push_back(NodeKind::Fluid);
  const auto [a, b] = s.segments[2];  // its ends below the water: wet on both sides
  const auto sides_at = [&](const FluidMesh& mesh, std::int32_t node) {
    std::array<int, 2> side{-1, -1};  // left, right
    for (std::size_t e = 0; e < mesh.triangles.size(); ++e)
      for (int c = 0; c < 3; ++c) {
        if (mesh.triangles[e][c] != node) continue;
        const auto& t = mesh.triangles[e];
        const bool left = s.x[t[0]] + s.x[t[1]] + s.x[t[2]] < 12 * kH;
        side[left ? 0 : 1] = mesh.side(e, c);
      }
    return side;
  };
  const FluidMesh plain = remesh(s.x, s.y, s.kind, options(s));
  const FluidMesh split = remesh_with_rider(s, 2, 2.5 * kSpacing);
  for (const std::int32_t end : {a, b}) {
    const auto before = sides_at(plain, end), after = sides_at(split, end);
    EXPECT_NE(before[0], before[1]) << end;
    EXPECT_EQ(before, after) << end;
  }
}

TEST(BeamRiders, ARiderOffItsSegmentsConstraintsIsRefused) {
  Scene s = scene(3.2 * kH);
  const std::vector<LineRider> riders{{s.first_rider, 0, 5}};
  s.kind[s.first_rider] = NodeKind::Structure;
  RemeshOptions with = options(s);
  with.riders = riders;
  EXPECT_THROW(remesh(s.x, s.y, s.kind, with), std::invalid_argument);
}

}  // namespace
}  // namespace pfem::mesh
