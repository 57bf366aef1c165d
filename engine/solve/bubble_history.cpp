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

template <class Value>
void archive_by_triangle(StateArchive& a, std::unordered_map<std::uint64_t, Value>& map) {
  std::vector<std::uint64_t> keys;
  for (const auto& [key, value] : map) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  a(keys);
  if (a.is_restoring()) map.clear();
  for (const auto key : keys) a(map[key]);
}
}  // namespace

void BubbleHistory::restore(Triangles triangles, int num_params, std::vector<Eigen::Vector2d>& velocity,
                            std::vector<Sensitivity>& sensitivity) const {
  const std::size_t ne = triangles.size();
  velocity.assign(ne, Eigen::Vector2d::Zero());
  sensitivity.assign(num_params > 0 ? ne : 0, Sensitivity::Zero(2, num_params));
  for (std::size_t e = 0; e < ne; ++e) {
    const std::uint64_t key = triangle_key(triangles[e]);
    if (auto it = velocity_.find(key); it != velocity_.end()) velocity[e] = it->second;
    if (auto it = sensitivity_.find(key); num_params > 0 && it != sensitivity_.end()) sensitivity[e] = it->second;
  }
}

void BubbleHistory::store(Triangles triangles, const Eigen::Ref<const Eigen::VectorXd>& velocity,
                          const Eigen::Ref<const Eigen::MatrixXd>& sensitivity) {
  velocity_.clear();
  sensitivity_.clear();
  for (std::size_t e = 0; e < triangles.size(); ++e) {
    const std::uint64_t key = triangle_key(triangles[e]);
    velocity_[key] = velocity.segment<2>(2 * e);
    if (sensitivity.cols() > 0) sensitivity_[key] = sensitivity.middleRows<2>(2 * e);
  }
}

void BubbleHistory::archive(StateArchive& a) {
  archive_by_triangle(a, velocity_);
  archive_by_triangle(a, sensitivity_);
}

}  // namespace pfem
