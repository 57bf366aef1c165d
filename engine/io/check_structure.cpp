#include "engine/io/section_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "engine/io/geometry_bounds.h"

namespace pfem {

namespace {
// Beam elements longer than this many particle spacings let water through: a particle at
// h/2 from an element of length l makes a triangle of circumradius (l^2 + h^2) / (4 h) with its
// ends, which fails the alpha test (1.2 h by default) once l approaches 2 h; the particle is
// then in no triangle, falls through the beam and is taken out.
constexpr double kMaxBeamElementSpacings = 1.5;
constexpr int kMaxFibers = 1000;
constexpr int kMaxIntegrationPoints = 10;  // as structure::DispBeamColumn2d

// Required, well-formed, unique: the name rules shared by every kind of structure component.
template <typename Items>
void check_names(const Items& items, const std::string& path, FieldChecker& out) {
  std::set<std::string> seen;
  for (int i = 0; i < items.size(); ++i) {
    const std::string& name = items[i].name();
    const std::string p = at(path, i) + ".name";
    if (name.empty()) out.error(p, "is required");
    else if (!valid_name(name))
      out.error(p, "must use only letters, digits, '_' and '-' (got '" + name + "')");
    else if (!seen.insert(name).second) out.error(p, "'" + name + "' is used twice");
  }
}

void check_structure_nodes(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out) {
  const auto& st = model.structure();
  check_names(st.nodes(), "structure.nodes", out);
  std::set<std::string> connected;
  for (const auto& b : st.beams()) connected.insert({b.from_node(), b.to_node()});
  for (int i = 0; i < st.nodes_size(); ++i) {
    const auto& n = st.nodes(i);
    const std::string path = at("structure.nodes", i);
    out.finite(path + ".x", n.x());
    out.finite(path + ".y", n.y());
    if (n.has_mass()) {
      out.non_negative(path + ".mass.x", n.mass().x());
      out.non_negative(path + ".mass.y", n.mass().y());
      out.non_negative(path + ".mass.rz", n.mass().rz());
    }
    if (n.has_load()) {
      out.finite(path + ".load.x", n.load().x());
      out.finite(path + ".load.y", n.load().y());
      out.finite(path + ".load.rz", n.load().rz());
    }
    const auto known = names.nodes.find(n.name());
    if (known != names.nodes.end() && known->second == i && connected.count(n.name()) == 0)
      out.error(path, "is not connected to any beam");
  }
}

void check_materials(const pfem::v1::Model& model, FieldChecker& out) {
  const auto& st = model.structure();
  check_names(st.materials(), "structure.materials", out);
  for (int i = 0; i < st.materials_size(); ++i) {
    const auto& m = st.materials(i);
    const std::string path = at("structure.materials", i);
    if (m.has_elastic()) {
      out.positive(path + ".elastic.e", m.elastic().e());
    } else if (m.has_bilinear()) {
      out.positive(path + ".bilinear.fy", m.bilinear().fy());
      out.positive(path + ".bilinear.e0", m.bilinear().e0());
      const double b = m.bilinear().hardening_ratio();
      if (!std::isfinite(b) || b < 0.0 || b >= 1.0)
        out.error(path + ".bilinear.hardening_ratio", "must be in [0, 1)");
    } else {
      out.error(path, "needs a kind: elastic or bilinear");
    }
  }
}

void check_sections(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out) {
  const auto& st = model.structure();
  check_names(st.sections(), "structure.sections", out);
  for (int i = 0; i < st.sections_size(); ++i) {
    const auto& s = st.sections(i);
    const std::string path = at("structure.sections", i);
    if (s.has_elastic()) {
      out.positive(path + ".elastic.e", s.elastic().e());
      out.positive(path + ".elastic.area", s.elastic().area());
      out.positive(path + ".elastic.inertia", s.elastic().inertia());
    } else if (s.has_fiber_rectangle()) {
      const auto& f = s.fiber_rectangle();
      out.positive(path + ".fiber_rectangle.width", f.width());
      out.positive(path + ".fiber_rectangle.depth", f.depth());
      if (f.fibers() < 1) out.error(path + ".fiber_rectangle.fibers", "must be >= 1");
      else if (f.fibers() > kMaxFibers)
        out.error(path + ".fiber_rectangle.fibers", "must be <= " + std::to_string(kMaxFibers));
      if (f.material().empty()) out.error(path + ".fiber_rectangle.material", "is required");
      else if (names.materials.count(f.material()) == 0)
        out.error(path + ".fiber_rectangle.material", "unknown material '" + f.material() + "'");
    } else {
      out.error(path, "needs a kind: elastic or fiber_rectangle");
    }
  }
}

void check_beams(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out) {
  const auto& st = model.structure();
  check_names(st.beams(), "structure.beams", out);
  for (int i = 0; i < st.beams_size(); ++i) {
    const auto& b = st.beams(i);
    const std::string path = at("structure.beams", i);
    const auto end_node = [&](const std::string& name, const char* field) -> const pfem::v1::StructureNode* {
      if (name.empty()) {
        out.error(path + "." + field, "is required (the name of a structure node)");
        return nullptr;
      }
      const auto n = names.nodes.find(name);
      if (n != names.nodes.end()) return &st.nodes(n->second);
      out.error(path + "." + field, "unknown node '" + name + "'" +
                                        (names.is_structure_node(name) ? " (a beam must end at a named structure "
                                                                         "node, not at a generated one)"
                                                                       : ""));
      return nullptr;
    };
    const auto* from = end_node(b.from_node(), "from_node");
    const auto* to = end_node(b.to_node(), "to_node");
    if (b.elements() < 1) out.error(path + ".elements", "must be >= 1");
    else if (b.elements() > kMaxBeamElements)
      out.error(path + ".elements", "must be <= " + std::to_string(kMaxBeamElements));
    if (from && to && std::isfinite(from->x()) && std::isfinite(from->y()) && std::isfinite(to->x()) &&
        std::isfinite(to->y())) {
      const double length = std::hypot(to->x() - from->x(), to->y() - from->y());
      const double scale = std::max(std::hypot(from->x(), from->y()), std::hypot(to->x(), to->y()));
      const int n = std::max(1, b.elements());
      if (length == 0.0 || !(length / n > 1e-12 * scale)) out.error(path, "has zero length");
      const double h = model.mesh().h();
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
        out.error(path + ".elements", why.str());
      }
    }
    const bool elastic = b.element_type() == "elastic";
    if (b.element_type().empty())
      out.error(path + ".element_type", "is required: elastic or displacement-based");
    else if (!elastic && b.element_type() != "displacement-based")
      out.error(path + ".element_type",
                "unknown element type '" + b.element_type() + "'; expected elastic or displacement-based");
    if (b.section().empty()) {
      out.error(path + ".section", "is required");
    } else if (const auto s = names.sections.find(b.section()); s == names.sections.end()) {
      out.error(path + ".section", "unknown section '" + b.section() + "'");
    } else if (elastic && st.sections(s->second).has_fiber_rectangle()) {
      const auto& material = st.sections(s->second).fiber_rectangle().material();
      const auto m = names.materials.find(material);
      if (m != names.materials.end() && !st.materials(m->second).has_elastic())
        out.error(path + ".section", "an elastic beam needs an elastic section or a fiber_rectangle of an elastic "
                                     "material; section '" + b.section() + "' uses material '" + material +
                                         "', which is not elastic");
    }
    if (b.has_transformation() && b.transformation() != "corotational" && b.transformation() != "linear")
      out.error(path + ".transformation",
                "unknown transformation '" + b.transformation() + "'; expected corotational or linear");
    if (b.has_integration_points() && elastic)
      out.error(path + ".integration_points", "is for displacement-based beams (an elastic beam has none)");
    else if (b.has_integration_points() &&
             (b.integration_points() < 1 || b.integration_points() > kMaxIntegrationPoints))
      out.error(path + ".integration_points", "must be in 1.." + std::to_string(kMaxIntegrationPoints));
    if (b.has_mass() && b.mass() != "lumped" && b.mass() != "consistent")
      out.error(path + ".mass", "unknown mass '" + b.mass() + "'; expected lumped or consistent");
    out.positive(path + ".rho", b.rho());
  }
}

// Beams may touch walls and each other (a beam standing on the floor) but not cross them or
// lie along them: the triangulation takes both as constraints.
void check_beam_crossings(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out) {
  const auto& st = model.structure();
  const auto point = [&](const std::string& node) {
    const auto& n = st.nodes(names.nodes.at(node));
    return std::array<double, 2>{n.x(), n.y()};
  };
  const auto report = [&](int i, SegmentContact contact, const std::string& other) {
    if (contact == SegmentContact::kCross) out.error(at("structure.beams", i), "crosses " + other);
    if (contact == SegmentContact::kOverlap) out.error(at("structure.beams", i), "lies along " + other);
  };
  for (int i = 0; i < st.beams_size(); ++i) {
    const auto a = point(st.beams(i).from_node()), b = point(st.beams(i).to_node());
    for (int w = 0; w < model.walls_size(); ++w) {
      const auto& pts = model.walls(w).points();
      const int pieces = pts.size() - 1 + (model.walls(w).closed() && pts.size() > 2 ? 1 : 0);
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

}  // namespace

void check_structure(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out) {
  if (!model.has_structure()) return;
  check_structure_nodes(model, names, out);
  check_materials(model, out);
  check_sections(model, names, out);
  check_beams(model, names, out);
  if (out.empty()) check_beam_crossings(model, names, out);
  if (model.structure().has_rayleigh()) {
    out.non_negative("structure.rayleigh.a0", model.structure().rayleigh().a0());
    out.non_negative("structure.rayleigh.a1", model.structure().rayleigh().a1());
  }
}

}  // namespace pfem
