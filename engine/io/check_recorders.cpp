#include "engine/io/model_checks.h"

#include <cmath>
#include <set>
#include <string>

#include "engine/io/geometry_bounds.h"
#include "engine/io/section_checks.h"

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

void check_boundary_recorder(const pfem::v1::Model& model, const pfem::v1::Recorder& r, const std::string& path,
                             FieldChecker& out) {
  if (!r.has_boundary())
    return out.error(path, "quantity '" + r.quantity() + "' needs a target: boundary (a wall or beam name)");
  int matches = 0;
  for (const auto& w : model.walls()) matches += w.name() == r.boundary();
  for (const auto& b : model.structure().beams()) matches += b.name() == r.boundary();
  if (matches == 0) out.error(path + ".boundary", "no wall or beam is named " + quoted(r.boundary()));
  else if (matches > 1) out.error(path + ".boundary", quoted(r.boundary()) + " names more than one wall or beam");
  if (r.has_about()) {
    out.finite(path + ".about.x", r.about().x());
    out.finite(path + ".about.y", r.about().y());
  }
}

void check_point(const pfem::v1::Model& model, const pfem::v1::Recorder& r, const std::string& path,
                 FieldChecker& out) {
  out.finite(path + ".point.x", r.point().x());
  out.finite(path + ".point.y", r.point().y());
  const Bounds domain = domain_bounds(model);
  if (domain.valid() && std::isfinite(r.point().x()) && std::isfinite(r.point().y()) &&
      !domain.contains(Bounds{r.point().x(), r.point().y(), r.point().x(), r.point().y()}, 0.0))
    out.error(path + ".point", "lies outside the domain");
}

void check_element_recorder(const pfem::v1::Model& model, const StructureNames& names, const pfem::v1::Recorder& r,
                            const std::string& path, FieldChecker& out) {
  const std::string& q = r.quantity();
  if (!r.has_element()) return out.error(path, "quantity '" + q + "' needs a target: element (\"<beam>/<k>\")");
  const int b = names.beam_of_element(r.element());
  if (b < 0) return out.error(path + ".element", "unknown element '" + r.element() + "'");
  if (q == "basic_force") {
    if (r.component() < 0 || r.component() > 2)
      out.error(path + ".component", "must be in 0..2 (0 = N, 1 = M_i, 2 = M_j) (got " +
                                         std::to_string(r.component()) + ")");
    return;
  }
  const auto& beam = model.structure().beams(b);
  const auto section = names.sections.find(beam.section());
  const bool fibers = beam.element_type() == "displacement-based" && section != names.sections.end() &&
                      model.structure().sections(section->second).has_fiber_rectangle();
  if (!fibers)
    return out.error(path + ".element", "element '" + r.element() + "' has no fibers: " + q +
                                            " needs a displacement-based beam with a fiber_rectangle section");
  const int points = beam.has_integration_points() ? beam.integration_points() : 2;
  if (r.section_point() < 0 || r.section_point() >= points)
    out.error(path + ".section_point", "must be in 0.." + std::to_string(points - 1) + " (got " +
                                           std::to_string(r.section_point()) + ")");
  const int n = model.structure().sections(section->second).fiber_rectangle().fibers();
  if (r.fiber() < 0 || r.fiber() >= n)
    out.error(path + ".fiber", "must be in 0.." + std::to_string(n - 1) + " (got " + std::to_string(r.fiber()) + ")");
}

}  // namespace

bool is_nodal_quantity(const std::string& q) { return nodal_quantities().count(q) > 0; }
bool is_element_quantity(const std::string& q) { return element_quantities().count(q) > 0; }
bool is_global_quantity(const std::string& q) { return global_quantities().count(q) > 0; }
bool is_point_quantity(const std::string& q) { return point_quantities().count(q) > 0; }

void check_recorders(const pfem::v1::Model& model, const StructureNames& components, FieldChecker& out) {
  std::set<std::string> names;
  for (int i = 0; i < model.recorders_size(); ++i) {
    const auto& r = model.recorders(i);
    const std::string path = at("recorders", i);
    if (r.name().empty()) out.error(path + ".name", "is required");
    else if (r.name().find_first_of(",\"\n ") != std::string::npos)
      out.error(path + ".name", "must not contain commas, quotes, spaces or newlines");
    else if (!names.insert(r.name()).second) out.error(path + ".name", "'" + r.name() + "' is used twice");
    if (is_nodal_quantity(r.quantity())) {
      const bool rz = r.quantity() == "rz";
      if (r.has_point()) {
        if (rz) out.error(path + ".point", "quantity 'rz' needs a structure node (node), not a point");
        check_point(model, r, path, out);
      } else if (r.has_node()) {
        if (!components.is_structure_node(r.node())) out.error(path + ".node", "unknown node '" + r.node() + "'");
      } else if (r.has_element()) {
        out.error(path + ".element", "quantity '" + r.quantity() + "' is sampled at a node" +
                                         (rz ? "" : " or a point") + ", not an element");
      } else {
        out.error(path, "quantity '" + r.quantity() + "' needs a target: " + (rz ? "node" : "node or point"));
      }
    } else if (is_element_quantity(r.quantity())) {
      check_element_recorder(model, components, r, path, out);
    } else if (is_point_quantity(r.quantity())) {
      if (r.has_point()) check_point(model, r, path, out);
      else out.error(path, "quantity '" + r.quantity() + "' needs a target: point");
    } else if (boundary_quantities().count(r.quantity())) {
      check_boundary_recorder(model, r, path, out);
    } else if (!is_global_quantity(r.quantity())) {
      out.error(path + ".quantity", "unknown quantity '" + r.quantity() + "'; expected one of " +
                                        listed(nodal_quantities()) + ", " + listed(element_quantities()) +
                                        ", " + listed(point_quantities()) + ", " + listed(boundary_quantities()) +
                                        ", " + listed(global_quantities()));
    }
    if (r.has_boundary() && !boundary_quantities().count(r.quantity()))
      out.error(path + ".boundary", "only for the quantities " + listed(boundary_quantities()));
    if (r.has_about() && r.quantity() != "moment") out.error(path + ".about", "only for the quantity moment");
  }
}

}  // namespace pfem
