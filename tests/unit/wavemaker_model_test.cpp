// Wavemaker walls in a model file: bad motions and bad motion targets are reported with the
// exact field path and a clear message, and a valid one builds into a problem whose paddle
// nodes move (and only those).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

pfem::v1::Model piston_tank() { return read_model_file(std::string(PFEM_SOURCE_DIR) + "/tests/data/piston-tank.json"); }

std::string describe(const std::vector<FieldError>& errors) {
  std::string out;
  for (const auto& e : errors) out += "\n  " + e.to_string();
  return out.empty() ? " (none)" : out;
}

void expect_single_error(const pfem::v1::Model& model, const std::string& path, const std::string& fragment) {
  const auto errors = validate_model(model);
  ASSERT_EQ(errors.size(), 1u) << "errors:" << describe(errors);
  EXPECT_EQ(errors[0].path, path);
  EXPECT_NE(errors[0].message.find(fragment), std::string::npos)
      << "message '" << errors[0].message << "' lacks '" << fragment << "'";
}

// The paddle's motion, with the parameters on its sinusoid gone (another signal has not theirs).
pfem::v1::WallMotion* paddle_motion(pfem::v1::Model& m) {
  m.clear_parameters();
  return m.mutable_walls(1)->mutable_motion();
}

TEST(WavemakerModel, ThePistonTankIsValid) {
  const auto m = piston_tank();
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
}

TEST(WavemakerModel, ATableNotIncreasingInTime) {
  auto m = piston_tank();
  auto* table = paddle_motion(m)->mutable_table();  // replaces the sinusoid (a oneof)
  for (const double t : {0.0, 0.5, 0.5, 1.0}) table->add_t(t);
  for (const double s : {0.0, 0.01, 0.02, 0.0}) table->add_s(s);
  expect_single_error(m, "walls[1].motion.table.t[2]", "times must increase strictly");
}

TEST(WavemakerModel, ATableWithADisplacementMissing) {
  auto m = piston_tank();
  auto* table = paddle_motion(m)->mutable_table();
  for (const double t : {0.0, 0.5, 1.0}) table->add_t(t);
  for (const double s : {0.0, 0.01}) table->add_s(s);
  expect_single_error(m, "walls[1].motion.table.s", "needs one displacement per time (3), got 2");
}

TEST(WavemakerModel, AHingeOffTheWall) {
  auto m = piston_tank();
  auto* motion = paddle_motion(m);
  motion->set_kind("flap");
  motion->set_arm(0.1);
  motion->mutable_hinge()->set_x(0.05);  // the paddle is the line x = 0
  motion->mutable_hinge()->set_y(0.0);
  expect_single_error(m, "walls[1].motion.hinge", "must lie on the wall's line");
  motion->mutable_hinge()->set_x(0.0);
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
}

TEST(WavemakerModel, ASlipPistonIsValidASlipFlapIsNot) {
  auto m = piston_tank();
  m.mutable_walls(1)->set_slip(true);
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
  auto* motion = paddle_motion(m);
  motion->set_kind("flap");
  motion->set_arm(0.1);
  motion->mutable_hinge()->set_x(0.0);
  expect_single_error(m, "walls[1].slip", "a flap must be no-slip");
}

TEST(WavemakerModel, ASlipPistonsInnerNodesHaveTheirVerticalVelocityFree) {
  auto m = piston_tank();
  m.mutable_walls(1)->set_slip(true);
  const Problem pb = build_problem(m);
  ASSERT_EQ(pb.moving_walls.size(), 1u);
  int free_y = 0;
  for (const int i : pb.moving_walls[0].nodes) {
    const bool end = pb.nodes.y[i] == 0.0 || pb.nodes.y[i] == 0.2;
    EXPECT_EQ(pb.slip_of(i), end ? 0 : kSlipY) << "node at y = " << pb.nodes.y[i];
    free_y += pb.slip_of(i) == kSlipY;
  }
  EXPECT_EQ(free_y, 19);  // the ends (the foot on the floor, the top) are corners: v the paddle's
}

TEST(WavemakerModel, AMotionThatCarriesTheWallOutOfTheDomain) {
  auto m = piston_tank();
  // The domain (no `domain`: the walls' box grown by half its size) starts at x = -0.65.
  paddle_motion(m)->mutable_sinusoid()->set_stroke(2.0);
  expect_single_error(m, "walls[1].motion", "carries the wall's point (0, 0) out of the domain");
}

TEST(WavemakerModel, APistonThatLeavesTheFloorItStandsOn) {
  auto m = piston_tank();
  // The floor starts 0.1 m behind the paddle: a 0.4 m stroke swings its foot 0.2 m back.
  paddle_motion(m)->mutable_sinusoid()->set_stroke(0.4);
  expect_single_error(m, "walls[1].motion", "carries the wall's point (0, 0) off the wall 'tank' it stands on");
  paddle_motion(m)->mutable_sinusoid()->set_stroke(0.19);
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
}

TEST(WavemakerModel, ASignalIsRequiredAndItsConstantsArePositive) {
  auto m = piston_tank();
  paddle_motion(m)->mutable_sinusoid()->set_period(0.0);
  expect_single_error(m, "walls[1].motion.sinusoid.period", "must be a finite number > 0");
  paddle_motion(m)->clear_sinusoid();
  expect_single_error(m, "walls[1].motion", "needs a signal");
  auto* solitary = paddle_motion(m)->mutable_solitary();
  solitary->set_depth(0.1);
  solitary->set_height(0.07);
  expect_single_error(m, "walls[1].motion.solitary.height", "must be at most 0.6 depth");
  paddle_motion(m)->set_kind("rotor");
  solitary->set_height(0.03);
  expect_single_error(m, "walls[1].motion.kind", "must be \"piston\" or \"flap\"");
}

TEST(WavemakerModel, AParameterTargetingAWallWithoutMotion) {
  auto m = piston_tank();
  m.mutable_parameters(0)->set_targets(0, "wavemaker.tank.stroke");
  expect_single_error(m, "parameters[0].targets[0]", "no wall 'tank' with a motion");
}

TEST(WavemakerModel, AParameterTargetingWhatTheSignalHasNot) {
  auto m = piston_tank();
  m.mutable_parameters(0)->set_targets(0, "wavemaker.paddle.height");
  expect_single_error(m, "parameters[0].targets[0]", "has no height (a sinusoid: stroke or period)");
}

TEST(WavemakerModel, OnlyThePaddlesNodesMoveAndItsFootIsItsOwn) {
  const Problem pb = build_problem(piston_tank());
  ASSERT_EQ(pb.moving_walls.size(), 1u);
  const auto& moving = pb.moving_walls[0].nodes;
  ASSERT_EQ(moving.size(), 21u);  // 0.2 m at h = 0.01
  for (const int i : moving) EXPECT_DOUBLE_EQ(pb.nodes.x[i], 0.0);
  // The floor has its own node at the paddle's foot (0, 0): the foot slides off it.
  int floor_nodes_at_foot = 0;
  for (std::size_t i = 0; i < pb.nodes.size(); ++i)
    if (pb.nodes.kind[i] == mesh::NodeKind::Wall && pb.nodes.x[i] == 0.0 && pb.nodes.y[i] == 0.0 &&
        std::find(moving.begin(), moving.end(), static_cast<int>(i)) == moving.end())
      ++floor_nodes_at_foot;
  EXPECT_EQ(floor_nodes_at_foot, 1);
}

}  // namespace
}  // namespace pfem
