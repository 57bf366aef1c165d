#include "engine/io/section_checks.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "engine/io/geometry_bounds.h"
#include "engine/io/motion_checks.h"

namespace pfem {

void check_walls(const pfem::v1::Model& model, FieldChecker& out) {
  if (model.walls_size() == 0) out.error("walls", "at least one wall is required");
  for (int i = 0; i < model.walls_size(); ++i) {
    const auto& w = model.walls(i);
    const std::string path = at("walls", i);
    if (w.points_size() < 2) out.error(path + ".points", "needs at least 2 points");
    for (int k = 0; k < w.points_size(); ++k) {
      out.finite(at(path + ".points", k) + ".x", w.points(k).x());
      out.finite(at(path + ".points", k) + ".y", w.points(k).y());
      // Points closer than 1e-6 h are merged into one wall node by the remesher, which then
      // fails the run ("constraint needs two different node indices"; seen at 1e-7 h).
      const double h = model.mesh().h(),
                   gap = k == 0 ? 1.0 : std::hypot(w.points(k).x() - w.points(k - 1).x(),
                                                   w.points(k).y() - w.points(k - 1).y());
      if (k > 0 && gap == 0.0)
        out.error(at(path + ".points", k), "repeats the previous point (zero-length segment)");
      else if (k > 0 && h > 0.0 && std::isfinite(h) && gap < 1e-6 * h) {
        char text[96];
        std::snprintf(text, sizeof text, "is only %.3g m from the previous point (less than 1e-6 mesh.h)", gap);
        out.error(at(path + ".points", k), std::string(text) + ": merge them");
      }
      const int next = (k + 1) % w.points_size();
      if (w.slip() && (k + 1 < w.points_size() || w.closed()) && w.points(k).x() != w.points(next).x() &&
          w.points(k).y() != w.points(next).y())
        out.error(at(path + ".points", k),
                  "a slip wall's pieces must be horizontal or vertical (this one ends at point " +
                      std::to_string(next) + ")");
    }
    if (w.has_motion() && w.points_size() >= 2)
      for (auto& e : wall_motion_errors(model, i)) out.add(std::move(e));
  }
}

void check_domain(const pfem::v1::Model& model, FieldChecker& out) {
  if (!model.has_domain()) return;
  const auto& d = model.domain();
  for (const auto& [name, v] : {std::pair{"domain.min.x", d.min().x()}, {"domain.min.y", d.min().y()},
                                {"domain.max.x", d.max().x()}, {"domain.max.y", d.max().y()}})
    out.finite(name, v);
  if (!(d.max().x() > d.min().x()) || !(d.max().y() > d.min().y()))
    out.error("domain", "max must be greater than min in x and y");
  if (d.has_on_exit() && d.on_exit() != "remove" && d.on_exit() != "fail")
    out.error("domain.on_exit", "must be \"remove\" or \"fail\" (got \"" + d.on_exit() + "\")");
}

void check_regions(const pfem::v1::Model& model, FieldChecker& out) {
  if (model.fluid_regions_size() == 0) out.error("fluid_regions", "at least one fluid region is required");
  const auto walls = walls_bounds(model);
  for (int i = 0; i < model.fluid_regions_size(); ++i) {
    const auto& r = model.fluid_regions(i);
    const std::string path = at("fluid_regions", i);
    Bounds b;
    if (r.has_rectangle()) {
      const auto& q = r.rectangle();
      for (const auto& [name, v] : {std::pair{".rectangle.min.x", q.min().x()}, {".rectangle.min.y", q.min().y()},
                                    {".rectangle.max.x", q.max().x()}, {".rectangle.max.y", q.max().y()}})
        out.finite(path + name, v);
      if (!(q.max().x() > q.min().x()) || !(q.max().y() > q.min().y())) {
        out.error(path + ".rectangle", "max must be greater than min in x and y");
        continue;
      }
      b = {q.min().x(), q.min().y(), q.max().x(), q.max().y()};
    } else if (r.has_polygon()) {
      const auto& poly = r.polygon();
      if (poly.points_size() < 3) {
        out.error(path + ".polygon.points", "needs at least 3 points");
        continue;
      }
      bool ok = true;
      for (int k = 0; k < poly.points_size(); ++k) {
        if (!std::isfinite(poly.points(k).x()) || !std::isfinite(poly.points(k).y())) {
          out.error(at(path + ".polygon.points", k), "must be finite");
          ok = false;
        }
      }
      if (!ok) continue;
      if (std::abs(polygon_area(poly)) <= 0.0) {
        out.error(path + ".polygon", "has zero area");
        continue;
      }
      b = polygon_bounds(poly);
    } else {
      out.error(path, "needs a shape: rectangle or polygon");
      continue;
    }
    out.finite(path + ".velocity.x", r.velocity().x());
    out.finite(path + ".velocity.y", r.velocity().y());
    if (walls.valid() && !walls.contains(b, 1e-9 * (walls.size() + 1.0)))
      out.error(path, "reaches beyond the walls (their bounding box)");
    const double h = model.mesh().h();
    if (std::isfinite(h) && h > 0 && (b.xmax - b.xmin < h * 0.999 || b.ymax - b.ymin < h * 0.999))
      out.error(path, "is smaller than the particle spacing mesh.h");
  }
}

}  // namespace pfem
