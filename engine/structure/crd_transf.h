#pragma once
// Coordinate transformation of a 2D beam: global end displacements u (6) <-> basic
// deformations v = (axial elongation, rotation at i, rotation at j; the rotations relative
// to the chord) and basic forces q = (N, Mi, Mj) <-> global end forces.
//
//   F_global = B^T q,   K_global = B^T kb B + sum_k q_k d2v_k/du2   (B = dv/du)
//
// The second term (geometric stiffness) is zero for Linear and complete for Corotational,
// so that K_global is the consistent tangent of F_global in both cases.
#include <memory>

#include "engine/state/state_archive.h"

#include "engine/structure/types.h"

namespace pfem::structure {

enum class TransfKind { kLinear, kCorotational };

class CrdTransf2d {
 public:
  // Reference end coordinates; throws std::invalid_argument (field "length") for a
  // zero-length beam.
  CrdTransf2d(const Vec2& xi, const Vec2& xj);
  virtual ~CrdTransf2d() = default;

  virtual TransfKind kind() const = 0;
  // Sets the trial global end displacements (uxi, uyi, rzi, uxj, uyj, rzj).
  virtual void update(const Vec6& u) = 0;
  virtual const Vec3& basic_deformation() const = 0;
  // B = dv/du at the trial displacement (the DDM maps du/dtheta to dv/dtheta with it).
  virtual const Mat36& basic_matrix() const = 0;
  virtual Vec6 global_force(const Vec3& q) const = 0;
  virtual Mat6 global_stiffness(const Mat3& kb, const Vec3& q) const = 0;
  virtual std::unique_ptr<CrdTransf2d> clone() const = 0;
  // Saves or restores the state of the last update() for a checkpoint.
  virtual void archive(StateArchive& a) = 0;

  double initial_length() const { return L0_; }
  double initial_cos() const { return c0_; }
  double initial_sin() const { return s0_; }
  // B = dv/du at the reference configuration (the same for every kind).
  Mat36 reference_basic_matrix() const;
  // Rotation T of the reference orientation: local end vector = T * global end vector.
  Mat6 reference_rotation() const;

 protected:
  double L0_ = 0.0;
  double c0_ = 1.0;  // reference chord direction
  double s0_ = 0.0;
};

std::unique_ptr<CrdTransf2d> make_crd_transf(TransfKind kind, const Vec2& xi, const Vec2& xj);

}  // namespace pfem::structure
