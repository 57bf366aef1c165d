#pragma once
// Bounding boxes and polygon helpers shared by validation and model building.
#include <algorithm>
#include <limits>

#include "pfem/v1/model.pb.h"

namespace pfem {

struct Bounds {
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -std::numeric_limits<double>::infinity(), ymax = xmax;
  bool valid() const { return xmax >= xmin && ymax >= ymin; }
  double size() const { return std::max(xmax - xmin, ymax - ymin); }
  void add(double x, double y) {
    xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  }
  bool contains(const Bounds& b, double tol) const {
    return b.xmin >= xmin - tol && b.xmax <= xmax + tol && b.ymin >= ymin - tol && b.ymax <= ymax + tol;
  }
};

// Bounding box of every wall point (invalid when there are none or they are not finite).
Bounds walls_bounds(const pfem::v1::Model& model);
// The model's domain: `domain`, or the walls' bounding box grown by half its size.
Bounds domain_bounds(const pfem::v1::Model& model);

// How two segments ab and cd meet: not at all, or at an end of one of them (a beam standing on
// a wall), crossing at a point inside both, or overlapping along a piece of positive length.
enum class SegmentContact { kNone, kTouch, kCross, kOverlap };
SegmentContact segment_contact(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                               double dy);
// The distance from the point (px, py) to the segment ab.
double distance_to_segment(double px, double py, double ax, double ay, double bx, double by);
Bounds polygon_bounds(const pfem::v1::Polygon& polygon);
double polygon_area(const pfem::v1::Polygon& polygon);  // signed, counter-clockwise positive

}  // namespace pfem
