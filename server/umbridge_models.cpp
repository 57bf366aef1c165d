#include "server/umbridge_models.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "engine/io/model_io.h"
#include "server/requests.h"
#include "server/status.h"

namespace pfem::server {
namespace {

using nlohmann::json;

// "<recorder>:<kind>[:<time>]" -> a Functional named after the text; an error message or "".
std::string parse_output(const std::string& text, pfem::v1::Functional* f) {
  const auto first = text.find(':');
  if (first == std::string::npos || first == 0) return "must be \"<recorder>:<kind>[:<time>]\"";
  const auto second = text.find(':', first + 1);
  const std::string kind =
      text.substr(first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
  // The proto's own names, lower case: "max" <-> KIND_MAX, "value_at" <-> KIND_VALUE_AT.
  std::string upper = "KIND_" + kind;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return std::toupper(c); });
  const bool lower =
      std::none_of(kind.begin(), kind.end(), [](unsigned char c) { return std::isupper(c); });
  pfem::v1::Functional::Kind k{};
  if (!lower || !pfem::v1::Functional::Kind_Parse(upper, &k) ||
      k == pfem::v1::Functional::KIND_UNSPECIFIED) {
    return "unknown kind '" + kind + "' (max, min, max_abs, final or value_at)";
  }
  f->set_recorder(text.substr(0, first));
  f->set_kind(k);
  f->set_name(text);
  const bool timed = k == pfem::v1::Functional::KIND_VALUE_AT;
  if (timed != (second != std::string::npos)) {
    return timed ? "value_at needs a time: \"<recorder>:value_at:<time>\""
                 : "only value_at takes a time";
  }
  if (timed) {
    const std::string t = text.substr(second + 1);
    std::size_t used = 0;
    double time = 0.0;
    try {
      time = std::stod(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != t.size() || !std::isfinite(time)) {
      return "time '" + t + "' is not a finite number";
    }
    f->set_time(time);
  }
  return "";
}

std::optional<double> read_time(const json& config, const char* key,
                                std::vector<FieldError>& errors) {
  const auto it = config.find(key);
  if (it == config.end()) return std::nullopt;
  if (!it->is_number() || !std::isfinite(it->get<double>()) || it->get<double>() <= 0.0) {
    errors.push_back({std::string("config.") + key, "must be a number > 0"});
    return std::nullopt;
  }
  return it->get<double>();
}

}  // namespace

UmbridgeConfig read_config(const json& config, const pfem::v1::Model& model) {
  std::vector<FieldError> errors;
  UmbridgeConfig out;
  if (!config.is_object()) throw_invalid({{"config", "must be an object"}});
  for (const auto& [key, value] : config.items()) {
    if (key != "params" && key != "outputs" && key != "t_end" && key != "dt" &&
        key != "sensitivity") {
      errors.push_back(
          {"config." + key, "unknown option (params, outputs, t_end, dt or sensitivity)"});
    }
  }
  if (const auto it = config.find("params"); it != config.end()) {
    if (!it->is_array()) errors.push_back({"config.params", "must be a list of parameter names"});
    for (std::size_t i = 0; it->is_array() && i < it->size(); ++i) {
      const std::string path = "config.params[" + std::to_string(i) + "]";
      const auto& name = (*it)[i];
      const auto p = std::find_if(model.parameters().begin(), model.parameters().end(),
                                  [&](const auto& q) { return name.is_string() && q.name() == name; });
      if (p == model.parameters().end()) {
        errors.push_back({path, "no parameter " + name.dump() + " in the model"});
      } else if (p->direction_size() > 0) {
        errors.push_back({path, name.dump() + " is a directional parameter: it has no value to input"});
      } else if (std::find(out.params.begin(), out.params.end(), name) != out.params.end()) {
        errors.push_back({path, "repeats " + name.dump()});
      } else {
        out.params.push_back(name);
      }
    }
  } else {
    for (const auto& p : model.parameters()) {
      if (p.direction_size() == 0) out.params.push_back(p.name());
    }
  }
  if (const auto it = config.find("outputs"); it != config.end()) {
    if (!it->is_array() || it->empty()) {
      errors.push_back({"config.outputs", "must be a non-empty list of \"<recorder>:<kind>\""});
    }
    for (std::size_t i = 0; it->is_array() && i < it->size(); ++i) {
      const std::string path = "config.outputs[" + std::to_string(i) + "]";
      pfem::v1::Functional f;
      const std::string why = (*it)[i].is_string() ? parse_output((*it)[i], &f)
                                                   : "must be a string \"<recorder>:<kind>\"";
      if (!why.empty()) errors.push_back({path, why});
      out.outputs.push_back(std::move(f));
    }
  } else {
    for (const auto& r : model.recorders()) {
      pfem::v1::Functional f;
      f.set_recorder(r.name());
      f.set_kind(pfem::v1::Functional::KIND_FINAL);
      f.set_name(r.name() + ":final");
      out.outputs.push_back(std::move(f));
    }
  }
  // The recorders named by well-formed outputs, checked as Evaluate checks them.
  google::protobuf::RepeatedPtrField<pfem::v1::Functional> parsed;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < out.outputs.size(); ++i) {
    if (out.outputs[i].kind() == pfem::v1::Functional::KIND_UNSPECIFIED) continue;
    *parsed.Add() = out.outputs[i];
    index.push_back(i);
  }
  if (!parsed.empty()) {
    for (const auto& e : check_functionals(model, parsed)) {
      // "functionals[j].recorder" -> "config.outputs[i]"
      const auto j = std::stoul(e.path.substr(e.path.find('[') + 1));
      errors.push_back({"config.outputs[" + std::to_string(index[j]) + "]", e.message});
    }
  } else if (out.outputs.empty()) {
    errors.push_back({"config.outputs", "the model has no recorder, so there is no output"});
  }
  out.t_end = read_time(config, "t_end", errors);
  out.dt = read_time(config, "dt", errors);
  if (const auto it = config.find("sensitivity"); it != config.end()) {
    if (*it == "ddm") {
      out.sensitivity = pfem::v1::SENSITIVITY_METHOD_DDM;
    } else if (*it == "fdm") {
      out.sensitivity = pfem::v1::SENSITIVITY_METHOD_FDM;
    } else {
      errors.push_back({"config.sensitivity", "must be \"ddm\" or \"fdm\""});
    }
  }
  if (!errors.empty()) throw_invalid(errors);
  return out;
}

