#include "engine/io/model_checks.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "engine/io/geometry_bounds.h"

namespace pfem {

namespace {
const std::set<std::string>& nodal_quantities() {
  static const std::set<std::string> q{"ux", "uy", "vx", "vy", "p"};
  return q;
}
const std::set<std::string>& global_quantities() {
  static const std::set<std::string> q{"fluid_area", "front_x", "front_y", "max_speed"};
  return q;
}
std::string listed(const std::set<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}
std::string at(const std::string& path, int i) { return path + "[" + std::to_string(i) + "]"; }
}  // namespace

bool is_nodal_quantity(const std::string& q) { return nodal_quantities().count(q) > 0; }
bool is_global_quantity(const std::string& q) { return global_quantities().count(q) > 0; }
bool is_parameter_target(const std::string& t) {
  return t == "fluid.rho" || t == "fluid.mu" || t == "fluid.kappa";
}

void ModelChecker::finite(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
}
void ModelChecker::positive(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
  else if (!(v > 0.0)) error(path, "must be > 0");
}
void ModelChecker::non_negative(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
  else if (v < 0.0) error(path, "must be >= 0");
}

std::vector<FieldError> ModelChecker::run() {
  errors_.clear();
  if (model_.fluid_regions_size() == 0 && model_.walls_size() == 0) {
    error("model", "is empty: it needs at least one fluid region and one wall");
    return errors_;
  }
  if (model_.has_thickness()) positive("thickness", model_.thickness());
  if (model_.has_gravity()) {
    finite("gravity.x", model_.gravity().x());
    finite("gravity.y", model_.gravity().y());
  }
  check_fluid();
  check_mesh();
  check_walls();
  check_domain();
  check_regions();
  check_analysis();
  check_recorders();
  check_parameters();
  return errors_;
}

void ModelChecker::check_fluid() {
  if (!model_.has_fluid()) return error("fluid", "is required (rho, mu, kappa)");
  positive("fluid.rho", model_.fluid().rho());
  non_negative("fluid.mu", model_.fluid().mu());
  positive("fluid.kappa", model_.fluid().kappa());
}

void ModelChecker::check_mesh() {
  if (!model_.has_mesh()) return error("mesh", "is required (h, alpha)");
  positive("mesh.h", model_.mesh().h());
  if (model_.mesh().has_alpha()) {
    const double a = model_.mesh().alpha();
    if (!std::isfinite(a) || a < 0.8 || a > 3.0) error("mesh.alpha", "must be in [0.8, 3]");
  }
  if (model_.mesh().has_removal_distance()) {
    const double d = model_.mesh().removal_distance();
    if (!std::isfinite(d) || d < 0.0 || d > 0.5) error("mesh.removal_distance", "must be in [0, 0.5]");
  }
  if (model_.mesh().has_insertion_length()) {
    const double l = model_.mesh().insertion_length();
    if (!std::isfinite(l) || (l != 0.0 && (l < 1.5 || l > 3.0)))
      error("mesh.insertion_length", "must be 0 (off) or in [1.5, 3]");
  }
}

void ModelChecker::check_walls() {
  if (model_.walls_size() == 0) error("walls", "at least one wall is required");
  for (int i = 0; i < model_.walls_size(); ++i) {
    const auto& w = model_.walls(i);
    const std::string path = at("walls", i);
    if (w.points_size() < 2) error(path + ".points", "needs at least 2 points");
    for (int k = 0; k < w.points_size(); ++k) {
      finite(at(path + ".points", k) + ".x", w.points(k).x());
      finite(at(path + ".points", k) + ".y", w.points(k).y());
      if (k > 0 && w.points(k).x() == w.points(k - 1).x() && w.points(k).y() == w.points(k - 1).y())
        error(at(path + ".points", k), "repeats the previous point (zero-length segment)");
    }
  }
}

void ModelChecker::check_domain() {
  if (!model_.has_domain()) return;
  const auto& d = model_.domain();
  for (const auto& [name, v] : {std::pair{"domain.min.x", d.min().x()}, {"domain.min.y", d.min().y()},
                                {"domain.max.x", d.max().x()}, {"domain.max.y", d.max().y()}})
    finite(name, v);
  if (!(d.max().x() > d.min().x()) || !(d.max().y() > d.min().y()))
    error("domain", "max must be greater than min in x and y");
}

void ModelChecker::check_regions() {
  if (model_.fluid_regions_size() == 0) error("fluid_regions", "at least one fluid region is required");
  const auto walls = walls_bounds(model_);
  for (int i = 0; i < model_.fluid_regions_size(); ++i) {
    const auto& r = model_.fluid_regions(i);
    const std::string path = at("fluid_regions", i);
    Bounds b;
    if (r.has_rectangle()) {
      const auto& q = r.rectangle();
      for (const auto& [name, v] : {std::pair{".rectangle.min.x", q.min().x()}, {".rectangle.min.y", q.min().y()},
                                    {".rectangle.max.x", q.max().x()}, {".rectangle.max.y", q.max().y()}})
        finite(path + name, v);
      if (!(q.max().x() > q.min().x()) || !(q.max().y() > q.min().y())) {
        error(path + ".rectangle", "max must be greater than min in x and y");
        continue;
      }
      b = {q.min().x(), q.min().y(), q.max().x(), q.max().y()};
    } else if (r.has_polygon()) {
      const auto& poly = r.polygon();
      if (poly.points_size() < 3) {
        error(path + ".polygon.points", "needs at least 3 points");
        continue;
      }
      bool ok = true;
      for (int k = 0; k < poly.points_size(); ++k) {
        if (!std::isfinite(poly.points(k).x()) || !std::isfinite(poly.points(k).y())) {
          error(at(path + ".polygon.points", k), "must be finite");
          ok = false;
        }
      }
      if (!ok) continue;
      if (std::abs(polygon_area(poly)) <= 0.0) {
        error(path + ".polygon", "has zero area");
        continue;
      }
      b = polygon_bounds(poly);
    } else {
      error(path, "needs a shape: rectangle or polygon");
      continue;
    }
    finite(path + ".velocity.x", r.velocity().x());
    finite(path + ".velocity.y", r.velocity().y());
    if (walls.valid() && !walls.contains(b, 1e-9 * (walls.size() + 1.0)))
      error(path, "lies outside every wall (beyond the walls' bounding box)");
    const double h = model_.mesh().h();
    if (std::isfinite(h) && h > 0 && (b.xmax - b.xmin < h * 0.999 || b.ymax - b.ymin < h * 0.999))
      error(path, "is smaller than the particle spacing mesh.h");
  }
}

void ModelChecker::check_analysis() {
  if (!model_.has_analysis()) return error("analysis", "is required (dt, t_end)");
  const auto& a = model_.analysis();
  positive("analysis.dt", a.dt());
  positive("analysis.t_end", a.t_end());
  if (std::isfinite(a.dt()) && std::isfinite(a.t_end()) && a.dt() > a.t_end())
    error("analysis.dt", "must not exceed analysis.t_end");
  if (a.has_newton_tolerance()) {
    const double tol = a.newton_tolerance();
    if (!std::isfinite(tol) || tol <= 0 || tol >= 1) error("analysis.newton_tolerance", "must be in (0, 1)");
  }
  if (a.has_newton_max_iterations() && a.newton_max_iterations() < 1)
    error("analysis.newton_max_iterations", "must be >= 1");
  if (a.has_record_every() && a.record_every() < 1) error("analysis.record_every", "must be >= 1");
  if (a.has_vtk_every() && a.vtk_every() < 1) error("analysis.vtk_every", "must be >= 1");
  if (a.has_solver() && a.solver() != "condensed-bubble" && a.solver() != "unified-fractional-step")
    error("analysis.solver", "unknown solver '" + a.solver() + "'; expected condensed-bubble or unified-fractional-step");
}

void ModelChecker::check_recorders() {
  std::set<std::string> names;
  for (int i = 0; i < model_.recorders_size(); ++i) {
    const auto& r = model_.recorders(i);
    const std::string path = at("recorders", i);
    if (r.name().empty()) error(path + ".name", "is required");
    else if (r.name().find_first_of(",\"\n ") != std::string::npos)
      error(path + ".name", "must not contain commas, quotes, spaces or newlines");
    else if (!names.insert(r.name()).second) error(path + ".name", "'" + r.name() + "' is used twice");
    if (is_nodal_quantity(r.quantity())) {
      if (r.has_point()) {
        finite(path + ".point.x", r.point().x());
        finite(path + ".point.y", r.point().y());
      } else if (r.has_node()) {
        error(path + ".node", "unknown node '" + r.node() + "'");
      } else {
        error(path, "quantity '" + r.quantity() + "' needs a target: node or point");
      }
    } else if (!is_global_quantity(r.quantity())) {
      error(path + ".quantity", "unknown quantity '" + r.quantity() + "'; expected one of " +
                                    listed(nodal_quantities()) + ", " + listed(global_quantities()));
    }
  }
}

void ModelChecker::check_parameters() {
  std::set<std::string> names;
  for (int i = 0; i < model_.parameters_size(); ++i) {
    const auto& p = model_.parameters(i);
    const std::string path = at("parameters", i);
    if (p.name().empty()) error(path + ".name", "is required");
    else if (!names.insert(p.name()).second) error(path + ".name", "'" + p.name() + "' is used twice");
    if (p.targets_size() == 0) error(path + ".targets", "needs at least one target");
    for (int k = 0; k < p.targets_size(); ++k) {
      if (!is_parameter_target(p.targets(k)))
        error(at(path + ".targets", k), "unknown target '" + p.targets(k) +
                                            "'; expected fluid.rho, fluid.mu or fluid.kappa");
    }
    if (p.has_value()) {
      if (!std::isfinite(p.value())) error(path + ".value", "must be a finite number");
      for (const auto& t : p.targets()) {
        if ((t == "fluid.rho" || t == "fluid.kappa") && !(p.value() > 0)) error(path + ".value", "must be > 0 for " + t);
        if (t == "fluid.mu" && p.value() < 0) error(path + ".value", "must be >= 0 for " + t);
      }
    }
  }
}

}  // namespace pfem
