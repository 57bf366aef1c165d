#pragma once
// What the 2D beam-columns share: a coordinate transformation chosen per element, the
// global force/tangent from the basic system (v, q, kb), and the element mass.
//
// Mass: m = rho * A per unit length (A = the section area). Lumped (default): m L0 / 2 on
// each end translation, nothing on rotations; rotation-invariant, so exact under large
// rotations. Consistent: linear axial + cubic Hermitian transverse shape functions, built
// once in the reference orientation and kept constant (no dM/du term), which is exact for
// the Linear transformation and an approximation for large corotational rotations.
//
// DDM: the transformation does not depend on any parameter, so the conditional force
// derivative is B(u)^T dq/dtheta|v and the total basic deformation sensitivity dv = B(u) du.
// dm/dtheta = drho A + rho dA with the seed of rho in BeamOptions and dA from the section.
#include <array>
#include <memory>
#include <vector>

#include "engine/structure/crd_transf.h"
#include "engine/structure/element.h"
#include "engine/structure/seeds.h"

namespace pfem::structure {

enum class MassKind { kLumped, kConsistent };

struct BeamOptions {
  TransfKind transf = TransfKind::kLinear;
  MassKind mass = MassKind::kLumped;
  double rho = 0.0;         // mass density rho_s (>= 0, field "rho"); mass per length rho * A
  Seeds<double> rho_seeds;  // DDM: drho/dtheta_k
};

// Global 6x6 mass matrix of a straight beam with mass per unit length m (reference geometry).
Mat6 beam_mass_matrix(double m, const CrdTransf2d& transf, MassKind kind);

class BeamColumn2d : public Element {
 public:
  std::array<int, 2> nodes() const override { return nodes_; }
  void set_trial_displacement(const Vec6& u) override;
  const Vec6& resisting_force() const override { return force_; }
  const Mat6& tangent_stiffness() const override { return tangent_; }
  const Mat6& initial_stiffness() const override { return initial_stiffness_; }
  const Mat6& mass_matrix() const override { return mass_; }
  bool has_lumped_mass() const override { return options_.mass == MassKind::kLumped; }
  void commit() override;
  void revert_to_last_commit() override;
  void archive(StateArchive& a) override;

  void set_num_parameters(int P) override;
  Vec6 conditional_force_sensitivity(int k) const override;
  Mat6 mass_sensitivity(int k) const override;
  Mat6 initial_stiffness_sensitivity(int k) const override;
  void set_displacement_sensitivity(int k, const Vec6& du) override;
  // Total dq/dtheta_k from the last set_displacement_sensitivity(k, .) (for recorders).
  const Vec3& basic_force_sensitivity(int k) const { return basic_force_sens_.at(k); }

  const CrdTransf2d& transformation() const { return *transf_; }
  const Vec3& basic_deformation() const { return transf_->basic_deformation(); }
  const Vec3& basic_force() const { return q_; }
  const Mat3& basic_stiffness() const { return kb_; }
  const BeamOptions& options() const { return options_; }
  double mass_per_length() const { return mass_per_length_; }

 protected:
  BeamColumn2d(std::array<int, 2> nodes, const Vec2& xi, const Vec2& xj, const BeamOptions& o);
  BeamColumn2d(const BeamColumn2d& other);
  BeamColumn2d& operator=(const BeamColumn2d&) = delete;

  // To be called at the end of the derived constructor: mass, initial stiffness, state u = 0.
  void initialize(double section_area);

  // The basic system: q(v) and kb = dq/dv at the trial deformation v (trial material state).
  virtual void compute_basic(const Vec3& v, Vec3& q, Mat3& kb) = 0;
  virtual Mat3 initial_basic_stiffness() const = 0;
  virtual void commit_basic() = 0;
  virtual void revert_basic() = 0;
  // The basic system's own state (its sections') for archive().
  virtual void archive_basic(StateArchive& a) = 0;
  // DDM of the basic system: dq/dtheta_k at fixed v, dkb0/dtheta_k, dA/dtheta_k, and the total
  // dv/dtheta_k at the converged trial state (sets the sections' history sensitivities).
  virtual Vec3 conditional_basic_force_sensitivity(int k) const = 0;
  virtual Mat3 initial_basic_stiffness_sensitivity(int k) const = 0;
  virtual double section_area_sensitivity(int k) const = 0;
  virtual void set_basic_deformation_sensitivity(int k, const Vec3& dv) = 0;

  double length() const { return transf_->initial_length(); }

 private:
  std::array<int, 2> nodes_;
  BeamOptions options_;
  std::unique_ptr<CrdTransf2d> transf_;
  double section_area_ = 0.0;
  double mass_per_length_ = 0.0;
  Vec6 committed_u_ = Vec6::Zero();
  Vec3 q_ = Vec3::Zero();
  Mat3 kb_ = Mat3::Zero();
  Vec6 force_ = Vec6::Zero();
  Mat6 tangent_ = Mat6::Zero();
  Mat6 initial_stiffness_ = Mat6::Zero();
  Mat6 mass_ = Mat6::Zero();
  Vec6 trial_u_ = Vec6::Zero();
  std::vector<Vec3> basic_force_sens_;  // per parameter
};

}  // namespace pfem::structure
