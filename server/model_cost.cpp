#include "server/model_cost.h"

#include <algorithm>
#include <string>

namespace pfem::server {
namespace {

double cross(const pfem::v1::Vec2& o, const pfem::v1::Vec2& a, const pfem::v1::Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Proper crossing of segments ab and cd (touching ends of neighbouring edges do not count).
bool segments_cross(const pfem::v1::Vec2& a, const pfem::v1::Vec2& b, const pfem::v1::Vec2& c,
                    const pfem::v1::Vec2& d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

}  // namespace

long count_geometry_points(const pfem::v1::Model& model) {
  long n = 0;
  for (const auto& w : model.walls()) n += w.points_size();
  for (const auto& r : model.fluid_regions()) {
    if (r.has_polygon()) n += r.polygon().points_size();
  }
  return n;
}

long count_fiber_points(const pfem::v1::Model& model) {
  const auto& s = model.structure();
  long total = 0;
  for (const auto& beam : s.beams()) {
    if (beam.element_type() != "displacement-based") continue;
    for (const auto& section : s.sections()) {
      if (section.name() != beam.section() || !section.has_fiber_rectangle()) continue;
      const long points = beam.has_integration_points() ? beam.integration_points() : 2;
      const long product = static_cast<long>(std::max(beam.elements(), 0)) *
                           std::max(points, 0L) *
                           std::max(section.fiber_rectangle().fibers(), 0);
      total += product;
    }
  }
  return total;
}

std::vector<FieldError> polygon_errors(const pfem::v1::Model& model) {
  std::vector<FieldError> errors;
  for (int r = 0; r < model.fluid_regions_size(); ++r) {
    if (!model.fluid_regions(r).has_polygon()) continue;
    const auto& p = model.fluid_regions(r).polygon().points();
    const int n = p.size();
    if (n < 4) continue;
    bool found = false;
    for (int i = 0; i < n && !found; ++i) {
      for (int j = i + 2; j < n && !found; ++j) {
        if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
        if (segments_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) {
          errors.push_back({"fluid_regions[" + std::to_string(r) + "].polygon",
                            "edges " + std::to_string(i) + " and " + std::to_string(j) +
                                " cross (the polygon must be simple)"});
          found = true;
        }
      }
    }
  }
  return errors;
}

}  // namespace pfem::server
