#include "engine/io/geometry_bounds.h"

#include <cmath>

namespace pfem {

Bounds walls_bounds(const pfem::v1::Model& model) {
  Bounds b;
  for (const auto& w : model.walls())
    for (const auto& p : w.points())
      if (std::isfinite(p.x()) && std::isfinite(p.y())) b.add(p.x(), p.y());
  return b;
}

Bounds polygon_bounds(const pfem::v1::Polygon& polygon) {
  Bounds b;
  for (const auto& p : polygon.points()) b.add(p.x(), p.y());
  return b;
}

double polygon_area(const pfem::v1::Polygon& polygon) {
  double a = 0.0;
  const int n = polygon.points_size();
  for (int i = 0; i < n; ++i) {
    const auto& p = polygon.points(i);
    const auto& q = polygon.points((i + 1) % n);
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

}  // namespace pfem
