#pragma once
// The unknowns of one PFEM step and where each node's velocities and pressure
// sit among them (engine/solve/fluid_step.h). Velocity unknowns come first: the
// free nodes' x and y, a slip wall node's free component, the structure's free
// dofs (a structure node's x and y velocity unknowns are the fluid's at that
// node, its rotation rate its own), then two bubble unknowns per triangle (a
// beam rider has none: its velocity is its beam segment's, StepRider);
// pressures are numbered apart, one at every mesh node (free surface included) and one per wet
// side at a node of wall or beam lines (mesh::FluidMesh::sides), node by node.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/structure/structure_model.h"

namespace pfem {

// A beam rider (mesh::LineRider, engine/mesh/beam_riders.h): a node on the beam
// segment from node a to node b, at a + s (b - a), whose velocity is the
// segment's there, (1 - s) v_a + s v_b. It has no velocity unknowns: its
// velocity rows go to a's and b's by the same weights (the water's force on it
// is the beam's), and its sensitivity follows s's (s is the level of a particle,
// set when the step began).
struct StepRider {
  int node = -1, a = -1, b = -1;
  double s = 0.0;
  std::vector<double> ds; // per parameter
};

// The unknowns a velocity component is made of and their weights (-1: none).
struct VelocityTerms {
  std::array<int, 2> u{-1, -1};
  std::array<double, 2> w{0.0, 0.0};
};

struct StepNumbering {
  std::vector<int> vx,
      vy; // per node: its x, y velocity unknown or -1 (fixed, not in the mesh)
  std::vector<std::array<int, 3>> corner_p; // per triangle: its corners' pressure unknowns
  std::vector<int> pressure_node;           // per pressure unknown: its node ...
  std::vector<std::uint8_t> pressure_side;  // ... and the side of it
  std::vector<int>
      structure; // per structure dof (3 per structure node): its unknown or -1
  std::vector<int> rider;        // per node: its index in riders, or -1
  std::vector<StepRider> riders; // the step's beam riders
  int node_velocities =
      0;              // velocity unknowns of the nodes (bubbles follow them)
  int velocities = 0; // ... and the bubbles'
  int pressures = 0;

  bool is_rider(int i) const { return !rider.empty() && rider[i] >= 0; }
  // Node i's velocity component c (0: x, 1: y) in the unknowns: its own (weight
  // 1), a rider's segment ends' (1 - s and s; -1 for a supported end, which
  // does not move); none for a node whose velocity is prescribed.
  VelocityTerms velocity_terms(int i, int c) const {
    const std::vector<int> &own = c == 0 ? vx : vy;
    if (own[i] >= 0 || !is_rider(i))
      return {{own[i], -1}, {own[i] >= 0 ? 1.0 : 0.0, 0.0}};
    const StepRider &r = riders[rider[i]];
    return {{own[r.a], own[r.b]}, {1.0 - r.s, r.s}};
  }
  // Node i's velocity component c in x (its terms' weighted sum; 0 where it has none), and
  // value added to its terms in y by their weights (a rider's row shared out to its ends).
  double velocity_in(int i, int c,
                     const Eigen::Ref<const Eigen::VectorXd> &x) const {
    const VelocityTerms t = velocity_terms(i, c);
    double sum = 0.0;
    for (int j = 0; j < 2; ++j)
      if (t.u[j] >= 0)
        sum += t.w[j] * x[t.u[j]];
    return sum;
  }
  void add_to_velocity(int i, int c, double value,
                       Eigen::Ref<Eigen::VectorXd> y) const {
    add_to_terms(velocity_terms(i, c), value, y);
  }
  // The same for terms already looked up.
  static void add_to_terms(const VelocityTerms &t, double value,
                           Eigen::Ref<Eigen::VectorXd> y) {
    for (int j = 0; j < 2; ++j)
      if (t.u[j] >= 0)
        y[t.u[j]] += t.w[j] * value;
  }
  // Whether a corner of the triangle is a rider (its velocity rows and columns
  // are then its ends', condensed_terms).
  bool has_rider(const std::array<std::int32_t, 3> &tri) const;
  // condensed_unknowns with each velocity as its terms (a pressure: its unknown,
  // weight 1).
  std::array<VelocityTerms, 9>
  condensed_terms(const std::array<std::int32_t, 3> &tri, int e) const;

  // The first of triangle e's two bubble unknowns.
  int bubble(int e) const { return node_velocities + 2 * e; }
  // A triangle's velocity unknowns: x, y of each corner (-1 where fixed), then
  // its bubble's.
  std::array<int, 8> element_velocities(const std::array<std::int32_t, 3> &tri,
                                        int e) const;
  // A triangle's unknowns in the condensed system (bubbles eliminated): corner
  // velocities x0 y0 x1 y1 x2 y2, then the corner pressures, numbered after the
  // node velocities.
  std::array<int, 9>
  condensed_unknowns(const std::array<std::int32_t, 3> &tri, int e) const;
};

// put(row, col, w_row w_col value) for each pair of the unknowns of two velocities: an element
// matrix entry between them, where a beam rider's is shared out to its segment's ends by their
// weights.
template <class Put>
void put_term_pairs(const VelocityTerms &row, const VelocityTerms &col,
                    double value, Put &&put) {
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      if (row.u[i] >= 0 && col.u[j] >= 0)
        put(row.u[i], col.u[j], row.w[i] * col.w[j] * value);
}

// slip: per node (empty: none), kSlipX or kSlipY for a slip wall's node;
// structure_node: the NodeState index of each structure node (model null: no
// structure); riders: the beam riders (structure nodes not in structure_node).
StepNumbering number_unknowns(const mesh::FluidMesh &mesh,
                              const NodeState &nodes,
                              std::span<const std::uint8_t> slip,
                              const structure::StructureModel *model,
                              std::span<const int> structure_node,
                              std::span<const StepRider> riders = {});

// The state at t_n in a step's unknowns: each node's velocities into its
// velocity unknowns of v (the rest of v untouched), and the pressure of each
// pressure unknown (a side that had no water yet takes its node's p,
// NodeState::pressure).
void gather_velocities(const StepNumbering &num, const NodeState &nodes,
                       Eigen::VectorXd &v);
Eigen::VectorXd gather_pressures(const StepNumbering &num,
                                 const mesh::FluidMesh &mesh,
                                 const NodeState &nodes);

} // namespace pfem
