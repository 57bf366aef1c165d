#include "engine/io/parameter_targets.h"

#include <algorithm>

#include "engine/io/field_checker.h"  // at(), quoted()
#include "engine/io/structure_names.h"

namespace pfem {

namespace {

using pfem::v1::Model;

// A kind of target. Texts with {} take the component's name, quoted.
struct Kind {
  const char* name;         // as targets spell it
  const char* placeholder;  // for the name in the list of target forms; nullptr: no component
  // The index of the component of that name, or -1 (nullptr: the kind has no component).
  int (*find)(const Model& m, const std::string& name);
  const char* unknown;  // its message when the model has no such component
  const char* subject;  // the component in a message about a property its form lacks
};

template <typename Items>
int first_named(const Items& items, const std::string& name) {
  for (int i = 0; i < items.size(); ++i)
    if (items[i].name() == name) return i;
  return -1;
}

const Kind kFluid{"fluid", nullptr, nullptr, "", ""};
const Kind kThickness{"thickness", nullptr, nullptr, "", ""};
const Kind kMaterial{"material", "<name>",
                     [](const Model& m, const std::string& n) { return first_named(m.structure().materials(), n); },
                     "unknown material {}", "material {}"};
const Kind kSection{"section", "<name>",
                    [](const Model& m, const std::string& n) { return first_named(m.structure().sections(), n); },
                    "unknown section {}", "section {}"};
const Kind kBeam{"beam", "<name>",
                 [](const Model& m, const std::string& n) { return first_named(m.structure().beams(), n); },
                 "unknown beam {}", "beam {}"};
// The first wall of that name that moves (wall names need not be unique).
const Kind kWavemaker{"wavemaker", "<wall>",
                      [](const Model& m, const std::string& n) {
                        for (int i = 0; i < m.walls_size(); ++i)
                          if (m.walls(i).name() == n && m.walls(i).has_motion()) return i;
                        return -1;
                      },
                      "no wall {} with a motion", "the motion of wall {}"};
const Kind* const kKinds[] = {&kFluid, &kThickness, &kMaterial, &kSection, &kBeam, &kWavemaker};

// One form of a component, which has some of its kind's properties (an elastic material, a
// sinusoid motion). A message about a property it lacks: "<subject> <is>has no <p> (<has>)".
struct Form {
  bool (*holds)(const Model& m, int i);
  const char* is;
  const char* has;
};

const Form kElasticMaterial{[](const Model& m, int i) { return m.structure().materials(i).has_elastic(); },
                            "is elastic: it ", "only e"};
// It has every property of its kind: no message says what it lacks.
const Form kBilinearMaterial{[](const Model& m, int i) { return m.structure().materials(i).has_bilinear(); }, "", ""};
const Form kElasticSection{[](const Model& m, int i) { return m.structure().sections(i).has_elastic(); },
                           "is elastic: it ", "e, area or inertia"};
const Form kRectangle{[](const Model& m, int i) { return m.structure().sections(i).has_fiber_rectangle(); },
                      "is a fiber_rectangle: it ", "width or depth; E is its material's"};
const Form kSinusoid{[](const Model& m, int i) { return m.walls(i).motion().has_sinusoid(); }, "",
                     "a sinusoid: stroke or period"};
const Form kSolitary{[](const Model& m, int i) { return m.walls(i).motion().has_solitary(); }, "",
                     "a solitary wave: height"};
// A motion with no signal counts as a table (validation names the missing signal at the motion).
const Form kTable{[](const Model& m, int i) { return !kSinusoid.holds(m, i) && !kSolitary.holds(m, i); }, "",
                  "a table: scale"};

enum class Range { kPositive, kNonNegative, kFraction };  // > 0, >= 0, [0, 1)

// A property of one kind of component in one of its forms (nullptr: the kind has one form).
struct Row {
  const Kind* kind;
  const char* property;
  const Form* form;
  double (*get)(const Model& m, int i);
  void (*set)(Model& m, int i, double v);
  Range range;
  double& (*seed)(ParameterSeed& s, int i);
  double (*at_most)(const Model& m, int i) = nullptr;  // a bound that depends on the model
  const char* at_most_is = "";                         // what that bound is, for its message
};

pfem::v1::Material& material(Model& m, int i) { return *m.mutable_structure()->mutable_materials(i); }
pfem::v1::Section& section(Model& m, int i) { return *m.mutable_structure()->mutable_sections(i); }
pfem::v1::WallMotion& motion(Model& m, int i) { return *m.mutable_walls(i)->mutable_motion(); }

// In the order of the list of target forms ("e|fy|hardening_ratio") and of their properties.
const Row kRows[] = {
    {&kFluid, "rho", nullptr, [](const Model& m, int) { return m.fluid().rho(); },
     [](Model& m, int, double v) { m.mutable_fluid()->set_rho(v); }, Range::kPositive,
     [](ParameterSeed& s, int) -> double& { return s.fluid.rho; }},
    {&kFluid, "mu", nullptr, [](const Model& m, int) { return m.fluid().mu(); },
     [](Model& m, int, double v) { m.mutable_fluid()->set_mu(v); }, Range::kNonNegative,
     [](ParameterSeed& s, int) -> double& { return s.fluid.mu; }},
    {&kFluid, "kappa", nullptr, [](const Model& m, int) { return m.fluid().kappa(); },
     [](Model& m, int, double v) { m.mutable_fluid()->set_kappa(v); }, Range::kPositive,
     [](ParameterSeed& s, int) -> double& { return s.fluid.kappa; }},
    {&kThickness, "", nullptr, [](const Model& m, int) { return m.has_thickness() ? m.thickness() : 1.0; },
     [](Model& m, int, double v) { m.set_thickness(v); }, Range::kPositive,
     [](ParameterSeed& s, int) -> double& { return s.fluid.thickness; }},
    {&kMaterial, "e", &kElasticMaterial, [](const Model& m, int i) { return m.structure().materials(i).elastic().e(); },
     [](Model& m, int i, double v) { material(m, i).mutable_elastic()->set_e(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.materials[i].e0; }},
    {&kMaterial, "e", &kBilinearMaterial,
     [](const Model& m, int i) { return m.structure().materials(i).bilinear().e0(); },
     [](Model& m, int i, double v) { material(m, i).mutable_bilinear()->set_e0(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.materials[i].e0; }},
    {&kMaterial, "fy", &kBilinearMaterial,
     [](const Model& m, int i) { return m.structure().materials(i).bilinear().fy(); },
     [](Model& m, int i, double v) { material(m, i).mutable_bilinear()->set_fy(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.materials[i].fy; }},
    {&kMaterial, "hardening_ratio", &kBilinearMaterial,
     [](const Model& m, int i) { return m.structure().materials(i).bilinear().hardening_ratio(); },
     [](Model& m, int i, double v) { material(m, i).mutable_bilinear()->set_hardening_ratio(v); }, Range::kFraction,
     [](ParameterSeed& s, int i) -> double& { return s.materials[i].b; }},
    {&kSection, "width", &kRectangle,
     [](const Model& m, int i) { return m.structure().sections(i).fiber_rectangle().width(); },
     [](Model& m, int i, double v) { section(m, i).mutable_fiber_rectangle()->set_width(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.sections[i].rectangle.width; }},
    {&kSection, "depth", &kRectangle,
     [](const Model& m, int i) { return m.structure().sections(i).fiber_rectangle().depth(); },
     [](Model& m, int i, double v) { section(m, i).mutable_fiber_rectangle()->set_depth(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.sections[i].rectangle.depth; }},
    {&kSection, "e", &kElasticSection, [](const Model& m, int i) { return m.structure().sections(i).elastic().e(); },
     [](Model& m, int i, double v) { section(m, i).mutable_elastic()->set_e(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.sections[i].elastic.E; }},
    {&kSection, "area", &kElasticSection,
     [](const Model& m, int i) { return m.structure().sections(i).elastic().area(); },
     [](Model& m, int i, double v) { section(m, i).mutable_elastic()->set_area(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.sections[i].elastic.A; }},
    {&kSection, "inertia", &kElasticSection,
     [](const Model& m, int i) { return m.structure().sections(i).elastic().inertia(); },
     [](Model& m, int i, double v) { section(m, i).mutable_elastic()->set_inertia(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.sections[i].elastic.I; }},
    {&kBeam, "rho", nullptr, [](const Model& m, int i) { return m.structure().beams(i).rho(); },
     [](Model& m, int i, double v) { m.mutable_structure()->mutable_beams(i)->set_rho(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.beam_rho[i]; }},
    {&kWavemaker, "stroke", &kSinusoid, [](const Model& m, int i) { return m.walls(i).motion().sinusoid().stroke(); },
     [](Model& m, int i, double v) { motion(m, i).mutable_sinusoid()->set_stroke(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.walls[i].stroke; }},
    {&kWavemaker, "period", &kSinusoid, [](const Model& m, int i) { return m.walls(i).motion().sinusoid().period(); },
     [](Model& m, int i, double v) { motion(m, i).mutable_sinusoid()->set_period(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.walls[i].period; }},
    // Goring's wave breaks beyond 0.6 of the depth (model.proto, SolitaryMotion).
    {&kWavemaker, "height", &kSolitary, [](const Model& m, int i) { return m.walls(i).motion().solitary().height(); },
     [](Model& m, int i, double v) { motion(m, i).mutable_solitary()->set_height(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.walls[i].height; },
     [](const Model& m, int i) { return 0.6 * m.walls(i).motion().solitary().depth(); },
     "0.6 of the solitary wave's depth"},
    {&kWavemaker, "scale", &kTable,
     [](const Model& m, int i) {
       const auto& t = m.walls(i).motion().table();
       return t.has_scale() ? t.scale() : 1.0;
     },
     [](Model& m, int i, double v) { motion(m, i).mutable_table()->set_scale(v); }, Range::kPositive,
     [](ParameterSeed& s, int i) -> double& { return s.walls[i].scale; }},
};

std::string spelled(const Kind& kind, const std::string& property) {
  return property.empty() ? kind.name : std::string(kind.name) + "." + property;
}

std::string with_name(const char* text, const std::string& name) {
  std::string out = text;
  return out.replace(out.find("{}"), 2, quoted(name));
}

// "fluid.rho, ..., thickness, material.<name>.e|fy|hardening_ratio, ... or wavemaker.<wall>.stroke|...".
std::string target_forms() {
  std::vector<std::string> forms;
  for (const Kind* kind : kKinds) {
    std::vector<std::string> properties;
    for (const Row& row : kRows)
      if (row.kind == kind && std::find(properties.begin(), properties.end(), row.property) == properties.end())
        properties.push_back(row.property);
    if (!kind->placeholder) {
      for (const auto& p : properties) forms.push_back(spelled(*kind, p));
      continue;
    }
    std::string form = std::string(kind->name) + "." + kind->placeholder + ".";
    for (std::size_t k = 0; k < properties.size(); ++k) form += (k ? "|" : "") + properties[k];
    forms.push_back(form);
  }
  std::string out;
  for (std::size_t k = 0; k < forms.size(); ++k)
    out += (k == 0 ? "" : k + 1 == forms.size() ? " or " : ", ") + forms[k];
  return out;
}

// A target looked up in a model: its row and component index, or why it names no value.
struct Lookup {
  const Row* row = nullptr;
  int index = 0;
  std::string error;
  bool component_invalid = false;  // a component of none of its kind's forms
};

Lookup look_up(const Model& model, const std::string& target) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return {nullptr, 0, "unknown target '" + target + "'; expected " + target_forms()};
  const Kind* kind =
      *std::find_if(std::begin(kKinds), std::end(kKinds), [&](const Kind* k) { return ref->kind == k->name; });
  const int index = kind->find ? kind->find(model, ref->name) : 0;
  if (index < 0) return {nullptr, 0, with_name(kind->unknown, ref->name) + " in target '" + target + "'"};
  for (const Row& row : kRows)
    if (row.kind == kind && row.property == ref->property && (!row.form || row.form->holds(model, index)))
      return {&row, index, ""};
  const std::string subject = with_name(kind->subject, ref->name);
  for (const Row& row : kRows)  // the component's form lacks the property
    if (row.kind == kind && row.form && row.form->holds(model, index))
      return {nullptr, 0, subject + " " + row.form->is + "has no " + ref->property + " (" + row.form->has + ")"};
  return {nullptr, 0, subject + " has no " + ref->property, true};
}

const Row& row_of(const Model& model, const std::string& target, const std::string& path, int& index) {
  Lookup found = look_up(model, target);
  if (!found.row) throw ModelError(path, std::move(found.error));
  index = found.index;
  return *found.row;
}

}  // namespace

std::optional<TargetRef> parse_parameter_target(const std::string& t) {
  for (const Row& row : kRows)
    if (!row.kind->placeholder && t == spelled(*row.kind, row.property))
      return TargetRef{row.kind->name, "", row.property};
  const auto first = t.find('.');
  const auto last = t.rfind('.');
  if (first == std::string::npos || last == first) return std::nullopt;
  TargetRef ref{t.substr(0, first), t.substr(first + 1, last - first - 1), t.substr(last + 1)};
  if (!valid_name(ref.name)) return std::nullopt;
  for (const Row& row : kRows)
    if (row.kind->placeholder && ref.kind == row.kind->name && ref.property == row.property) return ref;
  return std::nullopt;
}

std::string target_error(const Model& model, const std::string& target) {
  Lookup found = look_up(model, target);
  return found.row || found.component_invalid ? "" : std::move(found.error);
}

std::string target_value_error(const Model& model, const std::string& target, double value) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return "";
  // Every form of a property has the same range.
  const Row& any = *std::find_if(std::begin(kRows), std::end(kRows), [&](const Row& row) {
    return ref->kind == row.kind->name && ref->property == row.property;
  });
  if (any.range == Range::kNonNegative && value < 0) return "must be >= 0 for " + target;
  if (any.range == Range::kFraction && (value < 0 || value >= 1)) return "must be in [0, 1) for " + target;
  if (any.range == Range::kPositive && !(value > 0)) return "must be > 0 for " + target;
  const Lookup found = look_up(model, target);
  if (found.row && found.row->at_most && value > found.row->at_most(model, found.index))
    return std::string("must be at most ") + found.row->at_most_is + " for " + target;
  return "";
}

double model_target_value(const Model& model, const std::string& target, const std::string& path) {
  int index = 0;
  return row_of(model, target, path, index).get(model, index);
}

void set_model_target(Model& model, const std::string& target, double value, const std::string& path) {
  int index = 0;
  row_of(model, target, path, index).set(model, index, value);
}

void apply_parameter_overrides(Model& model) {
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

std::vector<double> parameter_values(const Model& with_values) {
  std::vector<double> values;
  for (const auto& p : with_values.parameters())
    values.push_back(p.has_value()          ? p.value()
                     : p.targets_size() > 0 ? model_target_value(with_values, p.targets(0))
                                            : 0.0);
  return values;
}

std::vector<ParameterSeed> parameter_seeds(const Model& model, const std::vector<std::vector<SeedTarget>>& targets) {
  const auto& st = model.structure();
  const ParameterSeed none{{},
                           std::vector<structure::BilinearParameters>(st.materials_size()),
                           std::vector<SectionSeed>(st.sections_size()),
                           std::vector<double>(st.beams_size(), 0.0),
                           std::vector<motion::SignalSeed>(model.walls_size())};
  std::vector<ParameterSeed> seeds(targets.size(), none);
  std::vector<FieldError> errors;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    for (std::size_t j = 0; j < targets[k].size(); ++j) {
      const auto& [target, weight] = targets[k][j];
      const Lookup found = look_up(model, target);
      if (found.row) found.row->seed(seeds[k], found.index) += weight;
      else errors.push_back({at(at("sensitivity_targets", static_cast<int>(k)), static_cast<int>(j)), found.error});
    }
  }
  if (!errors.empty()) throw ModelError(std::move(errors));
  return seeds;
}

}  // namespace pfem
