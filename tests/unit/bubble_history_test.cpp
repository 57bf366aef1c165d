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
  Eigen::VectorXd velocity;
  Eigen::MatrixXd sensitivity;
  h.restore(after, 2, velocity, sensitivity);
  ASSERT_EQ(velocity.size(), 6);
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(0)), Eigen::Vector2d(3, 4));
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(2)), Eigen::Vector2d::Zero());
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(4)), Eigen::Vector2d(1, 2));
  ASSERT_EQ(sensitivity.rows(), 6);
  ASSERT_EQ(sensitivity.cols(), 2);
  EXPECT_EQ(Eigen::MatrixXd(sensitivity.middleRows<2>(0)), Eigen::MatrixXd(dv.middleRows<2>(2)));
  EXPECT_EQ(Eigen::MatrixXd(sensitivity.middleRows<2>(2)), Eigen::MatrixXd::Zero(2, 2));
  EXPECT_EQ(Eigen::MatrixXd(sensitivity.middleRows<2>(4)), Eigen::MatrixXd(dv.middleRows<2>(0)));
  // Without parameters no sensitivities are asked for.
  h.restore(after, 0, velocity, sensitivity);
  EXPECT_EQ(sensitivity.size(), 0);
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(0)), Eigen::Vector2d(3, 4));
}

TEST(BubbleHistory, StoringReplacesTheLastStep) {
  BubbleHistory h;
  h.store(Triangles{{0, 1, 2}}, Eigen::Vector2d(1, 2), Eigen::MatrixXd());
  h.store(Triangles{{1, 2, 3}}, Eigen::Vector2d(5, 6), Eigen::MatrixXd());
  Eigen::VectorXd velocity;
  Eigen::MatrixXd sensitivity;
  h.restore(Triangles{{0, 1, 2}, {1, 2, 3}}, 1, velocity, sensitivity);
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(0)), Eigen::Vector2d::Zero());  // not in the last step
  EXPECT_EQ(Eigen::Vector2d(velocity.segment<2>(2)), Eigen::Vector2d(5, 6));
  EXPECT_EQ(sensitivity, Eigen::MatrixXd::Zero(4, 1));  // stored without any
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
  Eigen::VectorXd a, b;
  Eigen::MatrixXd da, db;
  h.restore(tris, 1, a, da);
  restored.restore(tris, 1, b, db);
  EXPECT_EQ(a, b);
  EXPECT_EQ(da, db);
  EXPECT_EQ(Eigen::Vector2d(b.segment<2>(2)), Eigen::Vector2d(3, 4));
  EXPECT_EQ(db(3, 0), -7);
  // The saved bytes do not depend on the hash table: the same history stored again saves the same.
  BubbleHistory again;
  again.store(tris, v, dv);
  StateArchive save_again = StateArchive::saving();
  again.archive(save_again);
  EXPECT_EQ(save.bytes(), save_again.bytes());
}

}  // namespace
}  // namespace pfem
