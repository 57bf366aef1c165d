#include "server/server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/impl/server_builder_option.h>

#include <cstdio>
#include <stdexcept>
#include <thread>

#include "engine/analysis/blas_threads.h"
#include "server/malformed_requests.h"
#include "server/port_credentials.h"

namespace pfem::server {
namespace {

// Reflection for one builder, on or off. Linking grpc++_reflection registers its plugin for
// every server of the process (a static initializer), so the option also takes it out.
class ReflectionOption : public grpc::ServerBuilderOption {
 public:
  explicit ReflectionOption(bool enabled) : enabled_(enabled) {}
  void UpdateArguments(grpc::ChannelArguments*) override {}
  void UpdatePlugins(std::vector<std::unique_ptr<grpc::ServerBuilderPlugin>>* plugins) override {
    std::erase_if(*plugins, [](const auto& p) { return p->name() == "proto_server_reflection"; });
    if (enabled_) plugins->push_back(std::make_unique<grpc::reflection::ProtoServerReflectionPlugin>());
  }

 private:
  bool enabled_;
};

}  // namespace

Server::Server(ServerOptions options, JobManager::RunFunction run) : options_(std::move(options)) {
  if (const auto errors = options_.validate(); !errors.empty()) {
    std::string message;
    for (const auto& e : errors) message += (message.empty() ? "" : "\n") + e;
    throw std::runtime_error(message);
  }
  if (!options_.token_file.empty()) auth_ = TokenAuth::from_file(options_.token_file);
  const auto credentials = port_credentials({options_.tls_cert, options_.tls_key}, auth_);

  JobManagerOptions job_options;
  job_options.workers = options_.workers > 0
                            ? options_.workers
                            : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Workers run side by side and each calls the BLAS (pfem::run): a BLAS without locks would
  // mix their products (different results for identical jobs), so refuse rather than answer
  // wrongly.
  if (!run && job_options.workers > 1 && !blas_is_thread_safe()) {
    throw std::runtime_error(
        "--workers: " + std::to_string(job_options.workers) +
        " workers would call the BLAS from several threads at once, but the loaded BLAS (" +
        blas_description() +
        ") is not thread-safe: install libopenblas0-pthread (scripts/install-deps) or use "
        "--workers 1");
  }
  job_options.max_queued = options_.limits.max_queued;
  try {
    store_ = std::make_unique<Store>(options_.data_dir, options_.max_store_mb * 1024 * 1024);
  } catch (const StoreError& e) {
    throw std::runtime_error(std::string("--data-dir: ") + e.what());
  }
  jobs_ = std::make_unique<JobManager>(*store_, job_options, std::move(run));
  cache_ = std::make_unique<ResultCache>(options_.cache_entries);
  service_ = std::make_unique<GradientService>(*store_, *jobs_, *cache_, options_.limits);

  grpc::EnableDefaultHealthCheckService(true);
  grpc::ServerBuilder builder;
  // Off by default: reflection lists every method and the whole model schema to anyone.
  builder.SetOption(std::make_unique<ReflectionOption>(options_.reflection));
  // gRPC sets SO_REUSEPORT by default: a second server on a port in use would start and share
  // the calls with the first.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.AddListeningPort(options_.listen, credentials, &port_);
  builder.RegisterService(service_.get());
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<MalformedRequestsFactory>());
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  const int max_bytes = options_.limits.max_message_mb * 1024 * 1024;
  builder.SetMaxReceiveMessageSize(max_bytes);
  builder.SetMaxSendMessageSize(max_bytes);
  if (options_.max_connection_age_seconds > 0) {
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_MS,
                               static_cast<int>(options_.max_connection_age_seconds * 1000.0));
  }
  jobs_->start();  // before the first call can queue a job
  server_ = builder.BuildAndStart();
  if (!server_ || port_ == 0) {
    jobs_->stop(std::chrono::steady_clock::now());
    shut_down_ = true;
    throw std::runtime_error("--listen: cannot listen on " + options_.listen);
  }
  if (!options_.umbridge_listen.empty()) {
    try {
      umbridge_models_ = std::make_unique<UmbridgeModels>(options_.umbridge_models, *store_);
      umbridge_evaluator_ =
          std::make_unique<Evaluator>(*store_, *jobs_, *cache_, options_.limits);
      umbridge_ = std::make_unique<UmbridgeServer>(
          options_.umbridge_listen, *umbridge_evaluator_, *umbridge_models_, auth_,
          2 * job_options.workers + 2, std::size_t(max_bytes));
    } catch (...) {
      server_->Shutdown();
      jobs_->stop(std::chrono::steady_clock::now());
      shut_down_ = true;
      throw;
    }
  }
  if (!options_.health_listen.empty()) start_health_server();
  for (grpc::Server* s : {server_.get(), health_server_.get()}) {
    if (!s) continue;
    s->GetHealthCheckService()->SetServingStatus(true);
    s->GetHealthCheckService()->SetServingStatus(pfem::v1::GradientService::service_full_name(), true);
  }
  if (health_server_) health_server_->GetHealthCheckService()->SetServingStatus(kLivenessService, true);
}

