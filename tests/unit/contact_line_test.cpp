// Wall nodes sliding to the contact line (engine/mesh/contact_line.h): the remesher reports the
// free edge from the last surface particle to the wall, and the wall node nearest that
// particle's foot slides there (within half the spacing), the others stay home.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "engine/mesh/contact_line.h"
#include "engine/mesh/remesher.h"

namespace pfem::mesh {
namespace {

constexpr double kH = 0.01;
constexpr std::array<double, 2> kLevel{1.0, 0.0};  // square to gravity (0, -g)

struct Scene {
  std::vector<double> x, y;
  std::vector<NodeKind> kind;
  std::vector<SlidingWallNode> sliding;
  std::vector<std::vector<int>> neighbours;
  std::vector<std::array<std::int32_t, 2>> walls;
};

// A wall up the left side (x = 0, nodes at y = 0, h, ..., 4h; the corner at the origin and the
// top end do not slide) and the floor to its right; water three particles wide in rows at 0.6 h,
// then every h below `surface`, and at `surface`.
Scene scene(double surface) {
  Scene s;
  const auto add = [&](double px, double py, NodeKind k) {
    s.x.push_back(px), s.y.push_back(py), s.kind.push_back(k);
    return static_cast<std::int32_t>(s.x.size()) - 1;
  };
  std::int32_t previous = -1;
  for (int j = 4; j >= 0; --j) {  // down the side wall
    const std::int32_t n = add(0.0, j * kH, NodeKind::Wall);
    if (previous >= 0) s.walls.push_back({previous, n});
    previous = n;
  }
  for (int i = 1; i <= 4; ++i) {  // along the floor
    const std::int32_t n = add(i * kH, 0.0, NodeKind::Wall);
    s.walls.push_back({previous, n});
    previous = n;
  }
  s.neighbours.assign(s.x.size(), {});
  for (int j = 1; j <= 3; ++j) {  // the side wall's inner nodes: indices 4 - j
    const int node = 4 - j, k = static_cast<int>(s.sliding.size());
    s.sliding.push_back({node, 0.0, j * kH, 0.0, 1.0, 0.49 * kH, 0.5 * kH, {node + 1, node - 1}});
    for (const int n : {node - 1, node, node + 1}) s.neighbours[n].push_back(k);
  }
  std::vector<double> rows{0.6 * kH};
  for (double py = surface - kH; py > 1.1 * kH; py -= kH) rows.push_back(py);
  rows.push_back(surface);
  for (const double py : rows)
    for (const double px : {kH, 2 * kH, 3 * kH}) add(px, py, NodeKind::Fluid);
  return s;
}

TEST(ContactLine, TheWallNodeNearestTheSurfaceParticlesFootSlidesThere) {
  Scene s = scene(1.3 * kH);
  RemeshOptions options{kH, 1.2, 0.0, -9.81, s.walls};
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, options);
  ASSERT_FALSE(mesh.contact_edges.empty());
  const auto slides = contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours, kLevel);
  ASSERT_EQ(slides.size(), 1u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 3);  // the node at y = h
  EXPECT_EQ(s.x[slides[0].particle], kH);
  EXPECT_EQ(s.y[slides[0].particle], 1.3 * kH);
  EXPECT_NEAR(slides[0].offset, 0.3 * kH, 1e-15);
  EXPECT_TRUE(slides[0].follows);
}

TEST(ContactLine, AFootBetweenTwoReachesTakesTheNearerNode) {
  // 0.497 h above the node at h, 0.503 h below the one at 2 h: beyond the free reach (0.49 h) of
  // both. Left at its place, the contact node would end the surface half a spacing off the water.
  Scene s = scene(1.497 * kH);
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, RemeshOptions{kH, 1.2, 0.0, -9.81, s.walls});
  const auto slides = contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours, kLevel);
  ASSERT_EQ(slides.size(), 1u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 3);  // the node at y = h
  EXPECT_NEAR(slides[0].offset, 0.497 * kH, 1e-15);
  EXPECT_TRUE(slides[0].follows);
}

