#pragma once
// A running pfem-server: the store, the job manager, the cache, the gRPC server with
// pfem.v1.GradientService, grpc.health.v1.Health and reflection, and with --health-listen a
// second plaintext server with the health service alone. Used by main.cpp and, in process,
// by the integration tests.
#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "server/auth.h"
#include "server/job_manager.h"
#include "server/options.h"
#include "server/result_cache.h"
#include "server/service.h"
#include "server/store.h"
#include "server/umbridge_server.h"

namespace pfem::server {

// The health port's service name for liveness probes: SERVING while the process runs, also
// while it drains (readiness, the empty name, turns NOT_SERVING then).
inline constexpr const char* kLivenessService = "liveness";

class Server {
 public:
  // Opens the store, re-queues interrupted jobs, starts the workers and listens. Throws
  // std::runtime_error (invalid options, unreadable token or TLS files, port in use).
  explicit Server(ServerOptions options, JobManager::RunFunction run = {});
  ~Server();  // shutdown() if not done
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int port() const { return port_; }
  // "host:port" actually bound.
  std::string address() const;
  // The health-only port actually bound (0 without --health-listen).
  int health_port() const { return health_port_; }
  // "host:port" of the UM-Bridge endpoint (--umbridge-listen); empty when it is off.
  std::string umbridge_address() const { return umbridge_ ? umbridge_->address() : ""; }

  // Drains: health NOT_SERVING, no new jobs, in-flight calls and running jobs get until the
  // grace period ends, then jobs still running are interrupted and stored as QUEUED.
  void shutdown();

  JobManager& jobs() { return *jobs_; }
  ResultCache& cache() { return *cache_; }

 private:
  void start_health_server();

  ServerOptions options_;
  std::unique_ptr<Store> store_;
  std::unique_ptr<JobManager> jobs_;
  std::unique_ptr<ResultCache> cache_;
  TokenAuth auth_;
  std::unique_ptr<GradientService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<grpc::Server> health_server_;  // --health-listen
  std::unique_ptr<UmbridgeModels> umbridge_models_;
  std::unique_ptr<Evaluator> umbridge_evaluator_;
  std::unique_ptr<UmbridgeServer> umbridge_;  // null without --umbridge-listen
  int port_ = 0;
  int health_port_ = 0;
  bool shut_down_ = false;
};

}  // namespace pfem::server
