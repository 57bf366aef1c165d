#include "engine/io/model_checks.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "engine/io/geometry_bounds.h"
#include "engine/io/model_size.h"
#include "engine/io/motion_checks.h"

namespace pfem {

namespace {
const std::set<std::string>& nodal_quantities() {
  static const std::set<std::string> q{"ux", "uy", "vx", "vy", "p", "rz"};
  return q;
}
const std::set<std::string>& element_quantities() {
  static const std::set<std::string> q{"basic_force", "fiber_stress", "fiber_strain"};
  return q;
}
// Fields read at a fixed place in space (engine/analysis/field_probes.h).
const std::set<std::string>& point_quantities() {
  static const std::set<std::string> q{"pressure", "wave_gauge"};
  return q;
}
const std::set<std::string>& boundary_quantities() {
  static const std::set<std::string> q{"force_x", "force_y", "moment"};
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
std::string quoted(const std::string& s) { return "'" + s + "'"; }

constexpr int kMaxBeamElements = 10000;
// Beam elements longer than this many particle spacings let water through: a particle at
// h/2 from an element of length l makes a triangle of circumradius (l^2 + h^2) / (4 h) with its
// ends, which fails the alpha test (1.2 h by default) once l approaches 2 h; the particle is
// then in no triangle, falls through the beam and is taken out.
constexpr double kMaxBeamElementSpacings = 1.5;
constexpr int kMaxFibers = 1000;
constexpr int kMaxIntegrationPoints = 10;  // as structure::DispBeamColumn2d

// Names of structure components: letters, digits, '_' and '-' (so that "<beam>/<k>" and the
// dotted parameter targets stay unambiguous).
bool valid_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

const char* kTargetForms =
    "fluid.rho, fluid.mu, fluid.kappa, thickness, material.<name>.e|fy|hardening_ratio, "
    "section.<name>.width|depth|e|area|inertia, beam.<name>.rho or wavemaker.<wall>.stroke|period|height|scale";

bool beam_elements_valid(const pfem::v1::Beam& b) {
  return b.elements() >= 1 && b.elements() <= kMaxBeamElements;
}
}  // namespace

bool is_nodal_quantity(const std::string& q) { return nodal_quantities().count(q) > 0; }
bool is_element_quantity(const std::string& q) { return element_quantities().count(q) > 0; }
bool is_global_quantity(const std::string& q) { return global_quantities().count(q) > 0; }
bool is_point_quantity(const std::string& q) { return point_quantities().count(q) > 0; }

std::optional<TargetRef> parse_parameter_target(const std::string& t) {
  if (t == "fluid.rho" || t == "fluid.mu" || t == "fluid.kappa") return TargetRef{"fluid", "", t.substr(6)};
  if (t == "thickness") return TargetRef{"thickness", "", ""};
  const auto first = t.find('.');
  const auto last = t.rfind('.');
  if (first == std::string::npos || last == first) return std::nullopt;
  TargetRef ref{t.substr(0, first), t.substr(first + 1, last - first - 1), t.substr(last + 1)};
  if (!valid_name(ref.name)) return std::nullopt;
  static const std::map<std::string, std::set<std::string>> properties{
      {"material", {"e", "fy", "hardening_ratio"}},
      {"section", {"width", "depth", "e", "area", "inertia"}},
      {"beam", {"rho"}},
      {"wavemaker", {"stroke", "period", "height", "scale"}}};
  const auto kind = properties.find(ref.kind);
  if (kind == properties.end() || kind->second.count(ref.property) == 0) return std::nullopt;
  return ref;
}

bool is_parameter_target(const std::string& t) { return parse_parameter_target(t).has_value(); }

std::optional<std::pair<std::string, int>> split_generated_name(const std::string& name) {
  const auto slash = name.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= name.size()) return std::nullopt;
  const std::string digits = name.substr(slash + 1);
  if (digits.size() > 9 || digits[0] == '0' ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::pair{name.substr(0, slash), std::stoi(digits)};
}

std::vector<FieldError> validate_structure(const pfem::v1::Model& model) {
  ModelChecker checker(model);
  return checker.run_structure();
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

std::vector<FieldError> ModelChecker::run_structure() {
  errors_.clear();
  collect_structure_names();
  check_structure();
  return errors_;
}

std::vector<FieldError> ModelChecker::run() {
  errors_.clear();
  collect_structure_names();
  if (model_.fluid_regions_size() == 0 && model_.walls_size() == 0) {
    error("model", "is empty: it needs at least one fluid region and one wall");
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
  check_structure();
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
  if (const long particles = estimate_particles(model_); particles > kMaxParticles)
    error("mesh.h", "gives about " + std::to_string(particles) + " fluid particles, more than the " +
                        std::to_string(kMaxParticles) + " a run may take");
  if (const long nodes = count_wall_nodes(model_); nodes > kMaxWallNodes)
    error("mesh.h", "gives " + std::to_string(nodes) + " wall nodes (wall length / mesh.h), more than the " +
                        std::to_string(kMaxWallNodes) + " a model may have");
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
  if (model_.mesh().has_interior_insertion_length()) {
    const double l = model_.mesh().interior_insertion_length();
    if (!std::isfinite(l) || (l != 0.0 && (l < 1.5 || l > 3.0)))
      error("mesh.interior_insertion_length", "must be 0 (same as insertion_length) or in [1.5, 3]");
  }
  if (model_.mesh().has_boundary_alpha()) {
    const double a = model_.mesh().boundary_alpha();
    if (!std::isfinite(a) || (a != 0.0 && (a < 0.6 || a > 3.0)))
      error("mesh.boundary_alpha", "must be 0 (same as alpha) or in [0.6, 3]");
  }
  if (model_.mesh().has_volume_relaxation_steps()) {
    const double n = model_.mesh().volume_relaxation_steps();
    if (!std::isfinite(n) || (n != 0.0 && (n < 1.0 || n > 1000.0)))
      error("mesh.volume_relaxation_steps", "must be 0 (off) or in [1, 1000]");
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
      // Points closer than 1e-6 h are merged into one wall node by the remesher, which then
      // fails the run ("constraint needs two different node indices"; seen at 1e-7 h).
      const double h = model_.mesh().h(),
                   gap = k == 0 ? 1.0 : std::hypot(w.points(k).x() - w.points(k - 1).x(),
                                                   w.points(k).y() - w.points(k - 1).y());
      if (k > 0 && gap == 0.0)
        error(at(path + ".points", k), "repeats the previous point (zero-length segment)");
      else if (k > 0 && h > 0.0 && std::isfinite(h) && gap < 1e-6 * h) {
        char text[96];
        std::snprintf(text, sizeof text, "is only %.3g m from the previous point (less than 1e-6 mesh.h)", gap);
        error(at(path + ".points", k), std::string(text) + ": merge them");
      }
      const int next = (k + 1) % w.points_size();
      if (w.slip() && (k + 1 < w.points_size() || w.closed()) && w.points(k).x() != w.points(next).x() &&
          w.points(k).y() != w.points(next).y())
        error(at(path + ".points", k), "a slip wall's pieces must be horizontal or vertical (this one ends at point " +
                                           std::to_string(next) + ")");
    }
    if (w.has_motion() && w.points_size() >= 2)
      for (auto& e : wall_motion_errors(model_, i)) errors_.push_back(std::move(e));
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
  if (d.has_on_exit() && d.on_exit() != "remove" && d.on_exit() != "fail")
    error("domain.on_exit", "must be \"remove\" or \"fail\" (got \"" + d.on_exit() + "\")");
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
      error(path, "reaches beyond the walls (their bounding box)");
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
  if (const std::string why = too_many_steps(a.t_end(), a.dt(), "analysis.dt"); !why.empty())
    error("analysis.t_end", why);
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
      const bool rz = r.quantity() == "rz";
      if (r.has_point()) {
        if (rz) error(path + ".point", "quantity 'rz' needs a structure node (node), not a point");
        check_point(r, path);
      } else if (r.has_node()) {
        if (!is_structure_node(r.node())) error(path + ".node", "unknown node '" + r.node() + "'");
      } else if (r.has_element()) {
        error(path + ".element", "quantity '" + r.quantity() + "' is sampled at a node" +
                                     (rz ? "" : " or a point") + ", not an element");
      } else {
        error(path, "quantity '" + r.quantity() + "' needs a target: " + (rz ? "node" : "node or point"));
      }
    } else if (is_element_quantity(r.quantity())) {
      check_element_recorder(r, path);
    } else if (is_point_quantity(r.quantity())) {
      if (r.has_point()) check_point(r, path);
      else error(path, "quantity '" + r.quantity() + "' needs a target: point");
    } else if (boundary_quantities().count(r.quantity())) {
      check_boundary_recorder(r, path);
    } else if (!is_global_quantity(r.quantity())) {
      error(path + ".quantity", "unknown quantity '" + r.quantity() + "'; expected one of " +
                                    listed(nodal_quantities()) + ", " + listed(element_quantities()) +
                                    ", " + listed(point_quantities()) + ", " + listed(boundary_quantities()) +
                                    ", " + listed(global_quantities()));
    }
    if (r.has_boundary() && !boundary_quantities().count(r.quantity()))
      error(path + ".boundary", "only for the quantities " + listed(boundary_quantities()));
    if (r.has_about() && r.quantity() != "moment") error(path + ".about", "only for the quantity moment");
  }
}

void ModelChecker::check_boundary_recorder(const pfem::v1::Recorder& r, const std::string& path) {
  if (!r.has_boundary()) return error(path, "quantity '" + r.quantity() + "' needs a target: boundary (a wall or beam name)");
  int matches = 0;
  for (const auto& w : model_.walls()) matches += w.name() == r.boundary();
  for (const auto& b : model_.structure().beams()) matches += b.name() == r.boundary();
  if (matches == 0) error(path + ".boundary", "no wall or beam is named " + quoted(r.boundary()));
  else if (matches > 1) error(path + ".boundary", quoted(r.boundary()) + " names more than one wall or beam");
  if (r.has_about()) {
    finite(path + ".about.x", r.about().x());
    finite(path + ".about.y", r.about().y());
  }
}

void ModelChecker::check_point(const pfem::v1::Recorder& r, const std::string& path) {
  finite(path + ".point.x", r.point().x());
  finite(path + ".point.y", r.point().y());
  const Bounds domain = domain_bounds(model_);
  if (domain.valid() && std::isfinite(r.point().x()) && std::isfinite(r.point().y()) &&
      !domain.contains(Bounds{r.point().x(), r.point().y(), r.point().x(), r.point().y()}, 0.0))
    error(path + ".point", "lies outside the domain");
}

void ModelChecker::check_element_recorder(const pfem::v1::Recorder& r, const std::string& path) {
  const std::string& q = r.quantity();
  if (!r.has_element()) return error(path, "quantity '" + q + "' needs a target: element (\"<beam>/<k>\")");
  const int b = beam_of_element(r.element());
  if (b < 0) return error(path + ".element", "unknown element '" + r.element() + "'");
  if (q == "basic_force") {
    if (r.component() < 0 || r.component() > 2)
      error(path + ".component", "must be in 0..2 (0 = N, 1 = M_i, 2 = M_j) (got " +
                                     std::to_string(r.component()) + ")");
    return;
  }
  const auto& beam = model_.structure().beams(b);
  const auto section = names_.sections.find(beam.section());
  const bool fibers = beam.element_type() == "displacement-based" && section != names_.sections.end() &&
                      model_.structure().sections(section->second).has_fiber_rectangle();
  if (!fibers)
    return error(path + ".element", "element '" + r.element() + "' has no fibers: " + q +
                                        " needs a displacement-based beam with a fiber_rectangle section");
  const int points = beam.has_integration_points() ? beam.integration_points() : 2;
  if (r.section_point() < 0 || r.section_point() >= points)
    error(path + ".section_point", "must be in 0.." + std::to_string(points - 1) + " (got " +
                                       std::to_string(r.section_point()) + ")");
  const int n = model_.structure().sections(section->second).fiber_rectangle().fibers();
  if (r.fiber() < 0 || r.fiber() >= n)
    error(path + ".fiber", "must be in 0.." + std::to_string(n - 1) + " (got " + std::to_string(r.fiber()) + ")");
}

void ModelChecker::check_parameters() {
  std::set<std::string> names;
  for (int i = 0; i < model_.parameters_size(); ++i) {
    const auto& p = model_.parameters(i);
    const std::string path = at("parameters", i);
    if (p.name().empty()) error(path + ".name", "is required");
    else if (!names.insert(p.name()).second) error(path + ".name", "'" + p.name() + "' is used twice");
    if (p.direction_size() > 0) {
      check_direction(p, path);
      continue;
    }
    if (p.targets_size() == 0) error(path + ".targets", "needs at least one target (or a direction)");
    std::set<std::string> seen;
    std::vector<std::string> targets;
    for (int k = 0; k < p.targets_size(); ++k) {
      if (!seen.insert(p.targets(k)).second) {
        error(at(path + ".targets", k), "target '" + p.targets(k) + "' is listed twice");
        continue;
      }
      targets.push_back(p.targets(k));
      check_target(p.targets(k), at(path + ".targets", k));
    }
    if (p.has_value()) {
      if (!std::isfinite(p.value())) error(path + ".value", "must be a finite number");
      else for (const auto& t : targets) check_target_value(t, p.value(), path + ".value");
    }
  }
}

void ModelChecker::check_direction(const pfem::v1::Parameter& p, const std::string& path) {
  if (p.targets_size() > 0)
    error(path + ".targets", "a directional parameter has no targets (its direction's parameters have them)");
  if (p.has_value())
    error(path + ".value", "a directional parameter has no value of its own (its point is its parameters')");
  std::set<std::string> seen;
  for (int k = 0; k < p.direction_size(); ++k) {
    const auto& w = p.direction(k);
    const std::string at_k = at(path + ".direction", k);
    const auto named = std::find_if(model_.parameters().begin(), model_.parameters().end(),
                                    [&](const auto& q) { return q.name() == w.parameter(); });
    if (named == model_.parameters().end())
      error(at_k + ".parameter", "no parameter '" + w.parameter() + "' in the model");
    else if (named->direction_size() > 0)
      error(at_k + ".parameter", "'" + w.parameter() + "' is directional: a direction weighs parameters with targets");
    else if (!seen.insert(w.parameter()).second)
      error(at_k + ".parameter", "'" + w.parameter() + "' is listed twice");
    if (!std::isfinite(w.weight())) error(at_k + ".weight", "must be a finite number");
  }
}

void ModelChecker::check_target(const std::string& target, const std::string& path) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return error(path, "unknown target '" + target + "'; expected " + kTargetForms);
  const auto& st = model_.structure();
  const std::string in = " in target '" + target + "'";
  if (ref->kind == "material") {
    const auto m = names_.materials.find(ref->name);
    if (m == names_.materials.end()) return error(path, "unknown material " + quoted(ref->name) + in);
    const auto& mat = st.materials(m->second);
    if (mat.has_elastic() && ref->property != "e")
      error(path, "material " + quoted(ref->name) + " is elastic: it has no " + ref->property + " (only e)");
  } else if (ref->kind == "section") {
    const auto s = names_.sections.find(ref->name);
    if (s == names_.sections.end()) return error(path, "unknown section " + quoted(ref->name) + in);
    const auto& sec = st.sections(s->second);
    const bool rect = ref->property == "width" || ref->property == "depth";
    if (sec.has_elastic() && rect)
      error(path, "section " + quoted(ref->name) + " is elastic: it has no " + ref->property +
                      " (e, area or inertia)");
    else if (sec.has_fiber_rectangle() && !rect)
      error(path, "section " + quoted(ref->name) + " is a fiber_rectangle: it has no " + ref->property +
                      " (width or depth; E is its material's)");
  } else if (ref->kind == "beam") {
    if (names_.beams.count(ref->name) == 0) error(path, "unknown beam " + quoted(ref->name) + in);
  } else if (ref->kind == "wavemaker") {
    const auto* motion = wall_motion_named(ref->name);
    if (!motion) return error(path, "no wall " + quoted(ref->name) + " with a motion" + in);
    const std::string& p = ref->property;
    const bool ok = motion->has_sinusoid() ? p == "stroke" || p == "period"
                    : motion->has_solitary() ? p == "height"
                                             : p == "scale";
    if (!ok)
      error(path, "the motion of wall " + quoted(ref->name) + " has no " + p +
                      (motion->has_sinusoid() ? " (a sinusoid: stroke or period)"
                       : motion->has_solitary() ? " (a solitary wave: height)"
                                                : " (a table: scale)"));
  }
}

const pfem::v1::WallMotion* ModelChecker::wall_motion_named(const std::string& name) const {
  for (const auto& w : model_.walls())
    if (w.name() == name && w.has_motion()) return &w.motion();
  return nullptr;
}

void ModelChecker::check_target_value(const std::string& target, double value, const std::string& path) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return;
  if (ref->property == "mu") {
    if (value < 0) error(path, "must be >= 0 for " + target);
  } else if (ref->property == "hardening_ratio") {
    if (value < 0 || value >= 1) error(path, "must be in [0, 1) for " + target);
  } else if (!(value > 0)) {
    error(path, "must be > 0 for " + target);
  } else if (ref->kind == "wavemaker" && ref->property == "height") {
    const auto* motion = wall_motion_named(ref->name);
    if (motion && motion->has_solitary() && value > 0.6 * motion->solitary().depth())
      error(path, "must be at most 0.6 of the solitary wave's depth for " + target);
  }
}

