#pragma once
// The structure as one object: nodes and elements, and at a trial displacement vector u
// (3 per node, global dof 3*node + k) the quantities the monolithic solve needs:
//
//   Fs_int(u)      resisting_force()
//   dFs/du         add_tangent(add, factor)       consistent (geometric + algorithmic)
//   M              add_mass(add, factor), mass_times(), lumped_mass()   constant
//   C = a0 M + a1 K0   add_damping(add, factor), damping_times()        constant
//   F_ext          external_load()                 nodal loads (dead loads)
//
// Rayleigh damping uses K0, the INITIAL stiffness (reference geometry, virgin materials):
// C is then constant and symmetric, gives no spurious damping forces when fibers yield, and
// the velocity-based residual r = F_ext - M (v - v_n)/dt - C v - Fs_int(u) has the exact
// tangent M/dt + C + dt dFs/du.
//
// Direct differentiation (DDM) w.r.t. parameters theta_k, k = 0..P-1, whose seeds the
// elements, sections and materials hold (set before they are added; see seeds.h). Per step,
// after convergence: resisting_force_sensitivity(), mass_sensitivity_times() and
// damping_sensitivity_times() enter the right-hand side of the sensitivity equations; the
// solved du/dtheta_k goes to set_displacement_sensitivity(), then commit() commits the
// history sensitivities with the state. Nodal masses and loads are not parameters.
//
// Ownership: the model owns its elements. Thread-safety: one model per job; no shared state.
// Supports are reported by is_fixed(); the model does not eliminate them (the caller does).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "engine/structure/beam_column.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/element.h"
#include "engine/structure/node.h"
#include "engine/structure/section.h"

namespace pfem::structure {

struct RayleighDamping {
  double a0 = 0.0;  // mass-proportional coefficient [1/s]
  double a1 = 0.0;  // stiffness-proportional coefficient [s], on the initial stiffness
};

class StructureModel {
 public:
  StructureModel() = default;
  StructureModel(StructureModel&&) = default;
  StructureModel& operator=(StructureModel&&) = default;
  StructureModel(const StructureModel& other);  // deep copy (elements cloned)
  StructureModel& operator=(const StructureModel&) = delete;

  // --- building (validation errors: std::invalid_argument) ---
  int add_node(double x, double y);  // returns the node index
  void fix(int node, bool ux, bool uy, bool rz);
  void add_nodal_mass(int node, double mx, double my, double mrz = 0.0);
  void add_nodal_load(int node, double fx, double fy, double mz = 0.0);
  void set_nodal_load(int node, double fx, double fy, double mz = 0.0);
  // Takes an element whose nodes() exist; returns its index.
  int add_element(std::unique_ptr<Element> element);
  // Conveniences that look the reference coordinates up from the nodes.
  int add_elastic_beam(int i, int j, const ElasticSectionProperties& section,
                       const BeamOptions& options = {},
                       const Seeds<ElasticSectionProperties>& section_seeds = {});
  int add_disp_beam(int i, int j, const Section& section, const BeamOptions& options = {},
                    int integration_points = 2);
  void set_rayleigh(const RayleighDamping& damping);

  // --- queries ---
  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  int num_dofs() const { return kDofsPerNode * num_nodes(); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  const Node& node(int n) const { return nodes_.at(n); }
  const Element& element(int e) const { return *elements_.at(e); }
  bool is_fixed(int dof) const { return nodes_[dof / kDofsPerNode].fixed[dof % kDofsPerNode]; }
  const RayleighDamping& rayleigh() const { return damping_; }

  // --- state ---
  // Sets the trial displacement of every dof (size num_dofs(); fixed dofs should hold 0).
  void set_trial_displacement(const Eigen::VectorXd& u);
  const Eigen::VectorXd& trial_displacement() const { return u_trial_; }
  const Eigen::VectorXd& committed_displacement() const { return u_committed_; }
  void commit();
  void revert_to_last_commit();
  // Saves or restores every mutable state (displacements, every element's trial and committed
  // state, history and sensitivities) for a checkpoint.
  void archive(StateArchive& a);

  // --- at the trial state ---
  Eigen::VectorXd resisting_force() const;
  void add_tangent(const AddEntry& add, double factor = 1.0) const;
  // --- constant ---
  void add_mass(const AddEntry& add, double factor = 1.0) const;
  void add_initial_stiffness(const AddEntry& add, double factor = 1.0) const;
  void add_damping(const AddEntry& add, double factor = 1.0) const;
  Eigen::VectorXd mass_times(const Eigen::VectorXd& a) const;     // M a
  Eigen::VectorXd damping_times(const Eigen::VectorXd& v) const;  // C v
  bool mass_is_lumped() const;          // every element lumped: M is diagonal
  Eigen::VectorXd lumped_mass() const;  // the diagonal of M; throws std::logic_error if not lumped
  Eigen::VectorXd external_load() const;

  // --- DDM ---
  // Sizes every object's sensitivity storage for P parameters (history sensitivities 0).
  void set_num_parameters(int P);
  int num_parameters() const { return num_parameters_; }
  // dFs_int/dtheta_k at the trial displacement held fixed, with the committed history
  // sensitivities (size num_dofs()).
  Eigen::VectorXd resisting_force_sensitivity(int k) const;
  Eigen::VectorXd mass_sensitivity_times(int k, const Eigen::VectorXd& a) const;     // dM a
  Eigen::VectorXd damping_sensitivity_times(int k, const Eigen::VectorXd& v) const;  // dC v
  // At the converged trial state, the total du/dtheta_k of every dof: the trial history
  // sensitivities (and the recorders' totals). commit() commits them, revert drops them.
  void set_displacement_sensitivity(int k, const Eigen::VectorXd& du);

 private:
  Vec6 gather(const Eigen::VectorXd& u, const Element& e) const;
  // out += the element vectors f(element, element part of x), scattered to global dofs.
  template <typename F>
  void add_element_vectors(const Eigen::VectorXd& x, F&& f, Eigen::VectorXd& out) const;
  void check_vector(const Eigen::VectorXd& x, const char* what) const;
  void check_parameter(int k) const;
  void check_node(int n, const char* what) const;

  std::vector<Node> nodes_;
  std::vector<std::unique_ptr<Element>> elements_;
  RayleighDamping damping_;
  int num_parameters_ = 0;
  Eigen::VectorXd u_trial_;
  Eigen::VectorXd u_committed_;
};

}  // namespace pfem::structure
