#include "engine/solve/condensed_bubble_system.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "engine/solve/fluid_step.h"

namespace pfem {

namespace {
constexpr double kStructureTangentChange = 1e-3;  // see refresh_structure
}  // namespace

void CondensedBubbleSystem::begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
                                  const StepStructure& structure) {
  mesh_ = &mesh, s_ = &s, num_ = &num, structure_ = &structure;
  analyzed_ = false;
}

void CondensedBubbleSystem::analyze() {
  const mesh::FluidMesh& mesh = *mesh_;
  const StepSettings& s = *s_;
  const StepNumbering& num = *num_;
  // The unknowns of a node (velocities, pressure, a structure node's rotation) as one group,
  // coupled to the nodes it shares a triangle or a beam element with.
  const int n = num.node_velocities + num.pressures;
  std::vector<int> node_of(n, -1), structure_unknowns;
  for (std::size_t i = 0; i < num.vx.size(); ++i) {
    if (num.vx[i] >= 0) node_of[num.vx[i]] = static_cast<int>(i);
    if (num.vy[i] >= 0) node_of[num.vy[i]] = static_cast<int>(i);
  }
  for (int q = 0; q < num.pressures; ++q) node_of[num.node_velocities + q] = num.pressure_node[q];
  for (std::size_t j = 0; j < num.structure.size(); ++j)
    if (const int d = num.structure[j]; d >= 0) node_of[d] = s.structure.node[j / 3], structure_unknowns.push_back(d);
  std::vector<std::array<int, 2>> couplings;
  couplings.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    couplings.push_back({tri[0], tri[1]}), couplings.push_back({tri[1], tri[2]}), couplings.push_back({tri[2], tri[0]});
    // A rider's velocity rows and columns are its segment ends': they couple to its triangles.
    for (const std::int32_t i : tri)
      if (num.is_rider(i))
        for (const int end : {num.riders[num.rider[i]].a, num.riders[num.rider[i]].b})
          for (const std::int32_t corner : tri) couplings.push_back({end, corner});
  }
  if (const auto* model = s.structure.model)
    for (int e = 0; e < model->num_elements(); ++e) {
      const auto [i, j] = model->element(e).nodes();
      couplings.push_back({s.structure.node[i], s.structure.node[j]});
    }
  factor_.analyze(n, node_of, couplings, structure_unknowns);

  // Each unknown's rank among its node's unknowns, the first unknown of each node, and where
  // each triangle's blocks and each pressure's diagonal go in the factor.
  CondensedLayout& l = layout_;
  l.slot.resize(n);
  std::vector<int> first(num.vx.size(), -1), count(num.vx.size(), 0);
  for (int u = 0; u < n; ++u) {
    const int i = node_of[u];
    if (first[i] < 0) first[i] = u;
    l.slot[u] = count[i]++;
  }
  const int ne = static_cast<int>(mesh.triangles.size());
  l.element_blocks.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const auto& tri = mesh.triangles[e];
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const int row0 = first[tri[kCornerPairs[p][0]]], col0 = first[tri[kCornerPairs[p][1]]];
      l.element_blocks[e][p] = row0 >= 0 && col0 >= 0 ? factor_.block(row0, col0) : SupernodalLdlt::Block{-1, 0, 0};
    }
  }
  l.pressure_diagonal.resize(num.pressures);
  for (int q = 0; q < num.pressures; ++q) {
    const int u = num.node_velocities + q;
    l.pressure_diagonal[q] = factor_.block(u, u).base;
  }
  analyzed_ = true;
  l.first_of_node = std::move(first);
}

