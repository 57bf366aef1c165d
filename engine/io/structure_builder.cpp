#include "engine/io/structure_builder.h"

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "engine/io/field_checker.h"  // at()
#include "engine/io/model_checks.h"
#include "engine/structure/bilinear_material.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/elastic_material.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/fiber_section.h"

namespace pfem {

namespace {

// A library error "field: rule (got x)" at prefix + fields[field] (an empty mapped field is the
// prefix itself). Fields the map does not know keep the library's whole message at prefix.
FieldError library_error(const std::invalid_argument& e, const std::string& prefix,
                         const std::map<std::string, std::string>& fields) {
  const std::string what = e.what();
  const auto colon = what.find(": ");
  if (colon != std::string::npos) {
    const auto f = fields.find(what.substr(0, colon));
    if (f != fields.end()) return {prefix + f->second, what.substr(colon + 2)};
  }
  return {prefix, what};
}

// A built section: the object for displacement-based beams and, when the section is elastic
// (or a rectangle of an elastic material), its properties (and their seeds) for elastic beams.
struct BuiltSection {
  std::unique_ptr<structure::Section> section;
  std::optional<structure::ElasticSectionProperties> elastic;
  structure::Seeds<structure::ElasticSectionProperties> elastic_seeds;
};

template <typename Items>
int find_named(const Items& items, const std::string& name) {
  for (int i = 0; i < items.size(); ++i)
    if (items[i].name() == name) return i;
  return -1;
}

void seed_material(structure::UniaxialMaterial& material, int k, const structure::BilinearParameters& d) {
  if (auto* e = dynamic_cast<structure::ElasticMaterial*>(&material)) e->set_modulus_seed(k, d.e0);
  if (auto* b = dynamic_cast<structure::BilinearMaterial*>(&material)) b->set_parameter_seed(k, d);
}

// d(E, b d, b d^3/12) of an elastic material's rectangle.
structure::ElasticSectionProperties rectangle_seed(double b, double d, double dE,
                                                   const structure::RectangleSeed& r) {
  return {dE, r.width * d + b * r.depth, (r.width * d * d * d + 3.0 * b * d * d * r.depth) / 12.0};
}

structure::TransfKind transformation(const pfem::v1::Beam& b) {
  return b.has_transformation() && b.transformation() == "linear" ? structure::TransfKind::kLinear
                                                                  : structure::TransfKind::kCorotational;
}

}  // namespace

StructureBuild build_structure(const pfem::v1::Model& model, const std::vector<ParameterSeed>& seeds, bool validated) {
  if (!validated)
    if (auto errors = validate_structure(model); !errors.empty()) throw ModelError(std::move(errors));
  StructureBuild out;
  if (!model.has_structure()) return out;
  const auto& st = model.structure();
  const int P = static_cast<int>(seeds.size());
  auto& sm = out.model;
  std::vector<FieldError> errors;

  for (int i = 0; i < st.nodes_size(); ++i) {
    const auto& n = st.nodes(i);
    const std::string path = at("structure.nodes", i);
    try {
      const int index = sm.add_node(n.x(), n.y());
      if (n.has_support()) sm.fix(index, n.support().ux(), n.support().uy(), n.support().rz());
      if (n.has_mass()) sm.add_nodal_mass(index, n.mass().x(), n.mass().y(), n.mass().rz());
      if (n.has_load()) sm.add_nodal_load(index, n.load().x(), n.load().y(), n.load().rz());
    } catch (const std::invalid_argument& e) {
      errors.push_back(library_error(e, path, {{"x", ""}, {"mass", ".mass"}}));
      continue;
    }
    out.node_index.emplace(n.name(), i);
    out.node_names.push_back(n.name());
  }
  if (!errors.empty()) throw ModelError(std::move(errors));  // node indices would shift

  std::vector<std::unique_ptr<structure::UniaxialMaterial>> materials(st.materials_size());
  for (int i = 0; i < st.materials_size(); ++i) {
    const auto& m = st.materials(i);
    const std::string path = at("structure.materials", i);
    try {
      if (m.has_elastic()) {
        materials[i] = std::make_unique<structure::ElasticMaterial>(m.elastic().e());
      } else {
        const auto& b = m.bilinear();
        materials[i] = std::make_unique<structure::BilinearMaterial>(b.fy(), b.e0(), b.hardening_ratio());
      }
      for (int k = 0; k < P; ++k) seed_material(*materials[i], k, seeds[k].materials[i]);
    } catch (const std::invalid_argument& e) {
      errors.push_back(library_error(e, path,
                                     {{"e", ".elastic.e"},
                                      {"fy", ".bilinear.fy"},
                                      {"e0", ".bilinear.e0"},
                                      {"hardening_ratio", ".bilinear.hardening_ratio"}}));
    }
  }

  std::vector<BuiltSection> sections(st.sections_size());
  for (int i = 0; i < st.sections_size(); ++i) {
    const auto& s = st.sections(i);
    const std::string path = at("structure.sections", i);
    try {
      if (s.has_elastic()) {
        const structure::ElasticSectionProperties p{s.elastic().e(), s.elastic().area(),
                                                    s.elastic().inertia()};
        auto section = std::make_unique<structure::ElasticSection>(p);
        for (int k = 0; k < P; ++k) {
          section->set_property_seed(k, seeds[k].sections[i].elastic);
          sections[i].elastic_seeds.set(k, seeds[k].sections[i].elastic);
        }
        sections[i].section = std::move(section);
        sections[i].elastic = p;
      } else {
        const auto& f = s.fiber_rectangle();
        const int m = find_named(st.materials(), f.material());
        const auto* material = materials[m].get();
        if (!material) continue;  // its own error is reported
        auto section = std::make_unique<structure::FiberSection>(
            *material, structure::FiberSectionGeometry{f.width(), f.depth(), f.fibers()});
        for (int k = 0; k < P; ++k) section->set_geometry_seed(k, seeds[k].sections[i].rectangle);
        sections[i].section = std::move(section);
        if (const auto* e = dynamic_cast<const structure::ElasticMaterial*>(material)) {
          const double b = f.width(), d = f.depth();
          sections[i].elastic =
              structure::ElasticSectionProperties{e->youngs_modulus(), b * d, b * d * d * d / 12.0};
          for (int k = 0; k < P; ++k)
            sections[i].elastic_seeds.set(
                k, rectangle_seed(b, d, seeds[k].materials[m].e0, seeds[k].sections[i].rectangle));
        }
      }
    } catch (const std::invalid_argument& e) {
      errors.push_back(library_error(e, path,
                                     {{"e", ".elastic.e"},
                                      {"a", ".elastic.area"},
                                      {"i", ".elastic.inertia"},
                                      {"width", ".fiber_rectangle.width"},
                                      {"depth", ".fiber_rectangle.depth"},
                                      {"fibers", ".fiber_rectangle.fibers"}}));
    }
  }

  for (int i = 0; i < st.beams_size(); ++i) {
    const auto& b = st.beams(i);
    const std::string path = at("structure.beams", i);
    const int from = out.node_index.at(b.from_node());
    const int to = out.node_index.at(b.to_node());
    const auto& section = sections[find_named(st.sections(), b.section())];
    const int n = b.elements();
    std::vector<int> nodes{from};
    const auto xi = sm.node(from).x, xj = sm.node(to).x;
    for (int k = 1; k < n; ++k) {
      const structure::Vec2 x = xi + (xj - xi) * (static_cast<double>(k) / n);
      const int index = sm.add_node(x(0), x(1));
      const std::string name = b.name() + "/" + std::to_string(k);
      out.node_index.emplace(name, index);
      out.node_names.push_back(name);
      nodes.push_back(index);
    }
    nodes.push_back(to);
    out.beam_nodes.push_back(nodes);
    out.beam_elements.emplace_back();
    if (!section.section) continue;  // its own error is reported

    structure::BeamOptions options;
    options.transf = transformation(b);
    options.mass = b.has_mass() && b.mass() == "consistent" ? structure::MassKind::kConsistent
                                                            : structure::MassKind::kLumped;
    options.rho = b.rho();
    for (int k = 0; k < P; ++k) options.rho_seeds.set(k, seeds[k].beam_rho[i]);
    const bool elastic = b.element_type() == "elastic";
    const int points = b.has_integration_points() ? b.integration_points() : 2;
    try {
      for (int k = 1; k <= n; ++k) {
        const int e = elastic ? sm.add_elastic_beam(nodes[k - 1], nodes[k], *section.elastic, options,
                                                    section.elastic_seeds)
                              : sm.add_disp_beam(nodes[k - 1], nodes[k], *section.section, options, points);
        const std::string name = b.name() + "/" + std::to_string(k);
        out.element_index.emplace(name, e);
        out.element_names.push_back(name);
        out.beam_elements.back().push_back(e);
      }
    } catch (const std::invalid_argument& e) {
      FieldError error =
          library_error(e, path, {{"integration_points", ".integration_points"}, {"rho", ".rho"}});
      if (std::string(e.what()).rfind("length: ", 0) == 0) error = {path, "has zero length"};
      errors.push_back(error);
    }
  }

  if (st.has_rayleigh()) {
    try {
      sm.set_rayleigh({st.rayleigh().a0(), st.rayleigh().a1()});
    } catch (const std::invalid_argument& e) {
      errors.push_back(library_error(e, "structure.rayleigh", {{"a0", ".a0"}, {"a1", ".a1"}}));
    }
  }
  if (!errors.empty()) throw ModelError(std::move(errors));
  sm.set_num_parameters(P);
  return out;
}

}  // namespace pfem
