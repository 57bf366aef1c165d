#include "engine/mesh/contact_line.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace pfem::mesh {

std::vector<WallSlide> contact_line_slides(const FluidMesh& previous, std::span<const double> x,
                                           std::span<const double> y, std::span<const SlidingWallNode> sliding,
                                           const std::vector<std::vector<int>>& neighbours,
                                           const std::array<double, 2>& level) {
  std::vector<WallSlide> slides;
  std::vector<std::uint8_t> taken(sliding.size(), 0);
  const auto sliding_index = [&](std::int32_t node) {  // of a wall node, or -1 for one that does not slide
    if (node < 0 || static_cast<std::size_t>(node) >= neighbours.size()) return -1;
    for (const int k : neighbours[node])
      if (sliding[k].node == node) return k;
    return -1;
  };
  // Where node k would go for the particle: the wall's point level with it, or its foot.
  const auto offset_of = [&](int k, std::int32_t particle, bool to_level, double& o) {
    if (to_level) return sliding[k].level_offset(x[particle], y[particle], level, o);
    o = sliding[k].offset(x[particle], y[particle]);
    return true;
  };
  // The point level with the particle where a node next to the contact covers it (taken or not).
  const auto goes_level = [&](const std::array<std::int32_t, 2>& contact) {
    const auto [particle, wall] = contact;
    if (static_cast<std::size_t>(wall) >= neighbours.size()) return false;
    for (const int k : neighbours[wall])
      if (double o = 0.0; offset_of(k, particle, true, o) && std::abs(o) <= sliding[k].cover) return true;
    return false;
  };
  // The covering node nearest a contact's point, among those not taken; -1 for none.
  const auto nearest = [&](const std::array<std::int32_t, 2>& contact, bool to_level, double& best_offset) {
    const auto [particle, wall] = contact;
    int best = -1;
    if (static_cast<std::size_t>(wall) >= neighbours.size()) return best;
    for (const int k : neighbours[wall]) {
      double offset = 0.0;
      if (taken[k] || !offset_of(k, particle, to_level, offset) || std::abs(offset) > sliding[k].cover) continue;
      if (best < 0 || std::abs(offset) < std::abs(best_offset)) best = k, best_offset = offset;
    }
    return best;
  };
  // Contacts nearest a node first, so that where two claim one node the geometry decides, not
  // the order of the triangulation's faces (which two runs a parameter's round-off apart can
  // take differently: the wave flume's FDM parted at 1.035 s so).
  std::vector<std::tuple<double, std::array<std::int32_t, 2>, bool>> order;  // distance, contact, to the level
  for (const auto& contact : previous.contact_edges) {
    const bool to_level = goes_level(contact);
    double offset = 0.0;
    if (nearest(contact, to_level, offset) >= 0) order.push_back({std::abs(offset), contact, to_level});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [distance, contact, to_level] : order) {
    const std::int32_t particle = contact[0];
    double best_offset = 0.0;
    const int best = nearest(contact, to_level, best_offset);
    if (best < 0) continue;
    taken[best] = 1;
    const SlidingWallNode& s = sliding[best];
    if (std::abs(best_offset) <= s.reach) {
      slides.push_back({best, particle, best_offset, true, to_level});
      continue;
    }
    // Past its reach, into the middle between it and the neighbour on that side: there when that
    // neighbour is still at its place (which it then keeps), else held at its reach.
    const int next = sliding_index(s.neighbours[best_offset > 0.0 ? 1 : 0]);
    if (next >= 0 && taken[next]) {
      slides.push_back({best, particle, std::copysign(s.reach, best_offset), false, to_level});
    } else {
      if (next >= 0) taken[next] = 1;
      slides.push_back({best, particle, best_offset, true, to_level});
    }
  }
  return slides;
}

}  // namespace pfem::mesh
