#pragma once
// The UM-Bridge 1.0 HTTP/JSON protocol for the
// engine, served by pfem-server --umbridge-listen HOST:PORT beside the gRPC service:
//   GET  /Info                     {"protocolVersion": 1.0, "models": [names]}
//   POST /ModelInfo                {"support": {"Evaluate": true, "Gradient": true,
//                                   "ApplyJacobian": true, "ApplyHessian": false}}
//   POST /InputSizes, /OutputSizes {"inputSizes": [P]}, {"outputSizes": [N]} (config honoured)
//   POST /Evaluate                 {"output": [[f_1 .. f_N]]}
//   POST /Gradient                 {"output": sens^T J}       (J from one DDM run, cached)
//   POST /ApplyJacobian            {"output": J vec}           (one directional DDM run, cached)
//   POST /ApplyHessian             400 UnsupportedFeature
// Inputs, outputs and config: server/umbridge_models.h. Every call goes through the same
// Evaluator and cache as the gRPC Evaluate (server/evaluator.h), so its numbers are the gRPC
// numbers, bit for bit. Errors: {"error": {"type", "message"}}, 400 for ModelNotFound,
// UnsupportedFeature and InvalidInput (field paths as in `pfem validate`), 401 Unauthorized
// (with --token-file: "Authorization: Bearer <token>"), 503 Unavailable while draining, 500
// otherwise (EvaluationFailed for a simulation failure, Cancelled, InternalError).
//
// A run whose client closes the connection is cancelled (server/peer_socket.h).
//
// Thread-safety: the HTTP threads call the evaluator concurrently; runs go on the job
// manager's workers, so at most --workers run at once.
#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "server/auth.h"
#include "server/evaluator.h"
#include "server/umbridge_models.h"

namespace httplib {
class Server;
}

namespace pfem::server {

class UmbridgeServer {
 public:
  // Binds listen ("HOST:PORT", port 0 = any) and starts serving on `threads` HTTP threads.
  // Bodies above max_body_bytes are refused (InvalidInput). Throws std::runtime_error when it
  // cannot listen. The references must outlive the server.
  UmbridgeServer(const std::string& listen, const Evaluator& evaluator,
                 const UmbridgeModels& models, const TokenAuth& auth, int threads,
                 std::size_t max_body_bytes);
  ~UmbridgeServer();  // stop()
  UmbridgeServer(const UmbridgeServer&) = delete;
  UmbridgeServer& operator=(const UmbridgeServer&) = delete;

  // "host:port" actually bound.
  std::string address() const { return host_ + ":" + std::to_string(port_); }

  // From now on every call gets 503 Unavailable; calls already running go on.
  void begin_drain() { draining_ = true; }
  int in_flight() const { return in_flight_.load(); }
  // Cancels the runs of the calls in progress (they answer 500 Cancelled): the end of a drain.
  void cancel_calls() { cancelled_ = true; }
  // Stops listening and waits for the calls in progress.
  void stop();

 private:
  void add_routes();

  const Evaluator& evaluator_;
  const UmbridgeModels& models_;
  const TokenAuth& auth_;
  std::unique_ptr<httplib::Server> http_;
  std::thread thread_;
  std::string host_;
  int port_ = 0;
  std::atomic<bool> draining_{false};
  std::atomic<bool> cancelled_{false};
  std::atomic<int> in_flight_{0};
  std::atomic<bool> listen_ended_{false};  // listen_after_bind() has returned
};

}  // namespace pfem::server
