#pragma once
// The Newton system of a step with the bubble condensed per element (kCondensedBubble, the
// default; engine/solve/fluid_step.h): what remains is [A -G'; -G'^T -C] in nodal velocities
// and pressures (pressure rows negated), symmetric quasi-definite with A = condensed M/dt + K
// and C = Mp/dt + the bubble's pressure coupling, factorised by the supernodal LDL^T on the graph
// of the mesh nodes (supernodal_ldlt.h). The structure's unknowns are ordered last, so that its
// tangent is refreshed between iterations by refactorising only the trailing dense block.
// The DDM's LU (step_jacobian.h) reuses the analysis and the layout.
#include <array>
#include <vector>

#include "engine/solve/bubble_condensation.h"
#include "engine/solve/step_linear_system.h"
#include "engine/solve/supernodal_ldlt.h"

namespace pfem {

// The corner pairs of a triangle whose blocks the symmetric Newton matrix needs once each: rows
// of the first corner, columns of the second.
inline constexpr std::array<std::array<int, 2>, 6> kCornerPairs{{{0, 0}, {1, 1}, {2, 2}, {1, 0}, {2, 0}, {2, 1}}};

// Where the condensed matrix's entries go in the factor, from the analysis.
struct CondensedLayout {
  std::vector<int> first_of_node;  // per node: its first condensed unknown (-1: none)
  std::vector<int> slot;  // per condensed unknown: its rank among its node's unknowns
  std::vector<std::array<SupernodalLdlt::Block, 6>> element_blocks;  // per triangle and corner pair
  std::vector<long> pressure_diagonal;  // per pressure unknown: its diagonal in the factor
};

class CondensedBubbleSystem final : public StepLinearSystem {
 public:
  void begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
             const StepStructure& structure) override;
  void factorize(const StepElements& elements, const Eigen::VectorXd& mp, bool analyze) override;
  // The factorisation with the structure's part at the current iterate (the fluid's part stays
  // that of the last factorisation), unless that part barely changed; false when it cannot be
  // updated so.
  bool refresh_structure() override;
  void solve(const StepResidual& r, Eigen::VectorXd& dv, Eigen::VectorXd& dp) const override;

  // The symbolic analysis on the graph of the mesh nodes, and where each triangle's blocks go in
  // the factor: at the step's first factorisation, or for the DDM when the step made none.
  void analyze();
  bool analyzed() const { return analyzed_; }  // in this step
  const SupernodalLdlt& factor() const { return factor_; }
  const CondensedLayout& layout() const { return layout_; }

 private:
  const mesh::FluidMesh* mesh_ = nullptr;
  const StepSettings* s_ = nullptr;
  const StepNumbering* num_ = nullptr;
  const StepStructure* structure_ = nullptr;
  SupernodalLdlt factor_;
  CondensedLayout layout_;
  bool analyzed_ = false;
  std::vector<BubbleCondensation> bubbles_;  // of the last factorisation
  std::vector<Eigen::Triplet<double>> factor_structure_;  // the structure's entries last factorised
  std::vector<Eigen::Triplet<double>> structure_in_factor_;  // ... and those the factor holds now
};

}  // namespace pfem