// ---------------------------------------------------------------------------------------------
// structure

void ModelChecker::collect_structure_names() {
  names_ = {};
  const auto& st = model_.structure();
  const auto collect = [](std::map<std::string, int>& names, const auto& items) {
    for (int i = 0; i < items.size(); ++i)
      if (valid_name(items[i].name())) names.emplace(items[i].name(), i);  // first one wins
  };
  collect(names_.nodes, st.nodes());
  collect(names_.materials, st.materials());
  collect(names_.sections, st.sections());
  collect(names_.beams, st.beams());
}

bool ModelChecker::is_structure_node(const std::string& name) const {
  if (names_.nodes.count(name) > 0) return true;
  const auto generated = split_generated_name(name);
  if (!generated) return false;
  const auto b = names_.beams.find(generated->first);
  if (b == names_.beams.end()) return false;
  const auto& beam = model_.structure().beams(b->second);
  return beam_elements_valid(beam) && generated->second < beam.elements();
}

int ModelChecker::beam_of_element(const std::string& name) const {
  const auto generated = split_generated_name(name);
  if (!generated) return -1;
  const auto b = names_.beams.find(generated->first);
  if (b == names_.beams.end()) return -1;
  const auto& beam = model_.structure().beams(b->second);
  return beam_elements_valid(beam) && generated->second <= beam.elements() ? b->second : -1;
}

