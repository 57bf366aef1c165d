#pragma once
// The bubble velocities a step hands to the next, and their DDM sensitivities, by triangle.
// The bubble's mass couples to the corners, so its momentum is carried from step to step: a
// triangle that survives remeshing (the same three nodes, in any order) keeps its bubble
// velocity; a new triangle starts with none (engine/solve/fluid_step.h).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "engine/state/state_archive.h"

namespace pfem {

class BubbleHistory {
 public:
  using Triangles = std::span<const std::array<std::int32_t, 3>>;

  // Per triangle, two rows: the velocity (and with num_params > 0 the sensitivities, a column
  // per parameter) of the last stored step; zero for a triangle that was not in it.
  void restore(Triangles triangles, int num_params, Eigen::VectorXd& velocity, Eigen::MatrixXd& sensitivity) const;
  // This step's, replacing the last: velocity holds two entries per triangle in order, and
  // sensitivity as many rows with one column per parameter (no columns: none).
  void store(Triangles triangles, const Eigen::Ref<const Eigen::VectorXd>& velocity,
             const Eigen::Ref<const Eigen::MatrixXd>& sensitivity);
  // For a checkpoint (in the stored triangles' order: the bytes do not depend on the hash table).
  void archive(StateArchive& a);

 private:
  void index_keys();  // index_ from keys_

  std::vector<std::uint64_t> keys_;               // the stored triangles, in their order
  std::unordered_map<std::uint64_t, int> index_;  // a stored triangle's place in keys_
  Eigen::VectorXd velocity_;                      // two rows a triangle, as keys_
  Eigen::MatrixXd sensitivity_;                   // two rows a triangle, a column a parameter
};

}  // namespace pfem
