#include "engine/structure/free_dofs.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <stdexcept>

namespace pfem::structure {

FreeDofs::FreeDofs(const StructureModel& model) : equation_(model.num_dofs(), -1) {
  for (int dof = 0; dof < model.num_dofs(); ++dof) {
    if (model.is_fixed(dof)) continue;
    equation_[dof] = static_cast<int>(free_.size());
    free_.push_back(dof);
  }
}

Eigen::VectorXd FreeDofs::restrict(const Eigen::VectorXd& global) const {
  Eigen::VectorXd r(size());
  for (int i = 0; i < size(); ++i) r(i) = global(free_[i]);
  return r;
}

Eigen::VectorXd FreeDofs::expand(const Eigen::VectorXd& reduced) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(equation_.size()));
  for (int i = 0; i < size(); ++i) g(free_[i]) = reduced(i);
  return g;
}

Eigen::VectorXd solve_free(const FreeDofs& dofs, const std::function<void(const AddEntry&)>& fill,
                           const Eigen::VectorXd& b_reduced) {
  std::vector<Eigen::Triplet<double>> entries;
  fill([&](int i, int j, double value) {
    const int r = dofs.equation(i);
    const int c = dofs.equation(j);
    if (r >= 0 && c >= 0) entries.emplace_back(r, c, value);
  });
  Eigen::SparseMatrix<double> A(dofs.size(), dofs.size());
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success)
    throw std::runtime_error("structure solve: singular tangent (" + lu.lastErrorMessage() + ")");
  return lu.solve(b_reduced);
}

}  // namespace pfem::structure