void ModelChecker::check_structure() {
  if (!model_.has_structure()) return;
  check_structure_nodes();
  check_materials();
  check_sections();
  check_beams();
  if (errors_.empty()) check_beam_crossings();
  if (model_.structure().has_rayleigh()) {
    non_negative("structure.rayleigh.a0", model_.structure().rayleigh().a0());
    non_negative("structure.rayleigh.a1", model_.structure().rayleigh().a1());
  }
}

namespace {
// Required, well-formed, unique: the name rules shared by every kind of structure component.
template <typename Items>
void check_names(const Items& items, const std::string& path, std::vector<FieldError>& errors) {
  std::set<std::string> seen;
  for (int i = 0; i < items.size(); ++i) {
    const std::string& name = items[i].name();
    const std::string p = at(path, i) + ".name";
    if (name.empty()) errors.push_back({p, "is required"});
    else if (!valid_name(name))
      errors.push_back({p, "must use only letters, digits, '_' and '-' (got '" + name + "')"});
    else if (!seen.insert(name).second) errors.push_back({p, "'" + name + "' is used twice"});
  }
}
}  // namespace

void ModelChecker::check_structure_nodes() {
  const auto& st = model_.structure();
  check_names(st.nodes(), "structure.nodes", errors_);
  std::set<std::string> connected;
  for (const auto& b : st.beams()) connected.insert({b.from_node(), b.to_node()});
  for (int i = 0; i < st.nodes_size(); ++i) {
    const auto& n = st.nodes(i);
    const std::string path = at("structure.nodes", i);
    finite(path + ".x", n.x());
    finite(path + ".y", n.y());
    if (n.has_mass()) {
      non_negative(path + ".mass.x", n.mass().x());
      non_negative(path + ".mass.y", n.mass().y());
      non_negative(path + ".mass.rz", n.mass().rz());
    }
    if (n.has_load()) {
      finite(path + ".load.x", n.load().x());
      finite(path + ".load.y", n.load().y());
      finite(path + ".load.rz", n.load().rz());
    }
    const auto known = names_.nodes.find(n.name());
    if (known != names_.nodes.end() && known->second == i && connected.count(n.name()) == 0)
      error(path, "is not connected to any beam");
  }
}