pfem::v1::EvaluateRequest evaluate_request(const pfem::v1::Model& model,
                                           const UmbridgeConfig& config,
                                           std::span<const double> input, bool with_gradient) {
  pfem::v1::EvaluateRequest request;
  *request.mutable_model() = model;
  for (std::size_t i = 0; i < input.size(); ++i) {
    auto* v = request.add_parameter_values();
    v->set_name(config.params.at(i));
    v->set_value(input[i]);
  }
  for (const auto& f : config.outputs) *request.add_functionals() = f;
  if (config.t_end) request.set_t_end(*config.t_end);
  if (config.dt) request.set_dt(*config.dt);
  if (with_gradient) {
    request.set_sensitivity(config.sensitivity);
    for (const auto& p : config.params) request.add_params(p);
  } else {
    request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_NONE);
  }
  return request;
}

pfem::v1::EvaluateRequest directional_request(const pfem::v1::Model& model,
                                              const UmbridgeConfig& config,
                                              std::span<const double> input,
                                              std::span<const double> vec) {
  auto request = evaluate_request(model, config, input, true);
  auto& parameters = *request.mutable_model()->mutable_parameters();
  std::string name = "vec";  // a name no parameter of the model has
  while (std::any_of(parameters.begin(), parameters.end(),
                     [&](const auto& p) { return p.name() == name; })) {
    name += '_';
  }
  auto* direction = parameters.Add();
  direction->set_name(name);
  for (std::size_t k = 0; k < vec.size(); ++k) {
    auto* w = direction->add_direction();
    w->set_parameter(config.params.at(k));
    w->set_weight(vec[k]);
  }
  request.clear_params();
  request.add_params(name);
  return request;
}

UmbridgeModels::UmbridgeModels(
    const std::vector<std::pair<std::string, std::filesystem::path>>& files, Store& store)
    : store_(store) {
  for (const auto& [name, file] : files) {
    const std::string flag = "--umbridge-model " + name + ": ";
    pfem::v1::Model model;
    try {
      model = read_model_file(file);
    } catch (const std::exception& e) {
      throw std::runtime_error(flag + e.what());
    }
    if (const auto errors = validate_model(model); !errors.empty()) {
      std::string message = flag + file.string() + " is not a valid model:";
      for (const auto& e : errors) message += "\n  " + e.to_string();
      throw std::runtime_error(message);
    }
    named_.emplace_back(name, std::move(model));
  }
}

std::vector<std::string> UmbridgeModels::names() const {
  std::vector<std::string> names;
  for (const auto& [name, model] : named_) names.push_back(name);
  for (auto& id : store_.model_ids()) names.push_back(std::move(id));
  return names;
}

std::optional<pfem::v1::Model> UmbridgeModels::find(const std::string& name) const {
  for (const auto& [n, model] : named_) {
    if (n == name) return model;
  }
  return store_.get_model(name);
}

}  // namespace pfem::server
