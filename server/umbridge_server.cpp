#include "server/umbridge_server.h"

#include <httplib.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "server/peer_socket.h"
#include "server/status.h"

namespace pfem::server {
namespace {

using nlohmann::json;

// An error in the protocol's format: {"error": {"type": type, "message": message}}.
struct ProtocolError {
  int http_status;
  std::string type;
  std::string message;
};

ProtocolError invalid(const std::string& message) { return {400, "InvalidInput", message}; }

// The protocol error of the exception being handled (inside a catch block).
ProtocolError current_error() {
  try {
    throw;
  } catch (const ProtocolError& e) {
    return e;
  } catch (...) {
    const grpc::Status status = status_from_current_exception();
    switch (status.error_code()) {
      case grpc::StatusCode::INVALID_ARGUMENT:
      case grpc::StatusCode::RESOURCE_EXHAUSTED:  // over one of the server's limits
        return invalid(status.error_message());
      case grpc::StatusCode::NOT_FOUND:
        return {400, "ModelNotFound", status.error_message()};
      case grpc::StatusCode::UNAUTHENTICATED:
        return {401, "Unauthorized", status.error_message()};
      case grpc::StatusCode::UNAVAILABLE:
        return {503, "Unavailable", status.error_message()};
      case grpc::StatusCode::FAILED_PRECONDITION:
        return {500, "EvaluationFailed", status.error_message()};
      case grpc::StatusCode::CANCELLED:
      case grpc::StatusCode::DEADLINE_EXCEEDED:
        return {500, "Cancelled", status.error_message()};
      default:
        return {500, "InternalError", status.error_message()};
    }
  }
}

void send(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void send_error(httplib::Response& res, const ProtocolError& e) {
  send(res, e.http_status, {{"error", {{"type", e.type}, {"message", e.message}}}});
}

// body[key] as T, or InvalidInput naming the key and what it must be.
template <class T>
T field(const json& body, const char* key, const char* what) {
  const auto it = body.find(key);
  if (it == body.end()) throw invalid(std::string(key) + ": required (" + what + ")");
  try {
    return it->get<T>();
  } catch (const json::exception&) {
    throw invalid(std::string(key) + ": must be " + what);
  }
}

// A vector of finite numbers of the expected size ("input[0]", "sens", "vec").
void check_vector(const std::vector<double>& v, std::size_t size, const std::string& name) {
  if (v.size() != size) {
    throw invalid(name + ": has " + std::to_string(v.size()) + " entries, the model expects " +
                  std::to_string(size));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) throw invalid(name + "[" + std::to_string(i) + "]: must be finite");
  }
}

// One resolved call: the model, its config and (for the calls that run it) its input.
struct Call {
  pfem::v1::Model model;
  UmbridgeConfig config;
  std::vector<double> input;  // the one input vector
};

// The index field (outWrt, inWrt) of a model with one input and one output vector.
void check_index(const json& body, const char* key) {
  const auto it = body.find(key);
  if (it == body.end() || !it->is_number_integer()) {
    throw invalid(std::string(key) + ": required (an integer)");
  }
  if (*it != 0) {
    throw invalid(std::string(key) + ": must be 0 (the model has one vector), not " + it->dump());
  }
}

}  // namespace

UmbridgeServer::UmbridgeServer(const std::string& listen, const Evaluator& evaluator,
                               const UmbridgeModels& models, const TokenAuth& auth, int threads,
                               std::size_t max_body_bytes)
    : evaluator_(evaluator),
      models_(models),
      auth_(auth),
      http_(std::make_unique<httplib::Server>()) {
  const auto colon = listen.rfind(':');
  host_ = listen.substr(0, colon);
  int port = -1;
  try {
    port = std::stoi(listen.substr(colon + 1));
  } catch (const std::exception&) {
  }
  if (colon == std::string::npos || host_.empty() || port < 0 || port > 65535) {
    throw std::runtime_error("--umbridge-listen: must be HOST:PORT, not '" + listen + "'");
  }
  http_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  http_->set_payload_max_length(max_body_bytes);
  http_->set_tcp_nodelay(true);  // small JSON answers: no Nagle delay on kept-alive connections
  http_->set_keep_alive_max_count(1000);
  // Unknown paths (404), bodies over the limit (413): the protocol's error body.
  http_->set_error_handler([max_body_bytes](const httplib::Request& req, httplib::Response& res) {
    if (res.status == 413) {
      send_error(res, invalid("request body larger than " + std::to_string(max_body_bytes >> 20) +
                              " MB (--max-message-mb)"));
    } else if (res.status == 404 || res.status == 405) {
      send_error(res, {404, "NotFound", "no UM-Bridge call " + req.method + " " + req.path});
    }
  });
  add_routes();
  port_ =
      port == 0 ? http_->bind_to_any_port(host_) : (http_->bind_to_port(host_, port) ? port : -1);
  if (port_ <= 0) throw std::runtime_error("--umbridge-listen: cannot listen on " + listen);
  thread_ = std::thread([this] {
    http_->listen_after_bind();
    listen_ended_ = true;
  });
  // httplib's stop() does nothing before the listen loop has begun, and the loop then waits in
  // accept() for ever: a server stopped right after it started hung its destructor (seen under
  // load in umbridge_test). Return once the loop runs (or has already ended, on an error).
  while (!http_->is_running() && !listen_ended_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

UmbridgeServer::~UmbridgeServer() { stop(); }

void UmbridgeServer::stop() {
  if (!thread_.joinable()) return;
  http_->stop();
  thread_.join();
}

void UmbridgeServer::add_routes() {
  // Runs one call: draining and auth checks, the body parsed as a JSON object, errors
  // converted once into the protocol's format.
  // A run stops (CANCELLED) when its client closes the connection, or at cancel_calls().
  using Body = std::function<json(const json& body, const Evaluator::StopFunction& should_stop)>;
  const auto route = [this](bool post, const char* path, Body body) {
    const auto handler = [this, body, post](const httplib::Request& req, httplib::Response& res) {
      if (draining_) return send_error(res, {503, "Unavailable", "server is shutting down"});
      ++in_flight_;
      try {
        if (auth_.enabled() && !auth_.accepts(req.get_header_value("Authorization"))) {
          throw ProtocolError{401, "Unauthorized", "missing or invalid bearer token"};
        }
        json request = json::object();
        if (post) {
          try {
            request = json::parse(req.body);
          } catch (const json::exception& e) {  // syntax, or a number out of range (1e999)
            throw invalid(std::string("the request body is not JSON: ") + e.what());
          }
          if (!request.is_object()) throw invalid("the request body must be a JSON object");
        }
        int fd = -2;  // the client's socket, looked up when a run first polls
        const auto should_stop = [&] {
          if (cancelled_) return grpc::StatusCode::CANCELLED;
          if (fd == -2) fd = find_peer_socket(port_, req.remote_addr, req.remote_port);
          return fd >= 0 && peer_closed(fd) ? grpc::StatusCode::CANCELLED : grpc::StatusCode::OK;
        };
        send(res, 200, body(request, should_stop));
      } catch (...) {
        send_error(res, current_error());
      }
      --in_flight_;
    };
    if (post)
      http_->Post(path, handler);
    else
      http_->Get(path, handler);
  };

  // The model named in the body and its config; with_input: and its checked input vector.
  const auto resolve = [this](const json& body, bool with_input) {
    const auto name = field<std::string>(body, "name", "a model name (see GET /Info)");
    auto model = models_.find(name);
    if (!model) {
      throw ProtocolError{400, "ModelNotFound", "no model '" + name + "' (see GET /Info)"};
    }
    Call call;
    call.config = read_config(body.value("config", json::object()), *model);
    call.model = std::move(*model);
    if (with_input) {
      const auto input =
          field<std::vector<std::vector<double>>>(body, "input", "a list of one list of numbers");
      if (input.size() != 1) {
        throw invalid("input: has " + std::to_string(input.size()) +
                      " vectors, the model has one input vector");
      }
      check_vector(input[0], call.config.params.size(), "input[0]");
      call.input = input[0];
    }
    return call;
  };
  // Runs the call through the shared Evaluator and cache.
  const auto evaluate = [this](const Call& call, bool with_gradient,
                               const Evaluator::StopFunction& should_stop) {
    pfem::v1::EvaluateResponse response;
    evaluator_.evaluate(evaluate_request(call.model, call.config, call.input, with_gradient),
                        should_stop, &response);
    return response;
  };
  // J[i][k] = d output_i / d input_k, with the inputs in config.params order.
  const auto jacobian = [evaluate](const Call& call, const Evaluator::StopFunction& should_stop) {
    const auto response = evaluate(call, true, should_stop);
    std::vector<std::vector<double>> j;
    for (const auto& v : response.values()) {
      std::vector<double> row;
      for (const auto& p : call.config.params) {
        const auto at = std::find(response.parameters().begin(), response.parameters().end(), p);
        row.push_back(v.gradient(static_cast<int>(at - response.parameters().begin())));
      }
      j.push_back(std::move(row));
    }
    return j;
  };

  route(false, "/Info", [this](const json&, const auto&) {
    return json{{"protocolVersion", 1.0}, {"models", models_.names()}};
  });
  route(true, "/ModelInfo", [resolve](const json& body, const auto&) {
    resolve(body, false);
    return json{{"support",
                 {{"Evaluate", true},
                  {"Gradient", true},
                  {"ApplyJacobian", true},
                  {"ApplyHessian", false}}}};
  });
  route(true, "/InputSizes", [resolve](const json& body, const auto&) {
    return json{{"inputSizes", json::array({resolve(body, false).config.params.size()})}};
  });
  route(true, "/OutputSizes", [resolve](const json& body, const auto&) {
    return json{{"outputSizes", json::array({resolve(body, false).config.outputs.size()})}};
  });
  route(true, "/Evaluate", [resolve, evaluate](const json& body, const auto& should_stop) {
    const auto response = evaluate(resolve(body, true), false, should_stop);
    std::vector<double> output;
    for (const auto& v : response.values()) output.push_back(v.value());
    return json{{"output", json::array({json(output)})}};
  });
  // Gradient and ApplyJacobian: the call and the request's vector `key` (sens, of the
  // output's size, or vec, of the input's).
  const auto derivative_call = [resolve](const json& body, const char* key) {
    Call call = resolve(body, true);
    if (call.config.params.empty()) {
      throw invalid("input[0]: empty, so there is nothing to differentiate (config.params)");
    }
    check_index(body, "outWrt");
    check_index(body, "inWrt");
    const auto v = field<std::vector<double>>(body, key, "a list of numbers");
    check_vector(
        v, std::string(key) == "sens" ? call.config.outputs.size() : call.config.params.size(),
        key);
    return std::pair{std::move(call), v};
  };
  route(true, "/Gradient", [derivative_call, jacobian](const json& body, const auto& should_stop) {
    const auto [call, sens] = derivative_call(body, "sens");
    const auto j = jacobian(call, should_stop);
    std::vector<double> g(call.config.params.size(), 0.0);
    for (std::size_t i = 0; i < j.size(); ++i) {
      for (std::size_t k = 0; k < g.size(); ++k) g[k] += sens[i] * j[i][k];
    }
    return json{{"output", g}};
  });
  // J vec: the derivative along vec, one directional parameter (umbridge_models.h).
  route(true, "/ApplyJacobian", [this, derivative_call](const json& body, const auto& should_stop) {
    const auto [call, vec] = derivative_call(body, "vec");
    pfem::v1::EvaluateResponse response;
    evaluator_.evaluate(directional_request(call.model, call.config, call.input, vec),
                        should_stop, &response);
    std::vector<double> jv;
    for (const auto& v : response.values()) jv.push_back(v.gradient(0));
    return json{{"output", jv}};
  });
  route(true, "/ApplyHessian", [resolve](const json& body, const auto&) -> json {
    resolve(body, false);
    throw ProtocolError{400, "UnsupportedFeature",
                        "ApplyHessian: the engine computes first derivatives only (DDM)"};
  });
}

}  // namespace pfem::server
