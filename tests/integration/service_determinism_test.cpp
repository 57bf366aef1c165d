// Determinism under concurrency: N identical DDM jobs run side by side on a real server (2 and
// 4 workers) give the in-process run's histories bit for bit. The engine's factorisations call
// the BLAS (UMFPACK, CHOLMOD and the supernodal LDL^T's dgemm/dtrsm) from every worker thread
// at once, so this fails whenever the BLAS is not safe to call concurrently (OpenBLAS built
// without locking, libopenblas0-serial: see server/blas_threads.h).
#include "tests/integration/service_test_support.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "server/convert.h"
#include "wire/convert.h"

namespace {

using namespace pfem::testing;

constexpr int kJobs = 4;

// The sloshing beam to t = 0.03 s: fluid, beam and DDM to two parameters (30 steps, about
// 0.2 s each run); large enough for supernodes wider than one panel (dgemm) and UMFPACK fronts.
pfem::v1::SubmitJobRequest sloshing_request() {
  std::ifstream in(std::string(PFEM_SOURCE_DIR) + "/examples/sloshing-beam.json");
  std::stringstream text;
  text << in.rdbuf();
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = pfem::parse_model_json(text.str());
  request.mutable_options()->set_t_end(0.03);
  request.mutable_options()->set_sensitivity(pfem::v1::SENSITIVITY_METHOD_DDM);
  request.mutable_options()->add_params("E");
  request.mutable_options()->add_params("rho_f");
  return request;
}

pfem::v1::Result in_process(const pfem::v1::SubmitJobRequest& request) {
  return pfem::wire::to_proto(pfem::run(
      request.model(), pfem::server::to_run_options(request.options(),
                                                    pfem::SensitivityMethod::kNone)));
}

void expect_identical_jobs_on(int workers) {
  const auto request = sloshing_request();
  const pfem::v1::Result expected = in_process(request);
  ASSERT_EQ(expected.summary().status(), pfem::v1::RUN_STATUS_COMPLETED);

  TempDir dir("determinism_" + std::to_string(workers));
  auto options = local_options(dir.path);
  options.workers = workers;
  pfem::server::Server server(options);
  auto stub = make_stub(server.address());
  std::vector<std::string> ids;
  for (int i = 0; i < kJobs; ++i) {
    grpc::ClientContext context;
    pfem::v1::SubmitJobResponse response;
    ASSERT_TRUE(stub->SubmitJob(&context, request, &response).ok());
    ids.push_back(response.job_id());
  }
  pfem::client::ConnectionOptions connection;
  connection.server = server.address();
  for (const auto& id : ids) {
    const auto job = wait_for_state(*stub, id, pfem::v1::JOB_STATE_SUCCEEDED, 300);
    ASSERT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED) << job.error().message();
    pfem::v1::Result result;
    ASSERT_TRUE(pfem::client::fetch_result(*stub, connection, id, &result).ok());
    EXPECT_EQ(result.summary().newton_iterations(), expected.summary().newton_iterations())
        << "job " << id << " on " << workers << " workers";
    EXPECT_TRUE(result.responses().SerializeAsString() ==
                expected.responses().SerializeAsString())
        << "job " << id << " on " << workers << " workers: responses differ";
    EXPECT_TRUE(result.sensitivities().SerializeAsString() ==
                expected.sensitivities().SerializeAsString())
        << "job " << id << " on " << workers << " workers: sensitivities differ";
  }
}

TEST(ServiceDeterminism, FourIdenticalDdmJobsOnTwoWorkersMatchTheInProcessRun) {
  expect_identical_jobs_on(2);
}

TEST(ServiceDeterminism, FourIdenticalDdmJobsOnFourWorkersMatchTheInProcessRun) {
  expect_identical_jobs_on(4);
}

// With OpenBLAS's serial build (no locks) loaded, pfem-server refuses more than one worker and
// says why, instead of answering identical jobs differently.
TEST(ServiceDeterminism, ServerRefusesSeveralWorkersOnABlasWithoutLocks) {
  const std::string serial = "/usr/lib/x86_64-linux-gnu/openblas-serial";
  if (!std::filesystem::exists(serial + "/libblas.so.3")) GTEST_SKIP() << "no " << serial;
  TempDir dir("determinism_serial");
  const std::string command = "LD_LIBRARY_PATH=" + serial + " " PFEM_BINARY_DIR
                              "/bin/pfem-server --listen 127.0.0.1:0 --workers 2 --data-dir " +
                              dir.path.string() + " 2>&1";
  FILE* out = popen(command.c_str(), "r");
  ASSERT_NE(out, nullptr);
  std::string text;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, out)) text += buffer;
  const int status = pclose(out);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << text;
  EXPECT_NE(text.find("--workers: 2 workers would call the BLAS from several threads at once"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("(sequential)"), std::string::npos) << text;
}

}  // namespace