// Two contacts on one wall, given directly (the remesher's contact edges are the input).
std::vector<WallSlide> two_contacts(Scene& s, double first_y, std::int32_t first_wall, double second_y,
                                    std::int32_t second_wall) {
  FluidMesh previous;
  for (const auto& [py, wall] : {std::pair{first_y, first_wall}, std::pair{second_y, second_wall}}) {
    s.x.push_back(0.5 * kH), s.y.push_back(py), s.kind.push_back(NodeKind::Fluid);
    previous.contact_edges.push_back({static_cast<std::int32_t>(s.x.size()) - 1, wall});
  }
  return contact_line_slides(previous, s.x, s.y, s.sliding, s.neighbours, kLevel);
}

TEST(ContactLine, ANodePastItsReachKeepsItsNeighbourAtItsPlace) {
  Scene s = scene(1.3 * kH);
  // The first foot 0.497 h above the node at h (index 3); the second 0.499 h above the node at
  // 2 h (index 2, farther, so it comes second), which stays for the first's sake, and the node at
  // 3 h does not cover it.
  const auto slides = two_contacts(s, 1.497 * kH, 3, 2.499 * kH, 2);
  ASSERT_EQ(slides.size(), 1u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 3);
  EXPECT_NEAR(slides[0].offset, 0.497 * kH, 1e-15);
}

TEST(ContactLine, TheContactNearestANodeTakesItWhateverTheOrderOfTheEdges) {
  // Two feet 0.3 h below and 0.2 h above the node at 2 h (index 2): the nearer takes it, given
  // first or second; the other then has the node at h (0.7 h from it: beyond its cover).
  for (const bool nearer_first : {true, false}) {
    Scene s = scene(1.3 * kH);
    const auto slides =
        nearer_first ? two_contacts(s, 2.2 * kH, 2, 1.7 * kH, 2) : two_contacts(s, 1.7 * kH, 2, 2.2 * kH, 2);
    ASSERT_EQ(slides.size(), 1u);
    EXPECT_EQ(s.sliding[slides[0].index].node, 2);
    EXPECT_NEAR(slides[0].offset, 0.2 * kH, 1e-15);
  }
}

TEST(ContactLine, ANodeStopsAtItsReachWhereItsNeighbourHasMoved) {
  Scene s = scene(1.3 * kH);
  // The node at 2 h follows the first foot up by 0.3 h; the second foot lies 0.497 h above the
  // node at h, toward the node at 2 h, which has moved: the node at h stops at 0.49 h.
  const auto slides = two_contacts(s, 2.3 * kH, 2, 1.497 * kH, 3);
  ASSERT_EQ(slides.size(), 2u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 2);
  EXPECT_NEAR(slides[0].offset, 0.3 * kH, 1e-15);
  EXPECT_EQ(s.sliding[slides[1].index].node, 3);
  EXPECT_NEAR(slides[1].offset, 0.49 * kH, 1e-15);
  EXPECT_FALSE(slides[1].follows);
}

TEST(ContactLine, AFootFartherThanHalfTheSpacingFromEveryInnerNodeMovesNothing) {
  // 0.3 h above the top end of the wall's sliding nodes (the node at 3 h), nearer the fixed end
  // at 4 h than to any node that slides.
  Scene s = scene(3.6 * kH);
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, RemeshOptions{kH, 1.2, 0.0, -9.81, s.walls});
  ASSERT_FALSE(mesh.contact_edges.empty());
  EXPECT_TRUE(contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours, kLevel).empty());
}

// A straight wall rising at angle theta from the origin, nodes every h (the ends fixed, the three
// inner ones sliding), and one contact: a particle off its node 2 by along * h along the wall and
// off * h into the water (the wall's left normal), on a contact edge to that node.
struct SlopedScene {
  std::vector<double> x, y;
  std::vector<SlidingWallNode> sliding;
  std::vector<std::vector<int>> neighbours;
  FluidMesh previous;
};

SlopedScene sloped(double theta, double along, double off) {
  SlopedScene s;
  const double tx = std::cos(theta), ty = std::sin(theta);
  for (int i = 0; i <= 4; ++i) s.x.push_back(i * kH * tx), s.y.push_back(i * kH * ty);
  s.neighbours.assign(5, {});
  for (int node = 1; node <= 3; ++node) {
    const int k = static_cast<int>(s.sliding.size());
    s.sliding.push_back({node, s.x[node], s.y[node], tx, ty, 0.49 * kH, 0.5 * kH, {node - 1, node + 1}});
    for (const int n : {node - 1, node, node + 1}) s.neighbours[n].push_back(k);
  }
  s.x.push_back(s.x[2] + kH * (along * tx - off * ty));
  s.y.push_back(s.y[2] + kH * (along * ty + off * tx));
  s.previous.contact_edges.push_back({5, 2});
  return s;
}

