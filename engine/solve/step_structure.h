#pragma once
// The structure in a step's Newton system (theory §4): its residual rows, its block of the
// Newton matrix and its rows of the DDM's right-hand side, in the step's unknowns
// (engine/solve/step_numbering.h).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "engine/solve/node_state.h"
#include "engine/solve/step_numbering.h"
#include "engine/structure/structure_model.h"

namespace pfem {

// The structure in the monolithic step: its nodes are nodes of the NodeState (kind Structure,
// boundary nodes of the fluid mesh) whose velocities are shared with the fluid; each also has a
// rotation rate. The structure adds F_ext - M ((v - v_n)/dt - g) - C v - Fs(u_n + dt v) to its rows
// and M/dt + C + dt dFs/du to the Newton matrix (theory §4).
struct StructureCoupling {
  structure::StructureModel* model = nullptr;
  std::vector<int> node;     // NodeState index of each structure node
  bool self_weight = true;  // gravity acts on its masses
};

class StepStructure {
 public:
  // The state at t_n from the structure's nodes (rotations included), and the rotation rates
  // there into the initial iterate v. num must outlive the step.
  void begin(const StructureCoupling& coupling, const StepNumbering& num, double dt, double gx, double gy,
             const NodeState& nodes, Eigen::VectorXd& v);
  // Adds its residual rows at the iterate v to rv, the model's trial state set there; returns
  // the magnitude of its forces (0 without a structure).
  double add_residual(const Eigen::VectorXd& v, Eigen::VectorXd& rv);
  // Entries of M/dt + C + dt dFs/du at its unknowns, at the trial state of the last residual.
  void add_tangent(const structure::AddEntry& put) const;
  // Those entries in the lower triangle.
  std::vector<Eigen::Triplet<double>> tangent_lower() const;
  // Its rows of the DDM's right-hand side for parameter k at the converged iterate v (the nodes
  // still at t_n with their sensitivities).
  Eigen::VectorXd sensitivity_rhs(const NodeState& nodes, int k, const Eigen::VectorXd& v) const;
  // The solved sensitivities of the step's unknowns (a column per parameter) to the rotations'
  // and rotation rates' sensitivities of the structure's nodes, and the nodes' displacement
  // sensitivities (translations already committed) to the model, before its commit.
  void commit_sensitivities(const Eigen::MatrixXd& dv, NodeState& nodes) const;

 private:
  Eigen::VectorXd velocities(const Eigen::VectorXd& v) const;  // per structure dof, at the iterate
  // (v - v_n)/dt - g at every structure dof (g at the translations; 0 without self-weight): M
  // times it is the inertia and the weight of the structure's masses.
  Eigen::VectorXd acceleration(const Eigen::VectorXd& vs) const;

  const StructureCoupling* coupling_ = nullptr;
  const StepNumbering* num_ = nullptr;
  double dt_ = 0.0, gx_ = 0.0, gy_ = 0.0;
  Eigen::VectorXd un_, vn_;  // displacements and velocities at t_n
};

}  // namespace pfem
