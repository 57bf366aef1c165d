#pragma once
// A uniaxial stress-strain law with a trial state kept apart from the committed state.
//
// Protocol (the same for sections and elements): set_trial_strain() any number of times
// during the Newton iterations of a step, each time from the last committed state; commit()
// once the step has converged; revert_to_last_commit() to abandon the trial state.
// Objects are not shared: every fiber owns its clone. Not thread-safe per object; distinct
// objects are independent (no static state).
#include <memory>

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
};

}  // namespace pfem::structure
