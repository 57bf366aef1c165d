#include "engine/mesh/beam_riders.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace pfem::mesh {

namespace {
double cross(double ux, double uy, const std::array<double, 2>& l) { return ux * l[1] - uy * l[0]; }
}  // namespace

bool level_fraction(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& p,
                    const std::array<double, 2>& l, double& s) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double dl = cross(dx, dy, l);
  if (std::abs(dl) <= 1e-6 * std::hypot(dx, dy)) return false;
  s = cross(p[0] - a[0], p[1] - a[1], l) / dl;
  return true;
}

double level_fraction_derivative(const std::array<double, 2>& a, const std::array<double, 2>& b, double s,
                                 const std::array<double, 2>& da, const std::array<double, 2>& db,
                                 const std::array<double, 2>& dp, const std::array<double, 2>& l) {
  return (cross(dp[0] - da[0], dp[1] - da[1], l) - s * cross(db[0] - da[0], db[1] - da[1], l)) /
         cross(b[0] - a[0], b[1] - a[1], l);
}

std::vector<RiderPlace> place_riders(const FluidMesh& previous, std::span<const double> x, std::span<const double> y,
                                     std::span<const std::array<std::int32_t, 2>> segments,
                                     const std::vector<std::vector<int>>& segments_of, std::int32_t first_rider,
                                     const std::array<double, 2>& level, double h) {
  if (level[0] == 0.0 && level[1] == 0.0) return {};
  const auto point = [&](std::int32_t i) { return std::array{x[i], y[i]}; };
  // Each contact's best segment, nearest first (ties by particle and segment).
  std::vector<std::tuple<double, std::int32_t, int, double>> claims;  // distance, particle, segment, s
  for (const auto& [particle, node] : previous.contact_edges) {
    // A beam node's segments; a rider's segment and those of its ends (the water may have
    // risen past one).
    std::vector<int> candidates;
    const auto add_segments_of = [&](std::int32_t i) {
      if (static_cast<std::size_t>(i) < segments_of.size())
        candidates.insert(candidates.end(), segments_of[i].begin(), segments_of[i].end());
    };
    if (node >= first_rider && node - first_rider < static_cast<std::int32_t>(segments.size())) {
      const auto& [a, b] = segments[node - first_rider];
      add_segments_of(a), add_segments_of(b);
    } else {
      add_segments_of(node);
    }
    std::tuple<double, std::int32_t, int, double> best{kRiderReach * h, particle, -1, 0.0};
    for (const int j : candidates) {
      const auto a = point(segments[j][0]), b = point(segments[j][1]), p = point(particle);
      double s = 0.0;
      if (!level_fraction(a, b, p, level, s) || s < kRiderMargin || s > 1.0 - kRiderMargin) continue;
      const double distance = std::hypot(a[0] + s * (b[0] - a[0]) - p[0], a[1] + s * (b[1] - a[1]) - p[1]);
      if (distance < std::get<0>(best)) best = {distance, particle, j, s};
    }
    if (std::get<2>(best) >= 0) claims.push_back(best);
  }
  std::sort(claims.begin(), claims.end());
  std::vector<RiderPlace> places;
  std::vector<std::uint8_t> taken(segments.size(), 0);
  for (const auto& [distance, particle, segment, s] : claims) {
    if (taken[segment]) continue;
    taken[segment] = 1;
    places.push_back({segment, particle, s});
  }
  std::sort(places.begin(), places.end(), [](const RiderPlace& p, const RiderPlace& q) { return p.segment < q.segment; });
  return places;
}

}  // namespace pfem::mesh
