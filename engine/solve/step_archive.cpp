// What one PFEM step hands to the next, saved for a checkpoint or restored from one (see
// UnifiedStep::archive). Everything else the step holds is rebuilt at every step.
#include <algorithm>

#include "engine/solve/fluid_step.h"

namespace pfem {

namespace {
// A map by triangle as its keys in increasing order and the values in that order (the saved
// bytes do not depend on the hash table's layout).
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

void UnifiedStep::archive(StateArchive& a) {
  archive_by_triangle(a, bubbles_by_triangle_);
  archive_by_triangle(a, bubble_sensitivity_by_triangle_);
  a(lu_steps_left_);
  a(lu_analyzed_);
  if (a.is_restoring() && lu_analyzed_.rows() > 0) jacobian_solver_.analyze(lu_analyzed_);
}

}  // namespace pfem
