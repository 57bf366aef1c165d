#include "engine/io/structure_builder.h"

#include <functional>
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

// The seeds the sensitivity targets ask for, [parameter k][component index].
struct SectionSeed {
  structure::RectangleSeed rectangle;             // fiber_rectangle: width, depth
  structure::ElasticSectionProperties elastic{};  // elastic: e, area, inertia
};
struct TargetSeeds {
  std::vector<std::vector<structure::BilinearParameters>> material;  // e0 holds E of an elastic one
  std::vector<std::vector<SectionSeed>> section;
  std::vector<std::vector<double>> rho;  // per beam
};

TargetSeeds target_seeds(const pfem::v1::Model& model, const std::vector<std::vector<SeedTarget>>& targets) {
  const auto& st = model.structure();
  const int P = static_cast<int>(targets.size());
  TargetSeeds seeds{std::vector(P, std::vector<structure::BilinearParameters>(st.materials_size())),
                    std::vector(P, std::vector<SectionSeed>(st.sections_size())),
                    std::vector(P, std::vector<double>(st.beams_size(), 0.0))};
  std::vector<FieldError> errors;
  for (int k = 0; k < P; ++k) {
    for (int j = 0; j < static_cast<int>(targets[k].size()); ++j) {
      const auto& [target, weight] = targets[k][j];
      try {
        model_target_value(model, target, at(at("sensitivity_targets", k), j));  // resolves
      } catch (const ModelError& e) {
        errors.insert(errors.end(), e.errors().begin(), e.errors().end());
        continue;
      }
      const auto ref = *parse_parameter_target(target);
      const std::string& p = ref.property;
      if (ref.kind == "material") {
        auto& m = seeds.material[k][find_named(st.materials(), ref.name)];
        (p == "e" ? m.e0 : p == "fy" ? m.fy : m.b) += weight;
      } else if (ref.kind == "section") {
        auto& s = seeds.section[k][find_named(st.sections(), ref.name)];
        (p == "width"   ? s.rectangle.width
         : p == "depth" ? s.rectangle.depth
         : p == "e"     ? s.elastic.E
         : p == "area"  ? s.elastic.A
                        : s.elastic.I) += weight;
      } else if (ref.kind == "beam") {
        seeds.rho[k][find_named(st.beams(), ref.name)] += weight;
      }  // fluid, thickness and wavemaker targets belong to the fluid and the walls
    }
  }
  if (!errors.empty()) throw ModelError(std::move(errors));
  return seeds;
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

// The proto field a target addresses: get() reads through const accessors only, set() writes.
struct TargetField {
  std::function<double()> get;
  std::function<void(double)> set;
};

TargetField resolve_target(pfem::v1::Model& model, const std::string& target, const std::string& path) {
  const auto ref = parse_parameter_target(target);
  if (!ref) throw ModelError(path, "unknown target '" + target + "'");
  const auto& cm = model;
  if (ref->kind == "fluid") {
    if (ref->property == "rho")
      return {[&] { return cm.fluid().rho(); }, [&](double v) { model.mutable_fluid()->set_rho(v); }};
    if (ref->property == "mu")
      return {[&] { return cm.fluid().mu(); }, [&](double v) { model.mutable_fluid()->set_mu(v); }};
    return {[&] { return cm.fluid().kappa(); }, [&](double v) { model.mutable_fluid()->set_kappa(v); }};
  }
  if (ref->kind == "thickness")
    return {[&] { return cm.has_thickness() ? cm.thickness() : 1.0; },
            [&](double v) { model.set_thickness(v); }};

  const std::string in = "' in target '" + target + "'";
  const auto no_property = [&](const std::string& what) {
    return ModelError(path, what + " '" + ref->name + "' has no " + ref->property);
  };
  if (ref->kind == "wavemaker") {
    const int i = find_named(cm.walls(), ref->name);
    if (i < 0 || !cm.walls(i).has_motion()) throw ModelError(path, "no moving wall '" + ref->name + in);
    auto m = [&model, i] { return model.mutable_walls(i)->mutable_motion(); };
    const auto& c = cm.walls(i).motion();
    const std::string& p = ref->property;
    if (c.has_sinusoid() && p == "stroke")
      return {[&c] { return c.sinusoid().stroke(); }, [m](double v) { m()->mutable_sinusoid()->set_stroke(v); }};
    if (c.has_sinusoid() && p == "period")
      return {[&c] { return c.sinusoid().period(); }, [m](double v) { m()->mutable_sinusoid()->set_period(v); }};
    if (c.has_solitary() && p == "height")
      return {[&c] { return c.solitary().height(); }, [m](double v) { m()->mutable_solitary()->set_height(v); }};
    if (c.has_table() && p == "scale")
      return {[&c] { return c.table().has_scale() ? c.table().scale() : 1.0; },
              [m](double v) { m()->mutable_table()->set_scale(v); }};
    throw no_property(c.has_sinusoid() ? "sinusoid wall motion" : c.has_solitary() ? "solitary wall motion"
                                                                                  : "wall motion table");
  }

  const auto& st = cm.structure();
  if (ref->kind == "material") {
    const int i = find_named(st.materials(), ref->name);
    if (i < 0) throw ModelError(path, "unknown material '" + ref->name + in);
    auto m = [&model, i] { return model.mutable_structure()->mutable_materials(i); };
    const auto& c = st.materials(i);
    if (c.has_elastic() && ref->property == "e")
      return {[&c] { return c.elastic().e(); }, [m](double v) { m()->mutable_elastic()->set_e(v); }};
    if (c.has_bilinear()) {
      if (ref->property == "e")
        return {[&c] { return c.bilinear().e0(); }, [m](double v) { m()->mutable_bilinear()->set_e0(v); }};
      if (ref->property == "fy")
        return {[&c] { return c.bilinear().fy(); }, [m](double v) { m()->mutable_bilinear()->set_fy(v); }};
      return {[&c] { return c.bilinear().hardening_ratio(); },
              [m](double v) { m()->mutable_bilinear()->set_hardening_ratio(v); }};
    }
    throw no_property(c.has_elastic() ? "elastic material" : "material");
  }
  if (ref->kind == "section") {
    const int i = find_named(st.sections(), ref->name);
    if (i < 0) throw ModelError(path, "unknown section '" + ref->name + in);
    auto s = [&model, i] { return model.mutable_structure()->mutable_sections(i); };
    const auto& c = st.sections(i);
    const std::string& p = ref->property;
    if (c.has_fiber_rectangle() && p == "width")
      return {[&c] { return c.fiber_rectangle().width(); },
              [s](double v) { s()->mutable_fiber_rectangle()->set_width(v); }};
    if (c.has_fiber_rectangle() && p == "depth")
      return {[&c] { return c.fiber_rectangle().depth(); },
              [s](double v) { s()->mutable_fiber_rectangle()->set_depth(v); }};
    if (c.has_elastic() && p == "e")
      return {[&c] { return c.elastic().e(); }, [s](double v) { s()->mutable_elastic()->set_e(v); }};
    if (c.has_elastic() && p == "area")
      return {[&c] { return c.elastic().area(); }, [s](double v) { s()->mutable_elastic()->set_area(v); }};
    if (c.has_elastic() && p == "inertia")
      return {[&c] { return c.elastic().inertia(); },
              [s](double v) { s()->mutable_elastic()->set_inertia(v); }};
    throw no_property(c.has_elastic()           ? "elastic section"
                      : c.has_fiber_rectangle() ? "fiber_rectangle section"
                                                : "section");
  }
  const int i = find_named(st.beams(), ref->name);  // kind "beam", property "rho"
  if (i < 0) throw ModelError(path, "unknown beam '" + ref->name + in);
  const auto& c = st.beams(i);
  return {[&c] { return c.rho(); },
          [&model, i](double v) { model.mutable_structure()->mutable_beams(i)->set_rho(v); }};
}

structure::TransfKind transformation(const pfem::v1::Beam& b) {
  return b.has_transformation() && b.transformation() == "linear" ? structure::TransfKind::kLinear
                                                                  : structure::TransfKind::kCorotational;
}

}  // namespace

