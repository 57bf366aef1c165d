#include "engine/solve/global_bubble_system.h"

#include <array>
#include <vector>

#include "engine/solve/fluid_step.h"

namespace pfem {

void GlobalBubbleSystem::begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
                               const StepStructure& structure) {
  mesh_ = &mesh, s_ = &s, num_ = &num, structure_ = &structure;
}

void GlobalBubbleSystem::factorize(const StepElements& elements, const Eigen::VectorXd& mp, bool analyze) {
  const StepNumbering& num = *num_;
  const auto& mats = elements.matrices();
  const int ne = static_cast<int>(mesh_->triangles.size());
  std::vector<Eigen::Triplet<double>> kt, gt;
  kt.reserve(64 * ne);
  gt.reserve(24 * ne);
  const double inv_dt = 1.0 / s_->dt;
  for (int e = 0; e < ne; ++e) {
    const auto& m = mats[e];
    const auto& tri = mesh_->triangles[e];
    // Each velocity row and column as its unknowns: a beam rider's are its segment ends' by
    // their weights (StepNumbering::velocity_terms), the bubble's its own.
    std::array<VelocityTerms, 8> t;
    for (int r = 0; r < 6; ++r) t[r] = num.velocity_terms(tri[r / 2], r % 2);
    t[6] = {{num.bubble(e), -1}, {1.0, 0.0}}, t[7] = {{num.bubble(e) + 1, -1}, {1.0, 0.0}};
    for (int r = 0; r < 8; ++r) {
      for (int c = 0; c < 8; ++c)
        put_term_pairs(t[r], t[c], m.M(r, c) * inv_dt + m.K(r, c),
                       [&kt](int row, int col, double value) { kt.emplace_back(row, col, value); });
      for (int i = 0; i < 2; ++i)
        for (int a = 0; t[r].u[i] >= 0 && a < 3; ++a) gt.emplace_back(t[r].u[i], num.corner_p[e][a], t[r].w[i] * m.G(r, a));
    }
  }
  structure_->add_tangent([&kt](int row, int col, double value) { kt.emplace_back(row, col, value); });
  SparseMatrix kvv(num.velocities, num.velocities);
  kvv.setFromTriplets(kt.begin(), kt.end());
  g_.resize(num.velocities, num.pressures);
  g_.setFromTriplets(gt.begin(), gt.end());
  factor_mp_ = mp;
  const Eigen::VectorXd d = s_->dt * mp.cwiseInverse();
  matrix_ = kvv + SparseMatrix(g_ * d.asDiagonal() * g_.transpose());
  if (analyze) solver_.analyze(matrix_);
  solver_.factorize(matrix_);
}

void GlobalBubbleSystem::solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const {
  const double dt = s_->dt;
  const Eigen::VectorXd dp_star = (dt * r.rp.array() / factor_mp_.array()).matrix();
  dv = solver_.solve(Eigen::VectorXd(r.rv + g_ * dp_star));
  dp = dp_star - (dt * (g_.transpose() * dv).array() / factor_mp_.array()).matrix();
}

}  // namespace pfem
