#include "engine/io/section_checks.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "engine/io/model_checks.h"
#include "engine/io/parameter_targets.h"

namespace pfem {

namespace {

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

// Parameter p's value, when it has one: finite, within each of its targets' ranges.
void check_value(const pfem::v1::Model& model, const pfem::v1::Parameter& p, const std::string& path,
                 FieldChecker& out) {
  if (!p.has_value()) return;
  if (!std::isfinite(p.value())) return out.error(path + ".value", "must be a finite number");
  std::set<std::string> seen;  // a target listed twice has its own error
  for (const auto& t : p.targets()) {
    if (!seen.insert(t).second) continue;
    if (const std::string why = target_value_error(model, t, p.value()); !why.empty()) out.error(path + ".value", why);
  }
}

}  // namespace

void check_parameters(const pfem::v1::Model& model, FieldChecker& out) {
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
    for (int k = 0; k < p.targets_size(); ++k) {
      if (!seen.insert(p.targets(k)).second) {
        out.error(at(path + ".targets", k), "target '" + p.targets(k) + "' is listed twice");
        continue;
      }
      if (const std::string why = target_error(model, p.targets(k)); !why.empty())
        out.error(at(path + ".targets", k), why);
    }
    check_value(model, p, path, out);
  }
}

std::vector<FieldError> validate_parameter_values(const pfem::v1::Model& model) {
  FieldChecker out;
  for (int i = 0; i < model.parameters_size(); ++i)
    if (model.parameters(i).direction_size() == 0) check_value(model, model.parameters(i), at("parameters", i), out);
  return out.errors();
}

}  // namespace pfem
