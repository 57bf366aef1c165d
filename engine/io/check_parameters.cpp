#include "engine/io/model_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "engine/io/section_checks.h"

namespace pfem {

namespace {
const char* kTargetForms =
    "fluid.rho, fluid.mu, fluid.kappa, thickness, material.<name>.e|fy|hardening_ratio, "
    "section.<name>.width|depth|e|area|inertia, beam.<name>.rho or wavemaker.<wall>.stroke|period|height|scale";

void check_direction(const pfem::v1::Model& model, const pfem::v1::Parameter& p, const std::string& path,
                     FieldChecker& out) {
  if (p.targets_size() > 0)
    out.error(path + ".targets", "a directional parameter has no targets (its direction's parameters have them)");
  if (p.has_value())
    out.error(path + ".value", "a directional parameter has no value of its own (its point is its parameters')");
  std::set<std::string> seen;
  for (int k = 0; k < p.direction_size(); ++k) {
    const auto& w = p.direction(k);
    const std::string at_k = at(path + ".direction", k);
    const auto named = std::find_if(model.parameters().begin(), model.parameters().end(),
                                    [&](const auto& q) { return q.name() == w.parameter(); });
    if (named == model.parameters().end())
      out.error(at_k + ".parameter", "no parameter '" + w.parameter() + "' in the model");
    else if (named->direction_size() > 0)
      out.error(at_k + ".parameter",
                "'" + w.parameter() + "' is directional: a direction weighs parameters with targets");
    else if (!seen.insert(w.parameter()).second)
      out.error(at_k + ".parameter", "'" + w.parameter() + "' is listed twice");
    if (!std::isfinite(w.weight())) out.error(at_k + ".weight", "must be a finite number");
  }
}

// The motion of the wall of that name (nullptr: none, or it does not move).
const pfem::v1::WallMotion* wall_motion_named(const pfem::v1::Model& model, const std::string& name) {
  for (const auto& w : model.walls())
    if (w.name() == name && w.has_motion()) return &w.motion();
  return nullptr;
}

void check_target(const pfem::v1::Model& model, const StructureNames& names, const std::string& target,
                  const std::string& path, FieldChecker& out) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return out.error(path, "unknown target '" + target + "'; expected " + kTargetForms);
  const auto& st = model.structure();
  const std::string in = " in target '" + target + "'";
  if (ref->kind == "material") {
    const auto m = names.materials.find(ref->name);
    if (m == names.materials.end()) return out.error(path, "unknown material " + quoted(ref->name) + in);
    const auto& mat = st.materials(m->second);
    if (mat.has_elastic() && ref->property != "e")
      out.error(path, "material " + quoted(ref->name) + " is elastic: it has no " + ref->property + " (only e)");
  } else if (ref->kind == "section") {
    const auto s = names.sections.find(ref->name);
    if (s == names.sections.end()) return out.error(path, "unknown section " + quoted(ref->name) + in);
    const auto& sec = st.sections(s->second);
    const bool rect = ref->property == "width" || ref->property == "depth";
    if (sec.has_elastic() && rect)
      out.error(path, "section " + quoted(ref->name) + " is elastic: it has no " + ref->property +
                          " (e, area or inertia)");
    else if (sec.has_fiber_rectangle() && !rect)
      out.error(path, "section " + quoted(ref->name) + " is a fiber_rectangle: it has no " + ref->property +
                          " (width or depth; E is its material's)");
  } else if (ref->kind == "beam") {
    if (names.beams.count(ref->name) == 0) out.error(path, "unknown beam " + quoted(ref->name) + in);
  } else if (ref->kind == "wavemaker") {
    const auto* motion = wall_motion_named(model, ref->name);
    if (!motion) return out.error(path, "no wall " + quoted(ref->name) + " with a motion" + in);
    const std::string& p = ref->property;
    const bool ok = motion->has_sinusoid() ? p == "stroke" || p == "period"
                    : motion->has_solitary() ? p == "height"
                                             : p == "scale";
    if (!ok)
      out.error(path, "the motion of wall " + quoted(ref->name) + " has no " + p +
                          (motion->has_sinusoid() ? " (a sinusoid: stroke or period)"
                           : motion->has_solitary() ? " (a solitary wave: height)"
                                                    : " (a table: scale)"));
  }
}

void check_target_value(const pfem::v1::Model& model, const std::string& target, double value, const std::string& path,
                        FieldChecker& out) {
  const auto ref = parse_parameter_target(target);
  if (!ref) return;
  if (ref->property == "mu") {
    if (value < 0) out.error(path, "must be >= 0 for " + target);
  } else if (ref->property == "hardening_ratio") {
    if (value < 0 || value >= 1) out.error(path, "must be in [0, 1) for " + target);
  } else if (!(value > 0)) {
    out.error(path, "must be > 0 for " + target);
  } else if (ref->kind == "wavemaker" && ref->property == "height") {
    const auto* motion = wall_motion_named(model, ref->name);
    if (motion && motion->has_solitary() && value > 0.6 * motion->solitary().depth())
      out.error(path, "must be at most 0.6 of the solitary wave's depth for " + target);
  }
}

}  // namespace

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

void check_parameters(const pfem::v1::Model& model, const StructureNames& components, FieldChecker& out) {
  std::set<std::string> names;
  for (int i = 0; i < model.parameters_size(); ++i) {
    const auto& p = model.parameters(i);
    const std::string path = at("parameters", i);
    if (p.name().empty()) out.error(path + ".name", "is required");
    else if (!names.insert(p.name()).second) out.error(path + ".name", "'" + p.name() + "' is used twice");
    if (p.direction_size() > 0) {
      check_direction(model, p, path, out);
      continue;
    }
    if (p.targets_size() == 0) out.error(path + ".targets", "needs at least one target (or a direction)");
    std::set<std::string> seen;
    std::vector<std::string> targets;
    for (int k = 0; k < p.targets_size(); ++k) {
      if (!seen.insert(p.targets(k)).second) {
        out.error(at(path + ".targets", k), "target '" + p.targets(k) + "' is listed twice");
        continue;
      }
      targets.push_back(p.targets(k));
      check_target(model, components, p.targets(k), at(path + ".targets", k), out);
    }
    if (p.has_value()) {
      if (!std::isfinite(p.value())) out.error(path + ".value", "must be a finite number");
      else for (const auto& t : targets) check_target_value(model, t, p.value(), path + ".value", out);
    }
  }
}

}  // namespace pfem
