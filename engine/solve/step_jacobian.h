#pragma once
// The exact Jacobian of a converged step for the DDM (theory §5; step_sensitivity.h), element by
// element: dt H and dt T (zero without geometric terms) condensed like the Newton matrix
// (bubble_condensation.h), with the structure's consistent tangent; its product with a vector,
// and its supernodal LU on the Newton matrix's analysis (supernodal_lu.h).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/fluid/mini_sensitivity.h"
#include "engine/solve/bubble_condensation.h"
#include "engine/solve/converged_step.h"
#include "engine/solve/supernodal_lu.h"

namespace pfem {

class StepJacobian {
 public:
  // Every element's geometric derivatives, condensation and condensed block at the iterate.
  void assemble(const ConvergedStep& c);
  // Those blocks and the structure's tangent into the LU, on the condensed system's analysis,
  // factorised; throws StepFailure on a non-finite pivot.
  void factorize(const ConvergedStep& c);
  // The Jacobian's product with x (condensed unknowns), or with each column of x.
  Eigen::VectorXd product(const ConvergedStep& c, const Eigen::VectorXd& x) const;
  Eigen::MatrixXd product(const ConvergedStep& c, const Eigen::MatrixXd& x) const;
  const SupernodalLu& lu() const { return lu_; }
  const std::vector<fluid::GeometricDerivatives>& geometric() const { return geometric_; }
  const std::vector<BubbleCondensation>& bubbles() const { return bubbles_; }

 private:
  // The LU's analysis (the LDL^T's) and where each triangle's blocks go in it.
  void layout(const ConvergedStep& c);

  std::vector<fluid::GeometricDerivatives> geometric_;
  std::vector<BubbleCondensation> bubbles_;
  std::vector<CondensedElement> elements_;
  SupernodalLu lu_;
  std::vector<std::array<SupernodalLu::Block, 9>> blocks_;
};

}  // namespace pfem
