#pragma once
// What a UM-Bridge model is here: a name (from --umbridge-model NAME=FILE, or the id of a
// model stored with PutModel), its inputs and outputs as chosen by the request's `config`,
// and the EvaluateRequest (server/evaluator.h) one UM-Bridge call becomes.
//
// config (every key optional; any other key is an InvalidInput error):
//   "params":  ["rho_f", ...]  the input vector's entries, in this order; default: every
//                              parameter of the model with targets (not the directional
//                              ones), in model order
//   "outputs": ["tip_ux:max", "p:value_at:0.25", ...]  the output vector's entries,
//              "<recorder>:<kind>[:<time>]" with kind max, min, max_abs, final or value_at
//              (then a time [s]); default: "<recorder>:final" for every recorder, in order
//   "t_end", "dt": numbers [s] overriding the model's analysis settings
//   "sensitivity": "ddm" (default) or "fdm", for Gradient and ApplyJacobian
//
// Thread-safety: UmbridgeModels is immutable after construction except for the store, which
// is thread-safe; every method may be called from any thread.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pfem/v1/service.pb.h"
#include "server/store.h"

namespace pfem::server {

struct UmbridgeConfig {
  std::vector<std::string> params;            // the input vector
  std::vector<pfem::v1::Functional> outputs;  // the output vector
  std::optional<double> t_end;
  std::optional<double> dt;
  pfem::v1::SensitivityMethod sensitivity = pfem::v1::SENSITIVITY_METHOD_DDM;
};

// Reads a request's config against the model. Throws ServiceError(INVALID_ARGUMENT) listing
// every problem with its path ("config.outputs[1]: no recorder 'x' in the model").
UmbridgeConfig read_config(const nlohmann::json& config, const pfem::v1::Model& model);

// The Evaluate call for one UM-Bridge input vector (input.size() == config.params.size()):
// sensitivity NONE for Evaluate, config.sensitivity (with params = config.params) otherwise.
pfem::v1::EvaluateRequest evaluate_request(const pfem::v1::Model& model,
                                           const UmbridgeConfig& config,
                                           std::span<const double> input, bool with_gradient);

// The ApplyJacobian call (vec.size() == config.params.size()): evaluate_request's with a
// directional parameter added to the model (model.proto, Parameter.direction) that weighs
// config.params by vec, and differentiated alone: its gradient is J vec from one sensitivity
// solve per step, whatever the number of inputs.
pfem::v1::EvaluateRequest directional_request(const pfem::v1::Model& model,
                                              const UmbridgeConfig& config,
                                              std::span<const double> input,
                                              std::span<const double> vec);

class UmbridgeModels {
 public:
  // Reads and validates every NAME=FILE; throws std::runtime_error naming the flag, the name
  // and every field error. The store must outlive this object.
  UmbridgeModels(const std::vector<std::pair<std::string, std::filesystem::path>>& files,
                 Store& store);

  // The named models (in flag order), then the ids of the stored models.
  std::vector<std::string> names() const;
  // The model called name, or nullopt.
  std::optional<pfem::v1::Model> find(const std::string& name) const;

 private:
  std::vector<std::pair<std::string, pfem::v1::Model>> named_;
  Store& store_;
};

}  // namespace pfem::server