void ModelChecker::check_materials() {
  const auto& st = model_.structure();
  check_names(st.materials(), "structure.materials", errors_);
  for (int i = 0; i < st.materials_size(); ++i) {
    const auto& m = st.materials(i);
    const std::string path = at("structure.materials", i);
    if (m.has_elastic()) {
      positive(path + ".elastic.e", m.elastic().e());
    } else if (m.has_bilinear()) {
      positive(path + ".bilinear.fy", m.bilinear().fy());
      positive(path + ".bilinear.e0", m.bilinear().e0());
      const double b = m.bilinear().hardening_ratio();
      if (!std::isfinite(b) || b < 0.0 || b >= 1.0)
        error(path + ".bilinear.hardening_ratio", "must be in [0, 1)");
    } else {
      error(path, "needs a kind: elastic or bilinear");
    }
  }
}

void ModelChecker::check_sections() {
  const auto& st = model_.structure();
  check_names(st.sections(), "structure.sections", errors_);
  for (int i = 0; i < st.sections_size(); ++i) {
    const auto& s = st.sections(i);
    const std::string path = at("structure.sections", i);
    if (s.has_elastic()) {
      positive(path + ".elastic.e", s.elastic().e());
      positive(path + ".elastic.area", s.elastic().area());
      positive(path + ".elastic.inertia", s.elastic().inertia());
    } else if (s.has_fiber_rectangle()) {
      const auto& f = s.fiber_rectangle();
      positive(path + ".fiber_rectangle.width", f.width());
      positive(path + ".fiber_rectangle.depth", f.depth());
      if (f.fibers() < 1) error(path + ".fiber_rectangle.fibers", "must be >= 1");
      else if (f.fibers() > kMaxFibers)
        error(path + ".fiber_rectangle.fibers", "must be <= " + std::to_string(kMaxFibers));
      if (f.material().empty()) error(path + ".fiber_rectangle.material", "is required");
      else if (names_.materials.count(f.material()) == 0)
        error(path + ".fiber_rectangle.material", "unknown material '" + f.material() + "'");
    } else {
      error(path, "needs a kind: elastic or fiber_rectangle");
    }
  }
}

