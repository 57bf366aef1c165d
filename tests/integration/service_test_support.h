#pragma once
// Shared pieces of the service tests: a tiny model, temporary data dirs, an in-process server
// on 127.0.0.1 with an ephemeral port, stubs, a raw health check, and fake engines for the job-mechanics tests.
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "clients/cli/client.h"
#include "engine/analysis/run.h"
#include "engine/io/model_io.h"
#include "pfem/v1/service.grpc.pb.h"
#include "server/server.h"

namespace pfem::testing {

// Still water in a small closed box: 5 x 4 particles, 5 steps of 2 ms (a fraction of a second).
inline const char* kTinyModelJson = R"({
  "name": "tiny",
  "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
  "mesh": {"h": 0.01},
  "fluid_regions": [{"name": "water", "rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.04}}}],
  "walls": [{"name": "box", "points": [{"x": 0.0, "y": 0.0}, {"x": 0.05, "y": 0.0}, {"x": 0.05, "y": 0.08}, {"x": 0.0, "y": 0.08}], "closed": true}],
  "analysis": {"dt": 0.002, "t_end": 0.01},
  "recorders": [
    {"name": "bottom_p", "quantity": "p", "point": {"x": 0.025, "y": 0.0}},
    {"name": "fluid_area", "quantity": "fluid_area"},
    {"name": "front_x", "quantity": "front_x"}
  ],
  "parameters": [{"name": "rho_f", "targets": ["fluid.rho"]}, {"name": "kappa", "targets": ["fluid.kappa"]}]
})";

inline pfem::v1::Model tiny_model() { return pfem::parse_model_json(kTinyModelJson); }

// A soft elastic cantilever in still water: 5 beam elements, 20 steps of 2 ms (about 0.1 s).
inline const char* kTinyCantileverJson = R"({
  "name": "tiny-cantilever", "thickness": 0.012,
  "fluid": {"rho": 1000.0, "mu": 0.01, "kappa": 2.15e9},
  "mesh": {"h": 0.01},
  "fluid_regions": [{"name": "water", "rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.05}}}],
  "walls": [{"name": "tank", "points": [{"x": 0.0, "y": 0.08}, {"x": 0.0, "y": 0.0}, {"x": 0.05, "y": 0.0}]}],
  "structure": {
    "nodes": [{"name": "base", "x": 0.05, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
              {"name": "tip", "x": 0.05, "y": 0.05}],
    "materials": [{"name": "soft", "elastic": {"e": 1e6}}],
    "sections": [{"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.012, "fibers": 10, "material": "soft"}}],
    "beams": [{"name": "beam", "from_node": "base", "to_node": "tip", "elements": 5,
               "element_type": "elastic", "section": "square", "rho": 2500.0}]
  },
  "analysis": {"dt": 0.002, "t_end": 0.04},
  "recorders": [{"name": "tip_ux", "quantity": "ux", "node": "tip"},
                {"name": "base_p", "quantity": "p", "node": "beam/1"}],
  "parameters": [{"name": "E", "targets": ["material.soft.e"]},
                 {"name": "density", "targets": ["fluid.rho"]}]
})";

// A directory removed when the test ends.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("pfem_" + name + "_" + std::to_string(::getpid()) + "_" +
              std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()))) {
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

inline pfem::server::ServerOptions local_options(const std::filesystem::path& data_dir) {
  pfem::server::ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.data_dir = data_dir;
  o.workers = 2;
  o.grace_seconds = 5;
  return o;
}

inline std::unique_ptr<pfem::v1::GradientService::Stub> make_stub(const std::string& address) {
  pfem::client::ConnectionOptions o;
  o.server = address;
  return pfem::v1::GradientService::NewStub(pfem::client::make_channel(o));
}

// Health of one service ("" = the server).
inline grpc::Status health_check(const std::string& address, const std::string& service,
                                 int* serving_status, const std::string& token = "") {
  auto channel = grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  grpc::GenericStub stub(channel);
  grpc::CompletionQueue cq;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
  std::string encoded;  // HealthCheckRequest{service}: field 1, length-delimited
  if (!service.empty()) encoded = std::string{0x0a, static_cast<char>(service.size())} + service;
  grpc::Slice slice(encoded);
  grpc::ByteBuffer request(&slice, 1);
  grpc::ByteBuffer response;
  auto call = stub.PrepareUnaryCall(&context, "/grpc.health.v1.Health/Check", request, &cq);
  call->StartCall();
  grpc::Status status;
  call->Finish(&response, &status, reinterpret_cast<void*>(1));
  void* tag = nullptr;
  bool ok = false;
  cq.Next(&tag, &ok);
  std::vector<grpc::Slice> slices;
  std::string bytes;
  if (status.ok() && response.Dump(&slices).ok()) {
    for (const auto& s : slices) bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  // HealthCheckResponse{status = 1 (SERVING)} is the two bytes 08 01.
  *serving_status = bytes.size() == 2 && bytes[0] == 0x08 ? bytes[1] : -1;
  return status;
}

// A fake engine: `steps` steps of `step_seconds` each, one recorder "x" = t and, with
// sensitivities, "dx/dp" = 2t. Honours the cancel flag and reports progress. With
// fail_at >= 0 it fails at that step, keeping the partial histories.
struct FakeEngine {
  int steps = 10;
  double step_seconds = 0.0;
  int fail_at = -1;
  int rows = 0;  // > 0: record this many samples at the end (for big results)
  std::shared_ptr<std::atomic<int>> runs = std::make_shared<std::atomic<int>>(0);

  pfem::server::JobManager::RunFunction function() const {
    FakeEngine self = *this;
    return [self](const pfem::v1::Model&, const pfem::RunOptions& options) {
      ++*self.runs;
      pfem::RunResult r;
      const double dt = options.dt.value_or(0.001);
      const bool sens = options.sensitivity != pfem::SensitivityMethod::kNone;
      r.responses.columns = {"x"};
      if (sens) {
        r.sensitivities.columns = {"dx/dp"};
        r.summary.parameters = {"p"};
        r.summary.parameter_values = {1.0};
      }
      const auto record = [&](double t) {
        r.responses.time.push_back(t);
        r.responses.rows.push_back({t});
        if (sens) {
          r.sensitivities.time.push_back(t);
          r.sensitivities.rows.push_back({2 * t});
        }
      };
      record(0.0);
      r.summary.dt = dt;
      r.summary.t_end = self.steps * dt;
      const auto start = std::chrono::steady_clock::now();
      for (int step = 1; step <= self.steps; ++step) {
        if (options.cancel && options.cancel->load()) {
          r.summary.status = pfem::RunStatus::kCancelled;
          r.summary.message = "cancelled";
          return r;
        }
        if (self.step_seconds > 0) {
          std::this_thread::sleep_for(std::chrono::duration<double>(self.step_seconds));
        }
        if (step == self.fail_at) {
          r.summary.status = pfem::RunStatus::kFailed;
          r.summary.message = "Newton did not converge";
          r.summary.failed_step = step;
          r.summary.failed_time = step * dt;
          return r;
        }
        record(step * dt);
        r.summary.steps = step;
        if (options.progress) {
          pfem::Progress p;
          p.step = step;
          p.total_steps = self.steps;
          p.time = step * dt;
          p.t_end = self.steps * dt;
          p.newton_iterations = 3;
          p.elapsed_seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          p.remaining_seconds = (self.steps - step) * self.step_seconds;
          options.progress(p);
        }
      }
      for (int i = 0; i < self.rows; ++i) record(1.0 + i * 1e-3);
      return r;
    };
  }
};

// Submits the request; the job id (empty, with a test failure, when refused).
inline std::string submit_job(pfem::v1::GradientService::Stub& stub,
                              const pfem::v1::SubmitJobRequest& request) {
  grpc::ClientContext context;
  pfem::v1::SubmitJobResponse response;
  const auto status = stub.SubmitJob(&context, request, &response);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return response.job_id();
}

// The finished job's result reassembled from GetResult, serialized (to compare bit for bit).
inline std::string result_bytes(pfem::v1::GradientService::Stub& stub, const std::string& address,
                                const std::string& id) {
  pfem::client::ConnectionOptions connection;
  connection.server = address;
  pfem::v1::Result result;
  const auto status = pfem::client::fetch_result(stub, connection, id, &result);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return result.SerializeAsString();
}

// Polls GetJob until the job reaches `state` (or a finished state), at most `seconds`.
inline pfem::v1::Job wait_for_state(pfem::v1::GradientService::Stub& stub, const std::string& id,
                                    pfem::v1::JobState state, double seconds = 30.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  pfem::v1::Job job;
  while (std::chrono::steady_clock::now() < deadline) {
    grpc::ClientContext context;
    pfem::v1::JobRequest request;
    request.set_job_id(id);
    const auto status = stub.GetJob(&context, request, &job);
    if (status.ok() && (job.state() == state || job.state() >= pfem::v1::JOB_STATE_SUCCEEDED)) {
      return job;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return job;
}

// The status's message contains `needle`.
inline ::testing::AssertionResult mentions(const grpc::Status& status, const std::string& needle) {
  if (status.error_message().find(needle) != std::string::npos) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "status message '" << status.error_message() << "' does not mention '" << needle << "'";
}

}  // namespace pfem::testing
