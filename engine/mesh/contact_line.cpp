#include "engine/mesh/contact_line.h"

#include <cmath>

namespace pfem::mesh {

std::vector<WallSlide> contact_line_slides(const FluidMesh& previous, std::span<const double> x,
                                           std::span<const double> y, std::span<const SlidingWallNode> sliding,
                                           const std::vector<std::vector<int>>& neighbours) {
  std::vector<WallSlide> slides;
  std::vector<std::uint8_t> taken(sliding.size(), 0);
  for (const auto& [particle, wall] : previous.contact_edges) {
    if (static_cast<std::size_t>(wall) >= neighbours.size()) continue;
    int best = -1;
    double best_offset = 0.0;
    for (const int k : neighbours[wall]) {
      const SlidingWallNode& s = sliding[k];
      const double offset = s.offset(x[particle], y[particle]);
      if (taken[k] || std::abs(offset) > s.reach) continue;
      if (best < 0 || std::abs(offset) < std::abs(best_offset)) best = k, best_offset = offset;
    }
    if (best < 0) continue;
    taken[best] = 1;
    slides.push_back({best, particle, best_offset});
  }
  return slides;
}

}  // namespace pfem::mesh