// A server with no service of its own: gRPC's default health service is all it answers
// (the reflection plugin, enabled process-wide, lists just that), plaintext and without the
// token check, which is the main port's (server/port_credentials.h).
void Server::start_health_server() {
  grpc::ServerBuilder builder;
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.AddListeningPort(options_.health_listen, grpc::InsecureServerCredentials(), &health_port_);
  health_server_ = builder.BuildAndStart();
  if (!health_server_ || health_port_ == 0) {
    server_->Shutdown(std::chrono::system_clock::now());
    server_->Wait();
    if (umbridge_) umbridge_->stop();
    jobs_->stop(std::chrono::steady_clock::now());
    shut_down_ = true;
    throw std::runtime_error("--health-listen: cannot listen on " + options_.health_listen);
  }
}

Server::~Server() { shutdown(); }

std::string Server::address() const {
  const auto colon = options_.listen.rfind(':');
  return options_.listen.substr(0, colon) + ":" + std::to_string(port_);
}

void Server::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline =
      start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                  std::chrono::duration<double>(options_.grace_seconds));
  const auto since = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // Stop accepting: health NOT_SERVING, new calls UNAVAILABLE, queued jobs stay queued.
  server_->GetHealthCheckService()->SetServingStatus(false);  // every service
  if (health_server_) {  // "liveness" stays SERVING: a draining server is alive, not ready
    auto* health = health_server_->GetHealthCheckService();
    health->SetServingStatus("", false);
    health->SetServingStatus(pfem::v1::GradientService::service_full_name(), false);
  }
  service_->begin_drain();
  if (umbridge_) umbridge_->begin_drain();
  jobs_->begin_drain();
  // Let the calls in progress and the running jobs finish within the grace period.
  while (std::chrono::steady_clock::now() < deadline &&
         (service_->in_flight() > 0 || jobs_->running() > 0 ||
          (umbridge_ && umbridge_->in_flight() > 0))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const int calls = service_->in_flight() + (umbridge_ ? umbridge_->in_flight() : 0);
  const long jobs = jobs_->running();
  // Then cancel what is left: calls end CANCELLED, running jobs are stored as QUEUED.
  if (umbridge_) umbridge_->cancel_calls();
  server_->Shutdown(std::chrono::system_clock::now());
  jobs_->stop(std::chrono::steady_clock::now());
  server_->Wait();
  if (umbridge_) umbridge_->stop();  // its calls have ended: their runs were cancelled
  if (health_server_) {
    health_server_->Shutdown(std::chrono::system_clock::now());
    health_server_->Wait();
  }
  std::fprintf(stderr, "pfem-server: drained in %.3f s (%d calls and %ld jobs were cut short)\n",
               since(), calls, jobs);
}
}  // namespace pfem::server
