// UM-Bridge overhead benchmark: the latency of a cached Evaluate through the UM-Bridge HTTP
// endpoint against the same cached Evaluate through gRPC, one client each on 127.0.0.1 with a
// kept-alive connection, against an in-process pfem-server.
//   pfem-bench-umbridge [--model FILE] [--t-end T] [--calls N] [--functional REC:KIND]
// Both paths run the same Evaluator on the same cache entry (the first call computes it), so
// the difference is the HTTP/JSON handling against the gRPC/protobuf handling. Times are
// printed, never asserted.
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "clients/cli/client.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_io.h"
#include "server/server.h"

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

struct Stats {
  double mean = 0, p50 = 0, p99 = 0;
};

Stats stats(std::vector<double> s) {
  std::sort(s.begin(), s.end());
  Stats out;
  for (double x : s) out.mean += x / s.size();
  out.p50 = s[s.size() / 2];
  out.p99 = s[std::min(s.size() - 1, s.size() * 99 / 100)];
  return out;
}

template <class Call>
std::vector<double> time_calls(int calls, const Call& call) {
  std::vector<double> seconds;
  for (int i = 0; i < calls; ++i) {
    const auto t0 = Clock::now();
    call();
    seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    pfem::cli::Arguments a(std::vector<std::string>(argv + 1, argv + argc));
    const std::filesystem::path model_file =
        a.take_string("--model").value_or(PFEM_SOURCE_DIR "/examples/dam-break-obstacle.json");
    const double t_end = a.take_double("--t-end").value_or(0.02);
    const int calls = a.take_int("--calls").value_or(2000);
    const std::string functional = a.take_string("--functional").value_or("front_x:max");
    a.expect_done(0);
    const auto colon = functional.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("--functional: must be REC:KIND");

    const auto dir =
        std::filesystem::temp_directory_path() /
        ("pfem_bench_umbridge_" + std::to_string(Clock::now().time_since_epoch().count()));
    pfem::server::ServerOptions o;
    o.listen = "127.0.0.1:0";
    o.data_dir = dir;
    o.workers = 1;
    o.umbridge_listen = "127.0.0.1:0";
    o.umbridge_models = {{"model", model_file}};
    pfem::server::Server server(o);
    const auto model = pfem::read_model_file(model_file);

    // UM-Bridge: Evaluate at the model's own values (an empty input vector: no parameters).
    const json body = {
        {"name", "model"},
        {"input", json::array({json::array()})},
        {"config", {{"params", json::array()}, {"outputs", {functional}}, {"t_end", t_end}}}};
    const std::string text = body.dump();
    httplib::Client http("http://" + server.umbridge_address());
    http.set_read_timeout(3600);
    double value_http = 0;
    const auto post = [&](const char* path) {
      const auto r = http.Post(path, text, "application/json");
      if (!r || r->status != 200) {
        throw std::runtime_error(std::string(path) + ": " + (r ? r->body : "no answer"));
      }
      value_http = json::parse(r->body)["output"][0][0].get<double>();
    };
    // gRPC: the same request.
    pfem::v1::EvaluateRequest request;
    *request.mutable_model() = model;
    auto* f = request.add_functionals();
    f->set_recorder(functional.substr(0, colon));
    pfem::v1::Functional::Kind kind{};
    std::string upper = "KIND_" + functional.substr(colon + 1);
    std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
    if (!pfem::v1::Functional::Kind_Parse(upper, &kind))
      throw std::invalid_argument("--functional: unknown kind");
    f->set_kind(kind);
    request.set_t_end(t_end);
    request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_NONE);
    pfem::client::ConnectionOptions co;
    co.server = server.address();
    auto stub = pfem::v1::GradientService::NewStub(pfem::client::make_channel(co));
    double value_grpc = 0;
    const auto evaluate = [&] {
      grpc::ClientContext context;
      pfem::v1::EvaluateResponse response;
      const auto status = stub->Evaluate(&context, request, &response);
      if (!status.ok()) throw std::runtime_error("gRPC Evaluate: " + status.error_message());
      value_grpc = response.values(0).value();
    };

    const auto first = time_calls(1, [&] { post("/Evaluate"); });  // computes the cache entry
    evaluate();
    for (int i = 0; i < 20; ++i) post("/Evaluate"), evaluate();  // warm both connections
    const auto grpc = stats(time_calls(calls, evaluate));
    const auto um = stats(time_calls(calls, [&] { post("/Evaluate"); }));
    std::printf("UM-Bridge overhead on a cached Evaluate (%s, t_end %g s, %s, %d calls each)\n",
                model_file.filename().c_str(), t_end, functional.c_str(), calls);
    std::printf("  first (uncached) UM-Bridge Evaluate: %.3f s\n", first[0]);
    std::printf("  %-24s %10s %10s %10s\n", "cached call", "mean ms", "p50 ms", "p99 ms");
    std::printf("  %-24s %10.3f %10.3f %10.3f\n", "gRPC Evaluate", 1e3 * grpc.mean, 1e3 * grpc.p50,
                1e3 * grpc.p99);
    std::printf("  %-24s %10.3f %10.3f %10.3f\n", "UM-Bridge /Evaluate", 1e3 * um.mean,
                1e3 * um.p50, 1e3 * um.p99);
    std::printf("  %-24s %10.3f %10.3f\n", "UM-Bridge - gRPC", 1e3 * (um.mean - grpc.mean),
                1e3 * (um.p50 - grpc.p50));
    std::printf("  same value both ways: %s (%.17g)\n", value_http == value_grpc ? "yes" : "NO",
                value_http);
    server.shutdown();
    std::filesystem::remove_all(dir);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pfem-bench-umbridge: %s\n", e.what());
    return 2;
  }
}
