// The bubble history: a triangle that survives remeshing keeps its bubble velocity and its
// sensitivities whatever the order of its nodes; a new one starts from zero; a step without
// parameters stores no sensitivities; a checkpoint's round trip gives the same history.
#include "engine/solve/bubble_history.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace pfem {
namespace {

using Triangles = std::vector<std::array<std::int32_t, 3>>;

TEST(BubbleHistory, ASurvivingTriangleKeepsItsBubbleInAnyNodeOrder) {
  BubbleHistory h;
  const Triangles before{{0, 1, 2}, {2, 1, 3}};
  Eigen::VectorXd v(4);
  v << 1, 2, 3, 4;
  Eigen::MatrixXd dv(4, 2);
  dv << 10, 11, 20, 21, 30, 31, 40, 41;
  h.store(before, v, dv);
  // After remeshing: the second triangle again (its nodes rotated), a new one, the first
  // triangle with its orientation reversed.
  const Triangles after{{1, 3, 2}, {3, 4, 2}, {2, 1, 0}};
  std::vector<Eigen::Vector2d> velocity;
  std::vector<BubbleHistory::Sensitivity> sensitivity;
  h.restore(after, 2, velocity, sensitivity);
  ASSERT_EQ(velocity.size(), 3u);
  EXPECT_EQ(velocity[0], Eigen::Vector2d(3, 4));
  EXPECT_EQ(velocity[1], Eigen::Vector2d::Zero());
  EXPECT_EQ(velocity[2], Eigen::Vector2d(1, 2));
  ASSERT_EQ(sensitivity.size(), 3u);
  EXPECT_EQ(sensitivity[0], dv.middleRows<2>(2));
  EXPECT_EQ(sensitivity[1], BubbleHistory::Sensitivity::Zero(2, 2));
  EXPECT_EQ(sensitivity[2], dv.middleRows<2>(0));
  // Without parameters no sensitivities are asked for.
  h.restore(after, 0, velocity, sensitivity);
  EXPECT_TRUE(sensitivity.empty());
  EXPECT_EQ(velocity[0], Eigen::Vector2d(3, 4));
}

TEST(BubbleHistory, StoringReplacesTheLastStep) {
  BubbleHistory h;
  h.store(Triangles{{0, 1, 2}}, Eigen::Vector2d(1, 2), Eigen::MatrixXd());
  h.store(Triangles{{1, 2, 3}}, Eigen::Vector2d(5, 6), Eigen::MatrixXd());
  std::vector<Eigen::Vector2d> velocity;
  std::vector<BubbleHistory::Sensitivity> sensitivity;
  h.restore(Triangles{{0, 1, 2}, {1, 2, 3}}, 1, velocity, sensitivity);
  EXPECT_EQ(velocity[0], Eigen::Vector2d::Zero());  // not in the last step
  EXPECT_EQ(velocity[1], Eigen::Vector2d(5, 6));
  EXPECT_EQ(sensitivity[1], BubbleHistory::Sensitivity::Zero(2, 1));  // stored without any
}

TEST(BubbleHistory, ACheckpointRoundTripGivesTheSameHistory) {
  BubbleHistory h;
  const Triangles tris{{0, 1, 2}, {2, 1, 3}, {3, 4, 2}};
  Eigen::VectorXd v(6);
  v << 1, 2, 3, 4, 5, 6;
  Eigen::MatrixXd dv = Eigen::MatrixXd::Constant(6, 1, 0.5);
  dv(3, 0) = -7;
  h.store(tris, v, dv);
  StateArchive save = StateArchive::saving();
  h.archive(save);
  BubbleHistory restored;
  StateArchive load = StateArchive::restoring(save.bytes());
  restored.archive(load);
  EXPECT_TRUE(load.at_end());
  std::vector<Eigen::Vector2d> a, b;
  std::vector<BubbleHistory::Sensitivity> da, db;
  h.restore(tris, 1, a, da);
  restored.restore(tris, 1, b, db);
  EXPECT_EQ(a, b);
  EXPECT_EQ(da, db);
  EXPECT_EQ(b[1], Eigen::Vector2d(3, 4));
  EXPECT_EQ(db[1](1, 0), -7);
  // The saved bytes do not depend on the hash table: the same history stored again saves the same.
  BubbleHistory again;
  again.store(tris, v, dv);
  StateArchive save_again = StateArchive::saving();
  again.archive(save_again);
  EXPECT_EQ(save.bytes(), save_again.bytes());
}

}  // namespace
}  // namespace pfem
