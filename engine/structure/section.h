#pragma once
// A beam cross-section: section deformations e = (eps0, kappa) -> resultants s = (N, M).
// Sign convention (as OpenSees): fiber strain eps(y) = eps0 - y*kappa, M = -sum sigma*y*A,
// so that M = EI*kappa for an elastic section. Same trial/commit protocol as the materials,
// and the same DDM protocol (uniaxial_material.h) with section deformations for strains.
#include <memory>

#include "engine/state/state_archive.h"

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
  // Saves or restores the mutable state (its fibers' included) for a checkpoint.
  virtual void archive(StateArchive& a) = 0;

  // --- DDM, parameters k = 0..P-1 ---
  // Sizes the sensitivity storage (history sensitivities 0; seeds kept).
  virtual void set_num_parameters(int P) = 0;
  // d(N, M)/dtheta_k with the trial deformation held fixed (committed history sensitivities).
  virtual Vec2 conditional_resultant_sensitivity(int k) const = 0;
  virtual Mat2 initial_tangent_sensitivity(int k) const = 0;
  virtual double area_sensitivity(int k) const = 0;
  // At the converged trial state, the total d(eps0, kappa)/dtheta_k: trial history sensitivities.
  virtual void set_deformation_sensitivity(int k, const Vec2& de) = 0;
};

}  // namespace pfem::structure
