// Wall nodes sliding to the contact line (engine/mesh/contact_line.h): the remesher reports the
// free edge from the last surface particle to the wall, and the wall node nearest that
// particle's foot slides there (within half the spacing), the others stay home.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "engine/mesh/contact_line.h"
#include "engine/mesh/remesher.h"

namespace pfem::mesh {
namespace {

constexpr double kH = 0.01;

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
  const auto slides = contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours);
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
  const auto slides = contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours);
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
  return contact_line_slides(previous, s.x, s.y, s.sliding, s.neighbours);
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
  EXPECT_TRUE(contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours).empty());
}

}  // namespace
}  // namespace pfem::mesh
