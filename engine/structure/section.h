#pragma once
// A beam cross-section: section deformations e = (eps0, kappa) -> resultants s = (N, M).
// Sign convention (as OpenSees): fiber strain eps(y) = eps0 - y*kappa, M = -sum sigma*y*A,
// so that M = EI*kappa for an elastic section. Same trial/commit protocol as the materials.
#include <memory>

#include "engine/structure/types.h"

namespace pfem::structure {

class Section {
 public:
  virtual ~Section() = default;

  virtual void set_trial_deformation(const Vec2& e) = 0;
  virtual const Vec2& deformation() const = 0;
  virtual const Vec2& resultant() const = 0;  // (N, M)
  virtual const Mat2& tangent() const = 0;    // d(N, M)/d(eps0, kappa), consistent
  virtual Mat2 initial_tangent() const = 0;
  virtual double area() const = 0;  // for the mass per unit length rho_s * A

  virtual void commit() = 0;
  virtual void revert_to_last_commit() = 0;
  virtual std::unique_ptr<Section> clone() const = 0;
};

}  // namespace pfem::structure
