#include "engine/mesh/contact_line.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pfem::mesh {

std::vector<WallSlide> contact_line_slides(const FluidMesh& previous, std::span<const double> x,
                                           std::span<const double> y, std::span<const SlidingWallNode> sliding,
                                           const std::vector<std::vector<int>>& neighbours) {
  std::vector<WallSlide> slides;
  std::vector<std::uint8_t> taken(sliding.size(), 0);
  const auto sliding_index = [&](std::int32_t node) {  // of a wall node, or -1 for one that does not slide
    if (node < 0 || static_cast<std::size_t>(node) >= neighbours.size()) return -1;
    for (const int k : neighbours[node])
      if (sliding[k].node == node) return k;
    return -1;
  };
  // The covering node nearest a contact's foot, among those not taken; -1 for none.
  const auto nearest = [&](const std::array<std::int32_t, 2>& contact, double& best_offset) {
    const auto [particle, wall] = contact;
    int best = -1;
    if (static_cast<std::size_t>(wall) >= neighbours.size()) return best;
    for (const int k : neighbours[wall]) {
      const SlidingWallNode& s = sliding[k];
      const double offset = s.offset(x[particle], y[particle]);
      if (taken[k] || std::abs(offset) > s.cover) continue;
      if (best < 0 || std::abs(offset) < std::abs(best_offset)) best = k, best_offset = offset;
    }
    return best;
  };
  // Contacts nearest a node first, so that where two claim one node the geometry decides, not
  // the order of the triangulation's faces (which two runs a parameter's round-off apart can
  // take differently: the wave flume's FDM parted at 1.035 s so).
  std::vector<std::pair<double, std::array<std::int32_t, 2>>> order;
  for (const auto& contact : previous.contact_edges) {
    double offset = 0.0;
    if (nearest(contact, offset) >= 0) order.push_back({std::abs(offset), contact});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [distance, contact] : order) {
    const std::int32_t particle = contact[0];
    double best_offset = 0.0;
    const int best = nearest(contact, best_offset);
    if (best < 0) continue;
    taken[best] = 1;
    const SlidingWallNode& s = sliding[best];
    if (std::abs(best_offset) <= s.reach) {
      slides.push_back({best, particle, best_offset, true});
      continue;
    }
    // Past its reach, into the middle between it and the neighbour on that side: there when that
    // neighbour is still at its place (which it then keeps), else held at its reach.
    const int next = sliding_index(s.neighbours[best_offset > 0.0 ? 1 : 0]);
    if (next >= 0 && taken[next]) {
      slides.push_back({best, particle, std::copysign(s.reach, best_offset), false});
    } else {
      if (next >= 0) taken[next] = 1;
      slides.push_back({best, particle, best_offset, true});
    }
  }
  return slides;
}

}  // namespace pfem::mesh