void ModelChecker::check_beams() {
  const auto& st = model_.structure();
  check_names(st.beams(), "structure.beams", errors_);
  for (int i = 0; i < st.beams_size(); ++i) {
    const auto& b = st.beams(i);
    const std::string path = at("structure.beams", i);
    const auto end_node = [&](const std::string& name, const char* field) -> const pfem::v1::StructureNode* {
      if (name.empty()) {
        error(path + "." + field, "is required (the name of a structure node)");
        return nullptr;
      }
      const auto n = names_.nodes.find(name);
      if (n != names_.nodes.end()) return &st.nodes(n->second);
      error(path + "." + field, "unknown node '" + name + "'" +
                                    (is_structure_node(name) ? " (a beam must end at a named structure node, "
                                                               "not at a generated one)"
                                                             : ""));
      return nullptr;
    };
    const auto* from = end_node(b.from_node(), "from_node");
    const auto* to = end_node(b.to_node(), "to_node");
    if (b.elements() < 1) error(path + ".elements", "must be >= 1");
    else if (b.elements() > kMaxBeamElements)
      error(path + ".elements", "must be <= " + std::to_string(kMaxBeamElements));
    if (from && to && std::isfinite(from->x()) && std::isfinite(from->y()) && std::isfinite(to->x()) &&
        std::isfinite(to->y())) {
      const double length = std::hypot(to->x() - from->x(), to->y() - from->y());
      const double scale = std::max(std::hypot(from->x(), from->y()), std::hypot(to->x(), to->y()));
      const int n = std::max(1, b.elements());
      if (length == 0.0 || !(length / n > 1e-12 * scale)) error(path, "has zero length");
      const double h = model_.mesh().h();
      if (b.elements() >= 1 && std::isfinite(h) && h > 0 && length / n > kMaxBeamElementSpacings * h) {
        std::ostringstream why;
        why << "gives elements of " << length / n << " m, longer than " << kMaxBeamElementSpacings
            << " mesh.h: water would pass between the beam's nodes; ";
        // Compared as a double: a beam 1e200 m long needs more elements than a long holds.
        const double needed = std::ceil(length / (kMaxBeamElementSpacings * h));
        if (needed <= kMaxBeamElements) {
          why << "use at least " << static_cast<long>(needed);
        } else {
          why << "it would need more than the " << kMaxBeamElements << " elements a beam may have";
        }
        error(path + ".elements", why.str());
      }
    }
    const bool elastic = b.element_type() == "elastic";
    if (b.element_type().empty())
      error(path + ".element_type", "is required: elastic or displacement-based");
    else if (!elastic && b.element_type() != "displacement-based")
      error(path + ".element_type",
            "unknown element type '" + b.element_type() + "'; expected elastic or displacement-based");
    if (b.section().empty()) {
      error(path + ".section", "is required");
    } else if (const auto s = names_.sections.find(b.section()); s == names_.sections.end()) {
      error(path + ".section", "unknown section '" + b.section() + "'");
    } else if (elastic && st.sections(s->second).has_fiber_rectangle()) {
      const auto& material = st.sections(s->second).fiber_rectangle().material();
      const auto m = names_.materials.find(material);
      if (m != names_.materials.end() && !st.materials(m->second).has_elastic())
        error(path + ".section", "an elastic beam needs an elastic section or a fiber_rectangle of an elastic "
                                 "material; section '" + b.section() + "' uses material '" + material +
                                     "', which is not elastic");
    }
    if (b.has_transformation() && b.transformation() != "corotational" && b.transformation() != "linear")
      error(path + ".transformation",
            "unknown transformation '" + b.transformation() + "'; expected corotational or linear");
    if (b.has_integration_points() && elastic)
      error(path + ".integration_points", "is for displacement-based beams (an elastic beam has none)");
    else if (b.has_integration_points() &&
             (b.integration_points() < 1 || b.integration_points() > kMaxIntegrationPoints))
      error(path + ".integration_points", "must be in 1.." + std::to_string(kMaxIntegrationPoints));
    if (b.has_mass() && b.mass() != "lumped" && b.mass() != "consistent")
      error(path + ".mass", "unknown mass '" + b.mass() + "'; expected lumped or consistent");
    positive(path + ".rho", b.rho());
  }
}

