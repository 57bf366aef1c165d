// Unit tests of the velocity a slip wall node takes home (engine/analysis/slip_wall_remap.h):
// a velocity linear along the wall is remapped exactly, a node with a dry neighbour on the side
// of home keeps its own, and the sensitivities are those of the remapped value (central
// differences of the whole remap with the positions, the home and the velocities depending on a
// parameter).
#include "engine/analysis/slip_wall_remap.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace pfem {
namespace {

// A vertical slip wall x = 0 with nodes at y = 0 (a corner), 0.01 (sliding, home y = 0.01 + e)
// and 0.02 (an end); after the step the middle node is at 0.012 + a theta and the corner node
// still at 0, the end at 0.02 + b theta; vy = 0.3 + 2 y + c theta at each node's place.
struct Wall {
  NodeState nodes;
  std::vector<mesh::SlidingWallNode> sliding;
  std::vector<std::array<double, 4>> dwall;
  std::vector<std::uint8_t> slip{0, kSlipY, 0}, wet{1, 1, 1};

  Wall(double theta, double home_shift) {
    constexpr double a = 0.001, b = 0.002, c = 0.05;
    const std::array<double, 3> y{0.0, 0.012 + a * theta, 0.02 + b * theta};
    for (const double yi : y) nodes.add(0.0, yi, mesh::NodeKind::Wall, 0.0, 0.3 + 2.0 * yi + c * theta);
    nodes.set_num_params(1);
    for (int i = 0; i < 3; ++i) {
      double* d = nodes.sensitivity(i, 0);
      d[NodeState::kDy] = i == 0 ? 0.0 : i == 1 ? a : b;
      d[NodeState::kDvy] = 2.0 * d[NodeState::kDy] + c;
    }
    mesh::SlidingWallNode s;
    s.node = 1, s.home_x = 0.0, s.home_y = 0.01 + home_shift * theta, s.tx = 0.0, s.ty = 1.0, s.reach = 0.0049;
    s.neighbours = {0, 2};
    sliding.push_back(s);
    dwall.push_back({0.0, home_shift, 0.0, 0.0});
  }
  void remap() { remap_slip_velocities(sliding, dwall, slip, wet, nodes); }
};

TEST(SlipWallRemap, AVelocityLinearAlongTheWallIsRemappedExactly) {
  Wall w(0.0, 0.0);
  w.remap();
  EXPECT_NEAR(w.nodes.vy[1], 0.3 + 2.0 * 0.01, 1e-15);  // the value at home, not at 0.012
  EXPECT_EQ(w.nodes.vy[0], 0.3);                         // only sliding nodes are remapped
  EXPECT_EQ(w.nodes.vx[1], 0.0);                         // the wall's normal component is not touched
}

TEST(SlipWallRemap, ANodeBelowItsHomeTakesTheValueFromItsNeighbourAbove) {
  Wall w(0.0, 0.0);
  w.nodes.y[1] = 0.0085, w.nodes.vy[1] = 0.3 + 2.0 * 0.0085;
  w.remap();
  EXPECT_NEAR(w.nodes.vy[1], 0.3 + 2.0 * 0.01, 1e-15);
}

TEST(SlipWallRemap, ANodeWithADryNeighbourOnTheSideOfHomeKeepsItsVelocity) {
  Wall w(0.0, 0.0);
  w.wet[0] = 0;
  w.remap();
  EXPECT_EQ(w.nodes.vy[1], 0.3 + 2.0 * 0.012);
  Wall no_slip(0.0, 0.0);
  no_slip.slip[1] = 0;
  no_slip.remap();
  EXPECT_EQ(no_slip.nodes.vy[1], 0.3 + 2.0 * 0.012);
}

TEST(SlipWallRemap, TheSensitivityIsThatOfTheRemappedValue) {
  // A velocity that is not linear along the wall (the end node's off the line), the home moving
  // with theta too: the remapped value's derivative against central differences.
  const auto remapped = [](double theta) {
    Wall w(theta, 0.004);
    w.nodes.vy[0] += 0.7;  // the corner's velocity off the line: the weight's derivative counts
    w.remap();
    return w.nodes.vy[1];
  };
  Wall w(0.0, 0.004);
  w.nodes.vy[0] += 0.7;
  w.remap();
  const double eps = 1e-6, fd = (remapped(eps) - remapped(-eps)) / (2 * eps);
  EXPECT_NEAR(w.nodes.sensitivity(1, 0)[NodeState::kDvy], fd, 1e-8 * std::abs(fd) + 1e-10);
  EXPECT_GT(std::abs(fd), 0.1);  // not trivially zero (0.127)
}

}  // namespace
}  // namespace pfem
