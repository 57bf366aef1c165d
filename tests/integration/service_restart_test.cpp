// The pfem-server binary across crashes and drains: after `kill -9` during a job, a restart on
// the same data dir keeps the stored results bit for bit and completes the interrupted job;
// SIGTERM drains (the running job is stored as queued) and the next start completes it.
#include "tests/integration/server_process.h"
#include "tests/integration/service_test_support.h"

namespace {

using namespace pfem::testing;

// One worker, the drain's grace period as given.
std::vector<std::string> server_flags(const std::filesystem::path& data_dir, double grace_seconds) {
  return {"--data-dir", data_dir.string(), "--workers", "1", "--grace-seconds",
          std::to_string(grace_seconds)};
}

pfem::v1::SubmitJobRequest hydrostatic(double t_end, pfem::v1::SensitivityMethod method) {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() =
      pfem::read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
  request.mutable_options()->set_t_end(t_end);
  request.mutable_options()->set_sensitivity(method);
  return request;
}

// Waits until the job has completed at least `step` steps.
pfem::v1::Job wait_for_step(pfem::v1::GradientService::Stub& stub, const std::string& id, int step) {
  pfem::v1::Job job;
  for (int i = 0; i < 3000 && job.progress().step() < step; ++i) {
    job = wait_for_state(stub, id, pfem::v1::JOB_STATE_SUCCEEDED, 0.01);
  }
  return job;
}

TEST(ServiceRestart, KillNineThenRestartKeepsResultsAndCompletesTheInterruptedJob) {
  TempDir dir("restart");
  std::string done_id, interrupted_id, done_bytes;
  {
    ServerProcess first(server_flags(dir.path, 5.0));
    auto stub = make_stub(first.address());
    done_id = submit_job(*stub, hydrostatic(0.004, pfem::v1::SENSITIVITY_METHOD_FDM));
    ASSERT_EQ(wait_for_state(*stub, done_id, pfem::v1::JOB_STATE_SUCCEEDED, 60).state(),
              pfem::v1::JOB_STATE_SUCCEEDED);
    done_bytes = result_bytes(*stub, first.address(), done_id);
    ASSERT_GT(done_bytes.size(), 100u);

    interrupted_id = submit_job(*stub, hydrostatic(0.4, pfem::v1::SENSITIVITY_METHOD_NONE));
    const auto running = wait_for_step(*stub, interrupted_id, 2);
    ASSERT_EQ(running.state(), pfem::v1::JOB_STATE_RUNNING);
    ASSERT_LT(running.progress().step(), 200);
    const int status = first.stop(SIGKILL, 10);
    ASSERT_TRUE(WIFSIGNALED(status));
  }
  ServerProcess second(server_flags(dir.path, 5.0));
  auto stub = make_stub(second.address());
  EXPECT_EQ(result_bytes(*stub, second.address(), done_id), done_bytes);

  grpc::ClientContext context;
  pfem::v1::JobRequest request;
  request.set_job_id(interrupted_id);
  auto reader = stub->WatchJob(&context, request);
  pfem::v1::Job job;
  while (reader->Read(&job)) {
  }
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED) << job.error().message();
  EXPECT_EQ(job.attempts(), 2);
  EXPECT_EQ(job.progress().step(), 200);
  pfem::v1::Result result;
  ASSERT_TRUE(result.ParseFromString(result_bytes(*stub, second.address(), interrupted_id)));
  EXPECT_EQ(result.summary().steps(), 200);
  EXPECT_EQ(result.responses().time_size(), 201);
  EXPECT_TRUE(WIFEXITED(second.stop(SIGTERM, 30)));
}

// A cancel is stored before it is acknowledged: kill -9 right after the answer, and the next
// start ends the job CANCELLED instead of running it again.
TEST(ServiceRestart, ACancelAcknowledgedBeforeKillNineStaysCancelled) {
  TempDir dir("restart_cancel");
  std::string id;
  {
    ServerProcess first(server_flags(dir.path, 5.0));
    auto stub = make_stub(first.address());
    id = submit_job(*stub, hydrostatic(0.4, pfem::v1::SENSITIVITY_METHOD_NONE));
    ASSERT_EQ(wait_for_step(*stub, id, 1).state(), pfem::v1::JOB_STATE_RUNNING);
    grpc::ClientContext context;
    pfem::v1::JobRequest request;
    request.set_job_id(id);
    pfem::v1::Job job;
    ASSERT_TRUE(stub->CancelJob(&context, request, &job).ok());
    ASSERT_TRUE(WIFSIGNALED(first.stop(SIGKILL, 10)));
  }
  ServerProcess second(server_flags(dir.path, 5.0));
  auto stub = make_stub(second.address());
  const auto job = wait_for_state(*stub, id, pfem::v1::JOB_STATE_CANCELLED, 10);
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_CANCELLED) << pfem::v1::JobState_Name(job.state());
  EXPECT_EQ(job.attempts(), 1);
  EXPECT_NE(job.error().message().find("cancelled by a client"), std::string::npos);
  EXPECT_TRUE(WIFEXITED(second.stop(SIGTERM, 30)));
}

TEST(ServiceRestart, SigtermDrainsAndTheNextStartCompletesTheJob) {
  TempDir dir("drain");
  std::string id;
  {
    ServerProcess first(server_flags(dir.path, 0.0));  // no grace: interrupt at once
    auto stub = make_stub(first.address());
    id = submit_job(*stub, hydrostatic(0.4, pfem::v1::SENSITIVITY_METHOD_NONE));
    const auto running = wait_for_step(*stub, id, 1);
    ASSERT_EQ(running.state(), pfem::v1::JOB_STATE_RUNNING);
    ASSERT_LT(running.progress().step(), 200);
    const auto start = std::chrono::steady_clock::now();
    const int status = first.stop(SIGTERM, 20);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    // The step in progress, not the whole run.
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  }
  ServerProcess second(server_flags(dir.path, 5.0));
  auto stub = make_stub(second.address());
  const auto job = wait_for_state(*stub, id, pfem::v1::JOB_STATE_SUCCEEDED, 60);
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(job.attempts(), 2);
  EXPECT_TRUE(WIFEXITED(second.stop(SIGTERM, 30)));
}

}  // namespace
