#include "engine/solve/bubble_history.h"

#include <algorithm>

namespace pfem {

namespace {
// The sorted node triple of a triangle packed in 64 bits (node indices below 2^21).
std::uint64_t triangle_key(const std::array<std::int32_t, 3>& t) {
  std::array<std::uint64_t, 3> n{static_cast<std::uint64_t>(t[0]), static_cast<std::uint64_t>(t[1]),
                                 static_cast<std::uint64_t>(t[2])};
  std::sort(n.begin(), n.end());
  return n[0] | (n[1] << 21) | (n[2] << 42);
}
}  // namespace

void BubbleHistory::restore(Triangles triangles, int num_params, Eigen::VectorXd& velocity,
                            Eigen::MatrixXd& sensitivity) const {
  const Eigen::Index ne = static_cast<Eigen::Index>(triangles.size());
  velocity.setZero(2 * ne);
  sensitivity.setZero(num_params > 0 ? 2 * ne : 0, num_params);
  const bool with_sensitivity = num_params > 0 && sensitivity_.cols() == num_params;
  for (Eigen::Index e = 0; e < ne; ++e) {
    const auto it = index_.find(triangle_key(triangles[e]));
    if (it == index_.end()) continue;
    velocity.segment<2>(2 * e) = velocity_.segment<2>(2 * it->second);
    if (with_sensitivity) sensitivity.middleRows<2>(2 * e) = sensitivity_.middleRows<2>(2 * it->second);
  }
}

void BubbleHistory::store(Triangles triangles, const Eigen::Ref<const Eigen::VectorXd>& velocity,
                          const Eigen::Ref<const Eigen::MatrixXd>& sensitivity) {
  keys_.resize(triangles.size());
  for (std::size_t e = 0; e < triangles.size(); ++e) keys_[e] = triangle_key(triangles[e]);
  velocity_ = velocity;
  sensitivity_ = sensitivity;
  index_keys();
}

void BubbleHistory::index_keys() {
  index_.clear();
  index_.reserve(keys_.size());
  for (std::size_t e = 0; e < keys_.size(); ++e) index_.emplace(keys_[e], static_cast<int>(e));
}

void BubbleHistory::archive(StateArchive& a) {
  a(keys_);
  a(velocity_);
  a(sensitivity_);
  if (!a.is_restoring()) return;
  if (velocity_.size() != 2 * static_cast<Eigen::Index>(keys_.size()) ||
      (sensitivity_.cols() > 0 && sensitivity_.rows() != velocity_.size()))
    throw CheckpointError("checkpoint: bubble velocities that do not match their triangles");
  index_keys();
}

}  // namespace pfem
