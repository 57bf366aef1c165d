#include "engine/io/geometry_bounds.h"

#include <algorithm>
#include <cmath>

namespace pfem {

Bounds walls_bounds(const pfem::v1::Model& model) {
  Bounds b;
  for (const auto& w : model.walls())
    for (const auto& p : w.points())
      if (std::isfinite(p.x()) && std::isfinite(p.y())) b.add(p.x(), p.y());
  return b;
}

Bounds domain_bounds(const pfem::v1::Model& model) {
  if (model.has_domain()) {
    const auto& d = model.domain();
    return {d.min().x(), d.min().y(), d.max().x(), d.max().y()};
  }
  Bounds b = walls_bounds(model);
  const double grow = 0.5 * b.size();
  return {b.xmin - grow, b.ymin - grow, b.xmax + grow, b.ymax + grow};
}

double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

SegmentContact segment_contact(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                               double dy) {
  const double scale = std::max({std::abs(bx - ax), std::abs(by - ay), std::abs(dx - cx), std::abs(dy - cy)});
  const double zero = 1e-12 * scale * scale;
  const auto side = [&](double px, double py, double qx, double qy, double rx, double ry) {
    const double cross = (qx - px) * (ry - py) - (qy - py) * (rx - px);
    return cross > zero ? 1 : (cross < -zero ? -1 : 0);
  };
  const int c = side(ax, ay, bx, by, cx, cy), d = side(ax, ay, bx, by, dx, dy);
  const int a = side(cx, cy, dx, dy, ax, ay), b = side(cx, cy, dx, dy, bx, by);
  if (c == 0 && d == 0) {  // on one line: overlap of the projections on it
    const double ux = bx - ax, uy = by - ay, length2 = ux * ux + uy * uy;
    if (length2 == 0.0) return SegmentContact::kNone;
    const double s = ((cx - ax) * ux + (cy - ay) * uy) / length2, t = ((dx - ax) * ux + (dy - ay) * uy) / length2;
    const double overlap = std::min(1.0, std::max(s, t)) - std::max(0.0, std::min(s, t));
    return overlap > 1e-9 ? SegmentContact::kOverlap : (overlap > -1e-9 ? SegmentContact::kTouch : SegmentContact::kNone);
  }
  if (c * d > 0 || a * b > 0) return SegmentContact::kNone;
  return c != 0 && d != 0 && a != 0 && b != 0 ? SegmentContact::kCross : SegmentContact::kTouch;
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
