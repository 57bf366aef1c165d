// A bounded load test: 32 concurrent clients make 200 Evaluate calls on a small model (four
// parameter values, every tenth call bypassing the cache so that runs go side by side) within
// 60 s, with zero errors and every value and gradient equal to an in-process run.
#include "tests/integration/service_test_support.h"

#include <mutex>

#include "engine/analysis/functional.h"

namespace {

using namespace pfem::testing;

constexpr int kClients = 32;
constexpr int kCalls = 200;
const double kRho[] = {990.0, 1000.0, 1010.0, 1020.0};

TEST(ServiceLoad, ThirtyTwoClientsTwoHundredEvaluations) {
  const auto method = pfem::SensitivityMethod::kDdm;  // Evaluate's default
  // Reference values: bottom_p max and its gradient, in process.
  std::vector<pfem::FunctionalValue> expected;
  for (double rho : kRho) {
    auto model = tiny_model();
    model.mutable_parameters(0)->set_value(rho);
    pfem::RunOptions options;
    options.sensitivity = method;
    const auto r = pfem::run(model, options);
    expected.push_back(pfem::evaluate_functional(
        r.responses, r.sensitivities, r.summary.parameters,
        {"bottom_p", pfem::FunctionalKind::kMax, 0.0}));
  }

  TempDir dir("load");
  pfem::server::Server server(local_options(dir.path));
  std::atomic<int> next{0}, errors{0}, wrong{0}, cached{0};
  std::mutex latency_mutex;
  std::vector<double> latencies;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&] {
      auto stub = make_stub(server.address());
      for (int i = next++; i < kCalls; i = next++) {
        pfem::v1::EvaluateRequest request;
        *request.mutable_model() = tiny_model();
        request.set_sensitivity(pfem::v1::SENSITIVITY_METHOD_DDM);
        auto* v = request.add_parameter_values();
        v->set_name("rho_f");
        v->set_value(kRho[i % 4]);
        auto* f = request.add_functionals();
        f->set_recorder("bottom_p");
        f->set_kind(pfem::v1::Functional::KIND_MAX);
        request.set_no_cache(i % 10 == 0);
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
        pfem::v1::EvaluateResponse response;
        const auto t0 = std::chrono::steady_clock::now();
        const auto status = stub->Evaluate(&context, request, &response);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!status.ok()) {
          ++errors;
          ADD_FAILURE() << status.error_message();
          continue;
        }
        cached += response.cached();
        const auto& e = expected[i % 4];
        const auto& got = response.values(0);
        if (got.value() != e.value || got.gradient_size() != 2 || got.gradient(0) != e.gradient[0] ||
            got.gradient(1) != e.gradient[1]) {
          ++wrong;
        }
        std::lock_guard lock(latency_mutex);
        latencies.push_back(seconds);
      }
    });
  }
  for (auto& t : clients) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::sort(latencies.begin(), latencies.end());
  ASSERT_EQ(latencies.size(), static_cast<std::size_t>(kCalls));
  std::printf("load: %d calls from %d clients in %.2f s (%.0f calls/s), p50 %.1f ms, p99 %.1f ms, "
              "%d cached, DDM\n",
              kCalls, kClients, wall, kCalls / wall, 1e3 * latencies[kCalls / 2],
              1e3 * latencies[kCalls * 99 / 100], cached.load());
  EXPECT_EQ(errors.load(), 0);
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_LE(wall, 60.0);
  EXPECT_GE(cached.load(), kCalls - kCalls / 10 - 4);  // all but the first run of each value
}

}  // namespace
