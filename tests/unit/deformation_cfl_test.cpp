// Unit tests of the deformation limit of a step (engine/mesh/deformation_cfl.h): the smallest area
// ratio det(I + s grad v) of linear velocity fields whose value is known in closed form, and
// whether a step of that length would be halved before its attempt (the time loop halves it
// while a triangle collapses within it: the first substep is dt / 2^k for the first k at which
// none does).
#include "engine/mesh/deformation_cfl.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <vector>

namespace {

using pfem::mesh::collapses_within;
using pfem::mesh::FluidMesh;
using pfem::mesh::smallest_area_ratio;

// Two triangles on the square [0, L]^2, L = 1/128 m (about h), the nodes moving with the velocity
// field v(x, y) about its centre. L, the rates and the steps are powers of two, so that a ratio
// of exactly 0 is computed exactly.
constexpr double L = 1.0 / 128, kMs = 1.0 / 1024;  // kMs: a step of about 1 ms
struct Square {
  std::vector<double> x{0.0, L, 0.0, L}, y{0.0, 0.0, L, L}, vx, vy;
  FluidMesh mesh;

  explicit Square(const std::function<std::array<double, 2>(double, double)>& v) {
    mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
    for (std::size_t i = 0; i < x.size(); ++i) {
      const auto [u, w] = v(x[i] - L / 2, y[i] - L / 2);
      vx.push_back(u), vy.push_back(w);
    }
  }
  double ratio(double dt) const { return smallest_area_ratio(mesh, x, y, vx, vy, dt); }
  bool collapses(double dt) const { return collapses_within(mesh, x, y, vx, vy, dt); }
};

TEST(DeformationCfl, UniaxialCompressionCollapsesAtOneOverItsRate) {
  // v = (-c x, 0): det(I + s grad v) = 1 - c s, collapsed at s = 1/c = 2/3 of kMs: a step of 4 kMs
  // is halved three times (ratios -5, -2, -0.5), its first substep kMs / 2 (0.25).
  const Square square([](double x, double) { return std::array{-1536.0 * x, 0.0}; });
  EXPECT_DOUBLE_EQ(square.ratio(4 * kMs), -5.0);
  EXPECT_DOUBLE_EQ(square.ratio(2 * kMs), -2.0);
  EXPECT_DOUBLE_EQ(square.ratio(kMs), -0.5);
  EXPECT_DOUBLE_EQ(square.ratio(kMs / 2), 0.25);
  EXPECT_TRUE(square.collapses(kMs));
  EXPECT_FALSE(square.collapses(kMs / 2));
}

TEST(DeformationCfl, AStepThatEndsExactlyCollapsedIsHalved) {
  const Square square([](double x, double) { return std::array{-1024.0 * x, 0.0}; });
  EXPECT_EQ(square.ratio(kMs), 0.0);
  EXPECT_TRUE(square.collapses(kMs));
  EXPECT_DOUBLE_EQ(square.ratio(kMs / 2), 0.5);
  EXPECT_FALSE(square.collapses(kMs / 2));
}

TEST(DeformationCfl, ATriangleThatPassesThroughCollapseWithinTheStepCounts) {
  // v = -c (x, y): det = (1 - c s)^2, zero at s = 1/c and back to 1 at 2/c, the triangle turned
  // about its centre: its end ratio is 1, but it collapsed on the way.
  const Square square([](double x, double y) { return std::array{-1024.0 * x, -1024.0 * y}; });
  EXPECT_EQ(square.ratio(2 * kMs), 0.0);
  EXPECT_TRUE(square.collapses(2 * kMs));
  EXPECT_EQ(square.ratio(kMs), 0.0);  // the end of the step
  EXPECT_TRUE(square.collapses(kMs));
  EXPECT_DOUBLE_EQ(square.ratio(kMs / 2), 0.25);
  EXPECT_FALSE(square.collapses(kMs / 2));
}

TEST(DeformationCfl, RotationAndShearKeepTheArea) {
  // Rotation: det = 1 + (w s)^2 > 1, never a collapse however fast; simple shear: det = 1.
  const Square spin([](double x, double y) { return std::array{-1e5 * y, 1e5 * x}; });
  EXPECT_DOUBLE_EQ(spin.ratio(kMs), 1.0);  // the smallest ratio is that at s = 0
  EXPECT_FALSE(spin.collapses(kMs));
  const Square shear([](double, double y) { return std::array{1e4 * y, 0.0}; });
  EXPECT_DOUBLE_EQ(shear.ratio(kMs), 1.0);
  EXPECT_FALSE(shear.collapses(kMs));
}

TEST(DeformationCfl, ExpansionAndNoTrianglesLoseNothing) {
  const Square square([](double x, double y) { return std::array{1000.0 * x, 1000.0 * y}; });
  EXPECT_DOUBLE_EQ(square.ratio(kMs), 1.0);
  const FluidMesh empty;
  EXPECT_DOUBLE_EQ(smallest_area_ratio(empty, {}, {}, {}, {}, kMs), 1.0);
  EXPECT_FALSE(collapses_within(empty, {}, {}, {}, {}, kMs));
}

}  // namespace
