#pragma once
// A structural element of the 2D frame: two end nodes, 6 dofs (uxi, uyi, rzi, uxj, uyj, rzj).
//
// Protocol: set_trial_displacement() with the global end displacements of the current
// iterate (measured from the reference configuration, always from the last committed
// state), then read resisting_force() and tangent_stiffness() (the consistent tangent
// d(force)/d(u)); commit() after convergence, revert_to_last_commit() to abandon a step.
// mass_matrix() and initial_stiffness() are constant. No shared state between elements.
//
// DDM w.r.t. parameters theta_k, k = 0..P-1 (the protocol of uniaxial_material.h): the
// conditional force derivative at the trial displacement, and after convergence
// set_displacement_sensitivity() with the total du/dtheta_k, committed by commit().
#include <array>
#include <memory>

#include "engine/state/state_archive.h"

#include "engine/structure/types.h"

namespace pfem::structure {

class Element {
 public:
  virtual ~Element() = default;

  virtual std::array<int, 2> nodes() const = 0;
  virtual void set_trial_displacement(const Vec6& u) = 0;
  virtual const Vec6& resisting_force() const = 0;
  virtual const Mat6& tangent_stiffness() const = 0;
  virtual const Mat6& initial_stiffness() const = 0;  // tangent at u = 0, virgin materials
  virtual const Mat6& mass_matrix() const = 0;
  virtual bool has_lumped_mass() const = 0;  // mass_matrix() is diagonal

  virtual void commit() = 0;
  virtual void revert_to_last_commit() = 0;
  virtual std::unique_ptr<Element> clone() const = 0;
  // Saves or restores the mutable state (trial and committed, history and sensitivities) for a
  // checkpoint.
  virtual void archive(StateArchive& a) = 0;

  // --- DDM ---
  // Sizes the sensitivity storage (history sensitivities 0; seeds kept).
  virtual void set_num_parameters(int P) = 0;
  // d(resisting_force)/dtheta_k with the trial displacement held fixed.
  virtual Vec6 conditional_force_sensitivity(int k) const = 0;
  virtual Mat6 mass_sensitivity(int k) const = 0;               // dM/dtheta_k
  virtual Mat6 initial_stiffness_sensitivity(int k) const = 0;  // dK0/dtheta_k
  virtual void set_displacement_sensitivity(int k, const Vec6& du) = 0;
};

}  // namespace pfem::structure
