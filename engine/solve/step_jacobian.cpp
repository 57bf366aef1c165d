#include "engine/solve/step_jacobian.h"

#include "engine/solve/fluid_step.h"

namespace pfem {

void StepJacobian::assemble(const ConvergedStep& c) {
  const StepSettings& s = c.settings;
  const auto& mats = c.elements.matrices();
  const auto& geometries = c.elements.geometries();
  const int ne = static_cast<int>(c.mesh.triangles.size());
  geometric_.resize(ne);
  bubbles_.resize(ne);
  elements_.resize(ne);
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    if (s.geometric_terms) {
      fluid::geometric_derivatives(geometries[e], mats[e], s.fluid.mu, s.thickness, s.dt,
                                   c.elements.state(e, c.v, c.p), geometric_[e]);
    } else {
      geometric_[e].drv_dx.setZero();
      geometric_[e].drp_dx.setZero();
    }
    condense_element(mats[e], s.dt, &geometric_[e], bubbles_[e], elements_[e]);
  }
}

void StepJacobian::layout(const ConvergedStep& c) {
  // The LU takes the LDL^T's analysis, and each triangle's nine corner-pair blocks (both orders)
  // from the six the LDL^T has (a pair's reverse is the same place with the steps exchanged).
  const CondensedLayout& l = c.condensed.layout();
  const int ne = static_cast<int>(c.mesh.triangles.size());
  lu_.analyze_as(c.condensed.factor());
  blocks_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const auto& tri = c.mesh.triangles[e];
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const SupernodalLdlt::Block& b = l.element_blocks[e][p];
      const int a = kCornerPairs[p][0], cc = kCornerPairs[p][1];
      if (b.base < 0) {
        blocks_[e][3 * a + cc] = blocks_[e][3 * cc + a] = SupernodalLu::Block{-1, 0, 0, false};
        continue;
      }
      const int row0 = l.first_of_node[tri[a]], col0 = l.first_of_node[tri[cc]];
      blocks_[e][3 * a + cc] = lu_.block(row0, col0, b.base, b.row_step, b.col_step);
      if (a != cc) blocks_[e][3 * cc + a] = lu_.block(col0, row0, b.base, b.col_step, b.row_step);
    }
  }
}

void StepJacobian::factorize(const ConvergedStep& c) {
  // The elements' condensed blocks added straight into the LU's storage, as the Newton matrix's
  // are into the LDL^T's. The layout is redone at every factorisation: the analysis is this
  // step's (at most one factorisation a step).
  layout(c);
  const StepNumbering& num = c.num;
  const std::vector<int>& slot = c.condensed.layout().slot;
  lu_.zero_values();
  const int ne = static_cast<int>(c.mesh.triangles.size());
  for (int e = 0; e < ne; ++e) {
    const CondensedElement& k = elements_[e];
    const std::array<int, 9> u = num.condensed_unknowns(c.mesh.triangles[e], e);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const SupernodalLu::Block& blk = blocks_[e][3 * a + b];
        if (blk.base < 0) continue;
        double* values = lu_.values(blk.upper);
        for (const int r : {2 * a, 2 * a + 1, 6 + a}) {
          if (u[r] < 0) continue;
          const long row = blk.base + slot[u[r]] * blk.row_step;
          for (const int col : {2 * b, 2 * b + 1, 6 + b})
            if (u[col] >= 0) values[row + slot[u[col]] * blk.col_step] += k(r, col);
        }
      }
    if (num.has_rider(c.mesh.triangles[e]))
      put_rider_entries(num, c.mesh.triangles[e], e, k, [this](int row, int col, double value) {
        const SupernodalLu::Block blk = lu_.block(row, col);
        lu_.values(blk.upper)[blk.base] += value;
      });
  }
  const std::vector<long>& pressure_diagonal = c.condensed.layout().pressure_diagonal;
  for (int q = 0; q < num.pressures; ++q) {
    const int u = num.node_velocities + q;
    const SupernodalLu::Block blk = lu_.block(u, u, pressure_diagonal[q], 1, 1);
    lu_.values(blk.upper)[blk.base] -= c.residual.mp[q] / c.settings.dt;
  }
  c.structure.add_tangent([this](int row, int col, double value) {
    const SupernodalLu::Block blk = lu_.block(row, col);
    lu_.values(blk.upper)[blk.base] += value;
  });
  if (!lu_.factorize_values()) throw StepFailure("the Jacobian could not be factorised (non-finite pivot)");
}

Eigen::VectorXd StepJacobian::product(const ConvergedStep& c, const Eigen::VectorXd& x) const {
  return product(c, Eigen::MatrixXd(x));
}

Eigen::MatrixXd StepJacobian::product(const ConvergedStep& c, const Eigen::MatrixXd& x) const {
  // Element by element, each element's unknowns looked up once for all columns, a column at a
  // time through the fixed-size block (products with a dynamic number of columns cost more).
  const StepNumbering& num = c.num;
  Eigen::MatrixXd y = Eigen::MatrixXd::Zero(x.rows(), x.cols());
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const auto& tri = c.mesh.triangles[e];
    const std::array<int, 9> u = num.condensed_unknowns(tri, static_cast<int>(e));
    for (long k = 0; k < x.cols(); ++k) {
      Eigen::Matrix<double, 9, 1> xe;
      for (int col = 0; col < 9; ++col) xe(col) = u[col] >= 0 ? x(u[col], k) : 0.0;
      const Eigen::Matrix<double, 9, 1> ye = elements_[e].lazyProduct(xe);
      for (int r = 0; r < 9; ++r)
        if (u[r] >= 0) y(u[r], k) += ye(r);
    }
    if (num.has_rider(tri))
      put_rider_entries(num, tri, static_cast<int>(e), elements_[e],
                        [&](int row, int col, double value) { y.row(row) += value * x.row(col); });
  }
  for (int q = 0; q < num.pressures; ++q) {
    const int u = num.node_velocities + q;
    y.row(u) -= c.residual.mp[q] / c.settings.dt * x.row(u);
  }
  c.structure.add_tangent([&](int row, int col, double value) { y.row(row) += value * x.row(col); });
  return y;
}

}  // namespace pfem