void ModelChecker::check_beam_crossings() {
  const auto& st = model_.structure();
  const auto point = [&](const std::string& node) {
    const auto& n = st.nodes(names_.nodes.at(node));
    return std::array<double, 2>{n.x(), n.y()};
  };
  const auto report = [&](int i, SegmentContact contact, const std::string& other) {
    if (contact == SegmentContact::kCross) error(at("structure.beams", i), "crosses " + other);
    if (contact == SegmentContact::kOverlap) error(at("structure.beams", i), "lies along " + other);
  };
  for (int i = 0; i < st.beams_size(); ++i) {
    const auto a = point(st.beams(i).from_node()), b = point(st.beams(i).to_node());
    for (int w = 0; w < model_.walls_size(); ++w) {
      const auto& pts = model_.walls(w).points();
      const int pieces = pts.size() - 1 + (model_.walls(w).closed() && pts.size() > 2 ? 1 : 0);
      SegmentContact worst = SegmentContact::kNone;
      for (int k = 0; k < pieces; ++k) {
        const auto& p = pts[k];
        const auto& q = pts[(k + 1) % pts.size()];
        const auto c = segment_contact(a[0], a[1], b[0], b[1], p.x(), p.y(), q.x(), q.y());
        if (c == SegmentContact::kCross || c == SegmentContact::kOverlap) worst = c;
      }
      report(i, worst, at("walls", w));
    }
    for (int j = i + 1; j < st.beams_size(); ++j) {
      const auto c = point(st.beams(j).from_node()), d = point(st.beams(j).to_node());
      report(i, segment_contact(a[0], a[1], b[0], b[1], c[0], c[1], d[0], d[1]), at("structure.beams", j));
    }
  }
}

}  // namespace pfem
