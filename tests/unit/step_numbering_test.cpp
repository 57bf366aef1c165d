// The step's unknowns: which nodes get velocity and pressure unknowns, in which
// order, a slip wall node's one free component, a structure node's velocities
// shared with the fluid, the bubbles after every node, and the element index
// maps built on them.
#include "engine/solve/step_numbering.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace pfem {
namespace {

using mesh::NodeKind;

struct Fixture {
  NodeState nodes;
  mesh::FluidMesh mesh;
  structure::StructureModel model;
  std::vector<std::uint8_t> slip;
  std::vector<int> structure_node{5, 6};
  Fixture() {
    // 0, 1 fluid; 2 a no-slip wall node; 3 and 4 slip wall nodes free in x and
    // in y; 5 and 6 structure nodes (5 supported); 7 a particle outside the
    // mesh; 8 a removed one.
    const NodeKind kinds[] = {
        NodeKind::Fluid,     NodeKind::Fluid, NodeKind::Wall,
        NodeKind::Wall,      NodeKind::Wall,  NodeKind::Structure,
        NodeKind::Structure, NodeKind::Fluid, NodeKind::Removed};
    for (int i = 0; i < 9; ++i)
      nodes.add(0.1 * i, 0.0, kinds[i]);
    mesh.triangles = {{0, 1, 2}, {1, 3, 4}, {0, 5, 6}};
    mesh.in_mesh = {1, 1, 1, 1, 1, 1, 1, 0, 0};
    slip = {0, 0, 0, kSlipX, kSlipY, 0, 0, 0, 0};
    model.add_node(0.5, 0.0);
    model.add_node(0.6, 0.0);
    model.fix(0, true, true, true);
  }
};

TEST(StepNumbering, NodesThenStructureThenBubbles) {
  Fixture f;
  const StepNumbering u =
      number_unknowns(f.mesh, f.nodes, f.slip, &f.model, f.structure_node);
  EXPECT_EQ(u.vx, (std::vector<int>{0, 2, -1, 4, -1, -1, 6, -1, -1}));
  EXPECT_EQ(u.vy, (std::vector<int>{1, 3, -1, -1, 5, -1, 7, -1, -1}));
  EXPECT_EQ(u.pressure_node, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(u.pressure_side, (std::vector<std::uint8_t>(7, 0)));
  EXPECT_EQ(u.corner_p,
            (std::vector<std::array<int, 3>>{{0, 1, 2}, {1, 3, 4}, {0, 5, 6}}));
  EXPECT_EQ(u.structure,
            (std::vector<int>{-1, -1, -1, 6, 7,
                              8})); // the free node's rotation rate: 8
  EXPECT_EQ(u.node_velocities, 9);
  EXPECT_EQ(u.velocities, 9 + 2 * 3);
  EXPECT_EQ(u.pressures, 7);
  EXPECT_EQ(u.bubble(1), 11);
  EXPECT_EQ(u.element_velocities(f.mesh.triangles[1], 1),
            (std::array<int, 8>{2, 3, 4, -1, -1, 5, 11, 12}));
  EXPECT_EQ(u.condensed_unknowns(f.mesh.triangles[2], 2),
            (std::array<int, 9>{0, 1, -1, -1, 6, 7, 9, 14, 15}));
}

TEST(StepNumbering, WithoutSlipOrStructure) {
  Fixture f;
  // No slip flags: every wall node is fixed; no structure model: its nodes have
  // no unknowns.
  const StepNumbering u = number_unknowns(f.mesh, f.nodes, {}, nullptr, {});
  EXPECT_EQ(u.vx, (std::vector<int>{0, 2, -1, -1, -1, -1, -1, -1, -1}));
  EXPECT_EQ(u.vy, (std::vector<int>{1, 3, -1, -1, -1, -1, -1, -1, -1}));
  EXPECT_TRUE(u.structure.empty());
  EXPECT_EQ(u.node_velocities, 4);
  EXPECT_EQ(u.velocities, 10);
  EXPECT_EQ(u.pressures, 7);
}

TEST(StepNumbering, OnePressurePerWetSideOfALine) {
  // Node 2 lies on a line with water on its sides 0 and 2 (triangles 0 and
  // 3), node 4 on side 1 only: node 2 gets two pressure unknowns, one after
  // the other, and node 4 one; each triangle's corner takes its side's.
  Fixture f;
  f.mesh.triangles.push_back({2, 1, 3});
  f.mesh.sides = {1, 1, 3, 1, 2, 1, 1, 1, 1};
  f.mesh.corner_side = {{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, {2, 0, 0}};
  const StepNumbering u = number_unknowns(f.mesh, f.nodes, {}, nullptr, {});
  EXPECT_EQ(u.pressures, 8);
  EXPECT_EQ(u.pressure_node, (std::vector<int>{0, 1, 2, 2, 3, 4, 5, 6}));
  EXPECT_EQ(u.pressure_side,
            (std::vector<std::uint8_t>{0, 0, 0, 2, 0, 1, 0, 0}));
  EXPECT_EQ(u.corner_p, (std::vector<std::array<int, 3>>{
                            {0, 1, 2}, {1, 4, 5}, {0, 6, 7}, {3, 1, 4}}));
  EXPECT_EQ(u.condensed_unknowns(f.mesh.triangles[3], 3),
            (std::array<int, 9>{-1, -1, 2, 3, -1, -1, 4 + 3, 4 + 1, 4 + 4}));
}

} // namespace
} // namespace pfem