TEST(ContactLine, TheNodeOfASlopedWallSlidesToThePointLevelWithTheParticle) {
  // A wall at 60 degrees, the particle 0.1 h up along it and 0.3 h off it: its foot is 0.1 h up,
  // the point of the wall at its height 0.1 h + 0.3 h / tan 60 up. Square to a sloped wall, the
  // free edge from the particle to the node would slope, and still water could not be at rest.
  SlopedScene s = sloped(M_PI / 3.0, 0.1, 0.3);
  const auto slides = contact_line_slides(s.previous, s.x, s.y, s.sliding, s.neighbours, kLevel);
  ASSERT_EQ(slides.size(), 1u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 2);
  EXPECT_TRUE(slides[0].level);
  EXPECT_NEAR(slides[0].offset, (0.1 + 0.3 / std::tan(M_PI / 3.0)) * kH, 1e-15);
  const SlidingWallNode& n = s.sliding[slides[0].index];
  EXPECT_NEAR(n.home_y + slides[0].offset * n.ty, s.y[5], 1e-15);
  // Without a level (no gravity), the foot.
  const auto feet = contact_line_slides(s.previous, s.x, s.y, s.sliding, s.neighbours, {0.0, 0.0});
  ASSERT_EQ(feet.size(), 1u);
  EXPECT_FALSE(feet[0].level);
  EXPECT_NEAR(feet[0].offset, 0.1 * kH, 1e-15);
}

TEST(ContactLine, OnAGentleSlopeWhoseLevelPointNoNodeCoversTheNodeGoesToTheFoot) {
  // A 1:10 slope: the point of the wall level with a particle 0.3 h off it lies 3 h up the wall,
  // beyond every node next to the contact; the node under the particle takes its foot.
  SlopedScene s = sloped(std::atan(0.1), 0.1, 0.3);
  const auto slides = contact_line_slides(s.previous, s.x, s.y, s.sliding, s.neighbours, kLevel);
  ASSERT_EQ(slides.size(), 1u);
  EXPECT_EQ(s.sliding[slides[0].index].node, 2);
  EXPECT_FALSE(slides[0].level);
  EXPECT_NEAR(slides[0].offset, 0.1 * kH, 1e-15);
}

TEST(ContactLine, TheLevelOffsetsDerivativeIsItsCentralDifference) {
  // d(offset) for a change of the particle (dx, dy) and of the wall (home and tangent, as a
  // moving flap's), against central differences of level_offset.
  const SlidingWallNode n{1, 0.01, 0.02, std::cos(1.3), std::sin(1.3), 0.49 * kH, 0.5 * kH, {0, 2}};
  const double px = 0.004, py = 0.027, dx = 0.3, dy = -0.7;
  const std::array<double, 4> dh{0.2, -0.1, 0.5, -0.4};
  double o = 0.0;
  ASSERT_TRUE(n.level_offset(px, py, kLevel, o));
  const double eps = 1e-7;
  const auto moved = [&](double e) {
    SlidingWallNode m = n;
    m.home_x += e * dh[0], m.home_y += e * dh[1], m.tx += e * dh[2], m.ty += e * dh[3];
    double v = 0.0;
    EXPECT_TRUE(m.level_offset(px + e * dx, py + e * dy, kLevel, v));
    return v;
  };
  const double fd = (moved(eps) - moved(-eps)) / (2.0 * eps);
  EXPECT_NEAR(n.level_offset_derivative(o, dx, dy, dh, kLevel), fd, 1e-8 * std::abs(fd));
  // A level wall has no level point.
  const SlidingWallNode floor{1, 0.01, 0.0, 1.0, 0.0, 0.49 * kH, 0.5 * kH, {0, 2}};
  EXPECT_FALSE(floor.level_offset(px, py, kLevel, o));
}

}  // namespace
}  // namespace pfem::mesh
