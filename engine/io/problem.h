#pragma once
// The engine's domain of one analysis, built from a pfem.v1.Model by engine/io/model_builder.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/fluid/mini_element.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/contact_line.h"
#include "engine/motion/wall_motion.h"
#include "engine/solve/node_state.h"
#include "engine/structure/structure_model.h"

namespace pfem {

struct Box {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  bool contains(double x, double y) const { return x >= xmin && x <= xmax && y >= ymin && y <= ymax; }
};

struct RecorderSpec {
  std::string name;
  std::string quantity;  // see model.proto Recorder
  int node = -1;         // node index for nodal quantities
  int element = -1;      // structure element for basic_force, fiber_stress, fiber_strain
  int component = 0;     // basic force: 0 = N, 1 = M_i, 2 = M_j
  int section_point = 0;  // fiber quantities: integration point and fiber (0 at the -y face)
  int fiber = 0;
  double x = 0.0, y = 0.0;  // the point of a point quantity (pressure, wave_gauge), of a moment
  std::vector<std::array<std::int32_t, 2>> pieces;  // force_x, force_y, moment: the boundary's node pairs
};

struct ParameterSpec {
  std::string name;
  std::vector<std::string> targets;  // empty for a directional parameter
  double value = 0.0;                // 0 for a directional parameter (its offset s)
  // A directional parameter (model.proto, Parameter.direction): the parameters it weighs.
  std::vector<std::pair<std::string, double>> direction;
};

struct Problem {
  fluid::FluidConstants fluid;
  double thickness = 1.0;
  double gx = 0.0, gy = -9.81;
  double h = 0.0, alpha = 1.2;
  // Alpha for triangles of three nodes on the previous mesh's boundary (mesh::RemeshOptions).
  double boundary_alpha = 0.9;
  double removal_distance = 0.2;  // relative to h
  double insertion_length = 1.6;  // relative to h, edges with an end on the free surface
  double interior_insertion_length = 2.0;  // relative to h, edges inside the water
  double volume_relaxation_steps = 10.0;  // mesh.volume_relaxation_steps (0: no volume correction)
  double dt = 0.0, t_end = 0.0;
  double newton_tolerance = 1e-10;
  int newton_max_iterations = 50;
  bool unified_fractional_step = false;  // analysis.solver
  bool incompressible = false;           // analysis.formulation (engine/solve/step_solver.h)
  int record_every = 1;
  int vtk_every = 10;
  Box domain;
  bool fail_on_exit = false;  // domain.on_exit == "fail"
  NodeState nodes;
  std::vector<std::array<std::int32_t, 2>> wall_segments;  // node pairs of every wall piece
  // Wall nodes that slide to the contact line (mesh/contact_line.h), and per node the indices
  // into it of the sliding nodes at and next to it (empty for other nodes).
  std::vector<mesh::SlidingWallNode> sliding_walls;
  // Per node: 0, or the one free velocity component of a slip wall's node (StepSettings::slip).
  std::vector<std::uint8_t> wall_slip;
  std::uint8_t slip_of(std::size_t i) const { return i < wall_slip.size() ? wall_slip[i] : 0; }
  std::vector<std::vector<int>> wall_neighbours;
  // Walls with a prescribed motion (wavemakers), and per sliding wall node the index of its
  // moving wall (-1: a fixed wall).
  std::vector<motion::WallMotion> moving_walls;
  std::vector<int> sliding_motion;
  std::vector<std::array<std::int32_t, 2>> beam_segments;  // node pairs of every beam element
  std::optional<structure::StructureModel> structure;     // with its nodes in `nodes`:
  std::vector<int> structure_nodes;                        // node index of each structure node
  bool structure_self_weight = true;                       // structure.self_weight
  std::vector<RecorderSpec> recorders;
  std::vector<ParameterSpec> parameters;
  // DDM: the parameters differentiated, in order, and how each moves the fluid constants (the
  // structure holds its own seeds; nodes carry the sensitivity storage).
  std::vector<std::string> sensitivity_params;
  std::vector<fluid::FluidSeed> fluid_seeds;
};

}  // namespace pfem
