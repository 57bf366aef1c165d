#pragma once
// A uniaxial stress-strain law with a trial state kept apart from the committed state.
//
// Protocol (the same for sections and elements): set_trial_strain() any number of times
// during the Newton iterations of a step, each time from the last committed state; commit()
// once the step has converged; revert_to_last_commit() to abandon the trial state.
// Objects are not shared: every fiber owns its clone. Not thread-safe per object; distinct
// objects are independent (no static state).
//
// Direct differentiation (DDM) w.r.t. parameters theta_k, k = 0..P-1, whose seeds the
// derived class holds (see seeds.h). Per step, after convergence: the conditional
// derivatives enter the global sensitivity equations, whose solution gives the total strain
// sensitivity; it goes to set_strain_sensitivity(), then commit() commits the history
// sensitivities together with the state.
#include <memory>
#include <vector>

#include "engine/state/state_archive.h"

namespace pfem::structure {

class UniaxialMaterial {
 public:
  virtual ~UniaxialMaterial() = default;

  virtual void set_trial_strain(double strain) = 0;
  virtual double strain() const = 0;
  virtual double stress() const = 0;
  // Consistent (algorithmic) tangent d(stress)/d(strain) at the trial state.
  virtual double tangent() const = 0;
  // Tangent of the virgin material (used by initial-stiffness Rayleigh damping).
  virtual double initial_tangent() const = 0;

  virtual void commit() = 0;
  virtual void revert_to_last_commit() = 0;
  virtual std::unique_ptr<UniaxialMaterial> clone() const = 0;
  // Saves or restores the mutable state (trial and committed, with the sensitivities) for a
  // checkpoint; derived classes add theirs to this one's.
  virtual void archive(StateArchive& a);

  // --- DDM ---
  // Sizes the sensitivity storage for P parameters; history sensitivities restart at 0.
  // Seeds are kept.
  virtual void set_num_parameters(int P);
  int num_parameters() const { return static_cast<int>(total_.size()); }
  // d(stress)/d(theta_k) with the trial strain held fixed: the trial state's return from the
  // committed history, differentiated with the committed history sensitivities.
  virtual double conditional_stress_sensitivity(int k) const = 0;
  virtual double initial_tangent_sensitivity(int k) const = 0;
  // At the converged trial state, the total d(strain)/d(theta_k): computes the trial history
  // sensitivities (committed by commit(), dropped by revert_to_last_commit()) and the total
  // stress sensitivity tangent() * dstrain + conditional_stress_sensitivity(k).
  void set_strain_sensitivity(int k, double dstrain);
  // Totals of the last set_strain_sensitivity(k, .) (for recorders).
  double strain_sensitivity(int k) const { return total_.at(k).strain; }
  double stress_sensitivity(int k) const { return total_.at(k).stress; }

 protected:
  // The trial history sensitivities for the total strain sensitivity dstrain.
  virtual void update_history_sensitivity(int k, double dstrain) = 0;

 private:
  struct Total {
    double strain = 0.0;
    double stress = 0.0;
  };
  std::vector<Total> total_;
};

}  // namespace pfem::structure