double model_target_value(const pfem::v1::Model& model, const std::string& target, const std::string& path) {
  // resolve_target's getters only read; the const_cast serves its shared signature.
  return resolve_target(const_cast<pfem::v1::Model&>(model), target, path).get();
}

void set_model_target(pfem::v1::Model& model, const std::string& target, double value,
                      const std::string& path) {
  resolve_target(model, target, path).set(value);
}

void apply_parameter_overrides(pfem::v1::Model& model) {
  std::vector<FieldError> errors;
  for (int i = 0; i < model.parameters_size(); ++i) {
    const auto p = model.parameters(i);  // a copy: setting a target may touch the model
    if (!p.has_value()) continue;
    for (int k = 0; k < p.targets_size(); ++k) {
      try {
        set_model_target(model, p.targets(k), p.value(), at(at("parameters", i) + ".targets", k));
      } catch (const ModelError& e) {
        errors.insert(errors.end(), e.errors().begin(), e.errors().end());
      }
    }
  }
  if (!errors.empty()) throw ModelError(std::move(errors));
}

StructureBuild build_structure(const pfem::v1::Model& model,
                               const std::vector<std::vector<SeedTarget>>& sensitivity_targets, bool validated) {
  if (!validated)
    if (auto errors = validate_structure(model); !errors.empty()) throw ModelError(std::move(errors));
  StructureBuild out;
  if (!model.has_structure()) return out;
  const auto& st = model.structure();
  const TargetSeeds seeds = target_seeds(model, sensitivity_targets);
  const int P = static_cast<int>(sensitivity_targets.size());
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
      for (int k = 0; k < P; ++k) seed_material(*materials[i], k, seeds.material[k][i]);
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
          section->set_property_seed(k, seeds.section[k][i].elastic);
          sections[i].elastic_seeds.set(k, seeds.section[k][i].elastic);
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
        for (int k = 0; k < P; ++k) section->set_geometry_seed(k, seeds.section[k][i].rectangle);
        sections[i].section = std::move(section);
        if (const auto* e = dynamic_cast<const structure::ElasticMaterial*>(material)) {
          const double b = f.width(), d = f.depth();
          sections[i].elastic =
              structure::ElasticSectionProperties{e->youngs_modulus(), b * d, b * d * d * d / 12.0};
          for (int k = 0; k < P; ++k)
            sections[i].elastic_seeds.set(
                k, rectangle_seed(b, d, seeds.material[k][m].e0, seeds.section[k][i].rectangle));
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
    for (int k = 0; k < P; ++k) options.rho_seeds.set(k, seeds.rho[k][i]);
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
