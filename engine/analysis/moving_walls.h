#pragma once
// The wavemakers' walls in the time loop (engine/motion): the velocities a step prescribes at
// their nodes, the nodes placed where the motion has them, and the sliding wall nodes carried
// with their walls. Positions are set from the motion at every step's end, so they never drift;
// the velocity over a step is the mean one, (x(t1) - x(t0)) / (t1 - t0), so that the step's
// x_n + dt v lands there too. The DDM gets the derivatives of both along every parameter.
#include <array>
#include <vector>

#include "engine/io/problem.h"

namespace pfem {

struct WallKinematics {
  std::vector<double> velocity;     // per node: x, y (StepSettings::wall_velocity); empty: no moving wall
  std::vector<double> sensitivity;  // per node and parameter: x, y
};

// The velocities over [t0, t1] of every moving wall's node and their sensitivities.
WallKinematics wall_kinematics(const Problem& problem, const NodeState& nodes, double t0, double t1);

// Puts every moving wall's node where its motion has it at t, with its position sensitivities,
// and gives it the velocity of the step that ended there (`step`; none: 0); a slip node's free
// component (along the wall) is the water's and stays, as on a fixed slip wall.
void place_moving_walls(const Problem& problem, double t, const WallKinematics& step, NodeState& nodes);

// The sliding wall nodes at time t (mesh/contact_line.h): a moving wall's home and tangent carried
// with the wall; per sliding node and parameter, the derivatives of (home_x, home_y, tx, ty).
// The triangulation's node kinds and constraints with the floor under a paddle cleared: a fixed
// wall node inside a straight piece (two constraints) closer than h/2 to a moving wall's node is
// left out, and its two pieces are joined into one. Otherwise a piston sliding over the floor's
// nodes makes a sliver with each as it passes (a needle with a prescribed and a free corner that
// Newton cannot converge on). A left-out node is in no triangle; its place and velocity stay.
void clear_under_moving_walls(const Problem& problem, const NodeState& nodes, std::vector<mesh::NodeKind>& kind,
                              std::vector<std::array<std::int32_t, 2>>& constraints);

std::vector<mesh::SlidingWallNode> sliding_walls_at(const Problem& problem, int num_params, double t,
                                                    std::vector<std::array<double, 4>>& sensitivities);

}  // namespace pfem
