// Wall nodes sliding to the contact line (engine/mesh/contact_line.h): the remesher reports the
// free edge from the last surface particle to the wall, and the wall node nearest that
// particle's foot slides there (within its reach), the others stay home.
#include <gtest/gtest.h>

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
// top end do not slide) and the floor to its right; water three particles wide whose top row is
// at `surface`.
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
    s.sliding.push_back({node, 0.0, j * kH, 0.0, 1.0, 0.49 * kH});
    for (const int n : {node - 1, node, node + 1}) s.neighbours[n].push_back(k);
  }
  for (const double py : {0.6 * kH, surface})
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
}

TEST(ContactLine, AFootBeyondEveryReachMovesNothing) {
  Scene s = scene(1.5 * kH);  // midway between the nodes at h and 2h: beyond 0.49 h of both
  const FluidMesh mesh = remesh(s.x, s.y, s.kind, RemeshOptions{kH, 1.2, 0.0, -9.81, s.walls});
  EXPECT_TRUE(contact_line_slides(mesh, s.x, s.y, s.sliding, s.neighbours).empty());
}

}  // namespace
}  // namespace pfem::mesh
