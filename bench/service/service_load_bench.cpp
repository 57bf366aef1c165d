// Service load benchmark: Evaluate throughput and latency over gRPC on 127.0.0.1.
//   pfem-bench-service [--server HOST:PORT] [--model FILE] [--clients N] [--calls N]
//                      [--uncached-calls N] [--workers N] [--functional REC:KIND]
// Without --server it starts an in-process server on an ephemeral port. It prints one table
// row per case: cached (every call after the first answered from the cache) and uncached
// (no_cache: every call runs the model on a worker). Times are printed, never asserted.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "clients/cli/client.h"
#include "engine/analysis/functional.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_io.h"
#include "bench/service/bench_server.h"

namespace {

struct Case {
  std::string name;
  int clients;
  int calls;
  bool no_cache;
};

struct Row {
  double wall = 0;
  std::vector<double> latencies;
  int errors = 0;
  std::string first_error;
};

Row run_case(const std::string& address, const pfem::v1::EvaluateRequest& base, const Case& c) {
  Row row;
  std::mutex mutex;
  std::atomic<int> next{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int t = 0; t < c.clients; ++t) {
    threads.emplace_back([&] {
      pfem::client::ConnectionOptions o;
      o.server = address;
      auto stub = pfem::v1::GradientService::NewStub(pfem::client::make_channel(o));
      while (next++ < c.calls) {
        auto request = base;
        request.set_no_cache(c.no_cache);
        grpc::ClientContext context;
        pfem::v1::EvaluateResponse response;
        const auto t0 = std::chrono::steady_clock::now();
        const auto status = stub->Evaluate(&context, request, &response);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::lock_guard lock(mutex);
        if (status.ok()) {
          row.latencies.push_back(s);
        } else if (row.errors++ == 0) {
          row.first_error = status.error_message();
        }
      }
    });
  }
  for (auto& t : threads) t.join();
  row.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::sort(row.latencies.begin(), row.latencies.end());
  return row;
}

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const auto i = static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5);
  return sorted[std::min(i, sorted.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    pfem::cli::Arguments a(std::vector<std::string>(argv + 1, argv + argc));
    const auto server_address = a.take_string("--server");
    const std::string model_file =
        a.take_string("--model").value_or(std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
    const int clients = a.take_int("--clients").value_or(32);
    const int calls = a.take_int("--calls").value_or(2000);
    const int uncached = a.take_int("--uncached-calls").value_or(64);
    const int workers = a.take_int("--workers").value_or(
        static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    const std::string functional = a.take_string("--functional").value_or("bottom_p:max");
    const double t_end = a.take_double("--t-end").value_or(0.01);
    a.expect_done(0);

    pfem::server::ServerOptions options;
    options.workers = workers;
    const pfem::bench::BenchServer server(server_address, "pfem_bench_service", options);
    const std::string& address = server.address();

    pfem::v1::EvaluateRequest request;
    *request.mutable_model() = pfem::read_model_file(model_file);
    request.set_t_end(t_end);
    request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_FDM);
    const auto colon = functional.find(':');
    auto* f = request.add_functionals();
    f->set_recorder(functional.substr(0, colon));
    const auto kind = pfem::parse_functional_kind(functional.substr(colon + 1));
    f->set_kind(kind == pfem::FunctionalKind::kMin      ? pfem::v1::Functional::KIND_MIN
                : kind == pfem::FunctionalKind::kMaxAbs ? pfem::v1::Functional::KIND_MAX_ABS
                : kind == pfem::FunctionalKind::kFinal  ? pfem::v1::Functional::KIND_FINAL
                                                        : pfem::v1::Functional::KIND_MAX);

    std::printf("service load: %s, model %s (t_end %g s, FDM), %s\n", address.c_str(),
                std::filesystem::path(model_file).filename().c_str(), t_end,
                server.in_process() ? ("in-process server, " + std::to_string(workers) + " workers").c_str()
                       : "external server");
    std::printf("%-18s %7s %7s %9s %10s %9s %9s %7s\n", "case", "clients", "calls", "wall[s]",
                "calls/s", "p50[ms]", "p99[ms]", "errors");
    const std::vector<Case> cases = {{"evaluate cached", clients, calls, false},
                                     {"evaluate uncached", std::min(clients, 8), uncached, true}};
    int errors = 0;
    for (const auto& c : cases) {
      const Row row = run_case(address, request, c);
      std::printf("%-18s %7d %7d %9.3f %10.1f %9.2f %9.2f %7d\n", c.name.c_str(), c.clients,
                  c.calls, row.wall, static_cast<double>(row.latencies.size()) / row.wall,
                  1e3 * percentile(row.latencies, 0.50), 1e3 * percentile(row.latencies, 0.99),
                  row.errors);
      if (row.errors) std::printf("  first error: %s\n", row.first_error.c_str());
      errors += row.errors;
    }
    std::fflush(stdout);
    return errors ? 1 : 0;
  } catch (const std::exception& e) {
    std::cerr << "pfem-bench-service: " << e.what() << '\n';
    return 2;
  }
}