void CondensedBubbleSystem::factorize(const StepElements& elements, const Eigen::VectorXd& mp, bool analyze) {
  // The symmetric matrix is added straight into the factor's storage, a triangle's blocks at
  // the places found by the analysis: no triplets to sort, no matrix to build.
  const StepNumbering& num = *num_;
  const auto& mats = elements.matrices();
  if (analyze) this->analyze();
  factor_.zero_values();
  double* lx = factor_.values();
  const int ne = static_cast<int>(mesh_->triangles.size());
  bubbles_.resize(ne);
  CondensedElement k;
  for (int e = 0; e < ne; ++e) {
    condense_element(mats[e], s_->dt, nullptr, bubbles_[e], k);
    const std::array<int, 9> u = num.condensed_unknowns(mesh_->triangles[e], e);
    for (std::size_t p = 0; p < kCornerPairs.size(); ++p) {
      const SupernodalLdlt::Block& b = layout_.element_blocks[e][p];
      if (b.base < 0) continue;
      const int rc = kCornerPairs[p][0], cc = kCornerPairs[p][1];
      for (const int r : {2 * rc, 2 * rc + 1, 6 + rc}) {
        if (u[r] < 0) continue;
        const long row = b.base + layout_.slot[u[r]] * b.row_step;
        for (const int c : {2 * cc, 2 * cc + 1, 6 + cc})
          if (u[c] >= 0) lx[row + layout_.slot[u[c]] * b.col_step] += k(r, c);
      }
    }
    if (num.has_rider(mesh_->triangles[e]))
      put_rider_entries(num, mesh_->triangles[e], e, k, [&](int row, int col, double value) {
        if (row >= col) lx[factor_.block(row, col).base] += value;
      });
  }
  for (int q = 0; q < num.pressures; ++q) lx[layout_.pressure_diagonal[q]] -= mp[q] / s_->dt;
  factor_structure_ = structure_->tangent_lower();
  structure_in_factor_ = factor_structure_;
  for (const auto& t : factor_structure_) lx[factor_.block(t.row(), t.col()).base] += t.value();
  if (!factor_.factorize_values())
    throw StepFailure("the Newton matrix could not be factorised (zero or wrong-signed pivot)");
}

bool CondensedBubbleSystem::refresh_structure() {
  if (!s_->structure.model) return true;
  std::vector<Eigen::Triplet<double>> current = structure_->tangent_lower();
  // The change from the tangent the factor holds, relative to the tangent (Frobenius norms over
  // the structure's block, its unknowns numbered consecutively). Below kStructureTangentChange
  // (an elastic beam's geometric stiffness between iterates: 1e-12 to 1e-5 on the sloshing beam)
  // the trailing block's refactorisation costs more than it saves; a yielding fiber changes it
  // by 1e-2 to 0.2 (the yielding obstacle: the same iterations at 1e-3 as at 0, more at 1e-2).
  int first = std::numeric_limits<int>::max(), last = -1;
  for (const int d : num_->structure)
    if (d >= 0) first = std::min(first, d), last = std::max(last, d);
  if (last < 0) return true;  // every structure dof supported
  const int m = last - first + 1;
  Eigen::MatrixXd change = Eigen::MatrixXd::Zero(m, m);
  for (const auto& e : current) change(e.row() - first, e.col() - first) += e.value();
  const Eigen::MatrixXd held = change;
  for (const auto& e : structure_in_factor_) change(e.row() - first, e.col() - first) -= e.value();
  if (change.norm() <= kStructureTangentChange * held.norm()) return true;
  std::vector<Eigen::Triplet<double>> delta = current;
  for (const auto& e : factor_structure_) delta.emplace_back(e.row(), e.col(), -e.value());
  structure_in_factor_ = std::move(current);
  return factor_.update_last(delta);
}

void CondensedBubbleSystem::solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const {
  Eigen::MatrixXd dvs, dps;
  const auto solve = [this](const Eigen::MatrixXd& b) {
    Eigen::MatrixXd x = b;
    factor_.solve(x);
    return x;
  };
  solve_condensed(*mesh_, *num_, bubbles_, solve, r.rv, r.rp, dvs, dps);
  dv = dvs.col(0);
  dp = dps.col(0);
}

}  // namespace pfem
