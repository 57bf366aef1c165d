#include "engine/analysis/beam_rider_nodes.h"

#include <algorithm>

namespace pfem {

BeamRiderNodes::BeamRiderNodes(std::span<const std::array<std::int32_t, 2>> segments, NodeState& nodes)
    : segments_(segments.begin(), segments.end()), first_(static_cast<std::int32_t>(nodes.size())),
      s_(segments.size(), 0.0), ds_(segments.size()) {
  for (std::size_t j = 0; j < segments_.size(); ++j) {
    const auto [a, b] = segments_[j];
    const std::size_t end = static_cast<std::size_t>(std::max(a, b)) + 1;
    if (segments_of_.size() < end) segments_of_.resize(end);
    segments_of_[a].push_back(static_cast<int>(j));
    segments_of_[b].push_back(static_cast<int>(j));
    nodes.add(nodes.x[a], nodes.y[a], mesh::NodeKind::Removed);
  }
}

std::span<const mesh::LineRider> BeamRiderNodes::place(const mesh::FluidMesh& previous, NodeState& nodes,
                                                       const std::array<double, 2>& level, double h) {
  for (std::size_t j = 0; j < segments_.size(); ++j) nodes.kind[first_ + j] = mesh::NodeKind::Removed;
  placed_.clear();
  const int P = nodes.num_params;
  for (const mesh::RiderPlace& place : mesh::place_riders(previous, nodes.x, nodes.y, segments_, segments_of_, first_,
                                                          level, h)) {
    const int j = place.segment;
    const std::int32_t particle = place.particle, a = segments_[j][0], b = segments_[j][1];
    const double s = place.s;
    const int c = first_ + j;
    placed_.push_back({c, a, b});
    s_[j] = s;
    nodes.kind[c] = mesh::NodeKind::Structure;
    const auto between = [s](double va, double vb) { return (1.0 - s) * va + s * vb; };
    nodes.x[c] = nodes.x0[c] = between(nodes.x[a], nodes.x[b]);
    nodes.y[c] = nodes.y0[c] = between(nodes.y[a], nodes.y[b]);
    nodes.vx[c] = between(nodes.vx[a], nodes.vx[b]);
    nodes.vy[c] = between(nodes.vy[a], nodes.vy[b]);
    nodes.p[c] = between(nodes.p[a], nodes.p[b]);
    nodes.rz[c] = nodes.wz[c] = 0.0;
    std::fill_n(&nodes.side_p[static_cast<std::size_t>(c) * mesh::kMaxPressureSides], mesh::kMaxPressureSides,
                NodeState::kNoSide);
    ds_[j].assign(P, 0.0);
    for (int k = 0; k < P; ++k) {
      const double *da = nodes.sensitivity(a, k), *db = nodes.sensitivity(b, k), *dp = nodes.sensitivity(particle, k);
      const double ds = ds_[j][k] = mesh::level_fraction_derivative(
          {nodes.x[a], nodes.y[a]}, {nodes.x[b], nodes.y[b]}, s, {da[NodeState::kDx], da[NodeState::kDy]},
          {db[NodeState::kDx], db[NodeState::kDy]}, {dp[NodeState::kDx], dp[NodeState::kDy]}, level);
      double* d = nodes.sensitivity(c, k);
      const std::array<const std::vector<double>*, 5> field{&nodes.x, &nodes.y, &nodes.vx, &nodes.vy, &nodes.p};
      for (const int f : {NodeState::kDx, NodeState::kDy, NodeState::kDvx, NodeState::kDvy, NodeState::kDp})
        d[f] = between(da[f], db[f]) + ds * ((*field[f])[b] - (*field[f])[a]);
      d[NodeState::kDrz] = d[NodeState::kDwz] = 0.0;
      std::fill_n(d + NodeState::kDpSide, mesh::kMaxPressureSides, NodeState::kNoSide);
    }
  }
  return placed_;
}

std::vector<StepRider> BeamRiderNodes::step_riders(const mesh::FluidMesh& mesh) const {
  std::vector<StepRider> riders;
  for (const auto& [node, a, b] : mesh.riders) {
    const int j = node - first_;
    riders.push_back({node, a, b, s_[j], ds_[j]});
  }
  return riders;
}

}  // namespace pfem
