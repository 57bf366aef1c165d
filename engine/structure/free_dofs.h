#pragma once
// Supports eliminated: the map from global dofs to the equations of the free dofs, and a
// sparse LU solve of a matrix delivered through the insertion callback (the structure alone
// is small, so the pattern is analysed at every solve).
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "engine/structure/structure_model.h"

namespace pfem::structure {

class FreeDofs {
 public:
  explicit FreeDofs(const StructureModel& model);

  int size() const { return static_cast<int>(free_.size()); }
  int equation(int dof) const { return equation_[dof]; }  // -1 for a supported dof
  Eigen::VectorXd restrict(const Eigen::VectorXd& global) const;
  // Global vector with the free entries from `reduced` and 0 on supported dofs.
  Eigen::VectorXd expand(const Eigen::VectorXd& reduced) const;

 private:
  std::vector<int> equation_;
  std::vector<int> free_;
};

// Solves A x = b on the free dofs; `fill` adds the entries of A (global numbering) to the
// callback it is given. Throws std::runtime_error if the factorisation fails (singular A).
Eigen::VectorXd solve_free(const FreeDofs& dofs, const std::function<void(const AddEntry&)>& fill,
                           const Eigen::VectorXd& b_reduced);

}  // namespace pfem::structure
