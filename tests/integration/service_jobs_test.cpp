// Jobs over the wire: submit -> watch -> result round trip against pfem::run, chunked
// results, cancellation, timeouts, failures with partial results, the queue limit, listing.
#include "tests/integration/service_test_support.h"

#include "wire/convert.h"

namespace {

using namespace pfem::testing;
using pfem::v1::JobState;

pfem::v1::SubmitJobRequest tiny_request(pfem::v1::SensitivityMethod method) {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = tiny_model();
  request.mutable_options()->set_sensitivity(method);
  auto* v = request.add_parameter_values();
  v->set_name("rho_f");
  v->set_value(1010.0);
  return request;
}

std::string submit(pfem::v1::GradientService::Stub& stub, const pfem::v1::SubmitJobRequest& r,
                   grpc::Status* status = nullptr) {
  grpc::ClientContext context;
  pfem::v1::SubmitJobResponse response;
  const auto s = stub.SubmitJob(&context, r, &response);
  if (status) *status = s;
  else EXPECT_TRUE(s.ok()) << s.error_message();
  return response.job_id();
}

pfem::v1::Result fetch(pfem::v1::GradientService::Stub& stub, const pfem::server::Server& server,
                       const std::string& id) {
  pfem::v1::Result result;
  pfem::client::ConnectionOptions connection;
  connection.server = server.address();
  EXPECT_TRUE(pfem::client::fetch_result(stub, connection, id, &result).ok());
  return result;
}

// tiny_request's run in process (rho_f = 1010), as the service returns it.
pfem::v1::Result run_in_process(pfem::SensitivityMethod method, std::vector<std::string> params = {}) {
  pfem::v1::Model model = tiny_model();
  model.mutable_parameters(0)->set_value(1010.0);
  pfem::RunOptions options;
  options.sensitivity = method;
  options.params = std::move(params);
  return pfem::wire::to_proto(pfem::run(model, options));
}

TEST(ServiceJobs, SubmitWatchResultMatchesAnInProcessRun) {
  TempDir dir("jobs_roundtrip");
  pfem::server::Server server(local_options(dir.path));
  auto stub = make_stub(server.address());

  const auto request = tiny_request(pfem::v1::SENSITIVITY_METHOD_FDM);
  const std::string id = submit(*stub, request);
  ASSERT_EQ(id.size(), 16u);

  grpc::ClientContext watch_context;
  pfem::v1::JobRequest job_request;
  job_request.set_job_id(id);
  auto reader = stub->WatchJob(&watch_context, job_request);
  pfem::v1::Job job;
  int updates = 0;
  while (reader->Read(&job)) ++updates;
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_GE(updates, 1);
  ASSERT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED) << job.error().message();
  EXPECT_EQ(job.progress().step(), 5);
  EXPECT_EQ(job.progress().total_steps(), 5);
  EXPECT_DOUBLE_EQ(job.progress().time(), 0.01);
  EXPECT_EQ(job.attempts(), 1);
  EXPECT_EQ(job.model_name(), "tiny");

  const pfem::v1::Result result = fetch(*stub, server, id);
  // The same run in process, bit for bit.
  const auto expected = run_in_process(pfem::SensitivityMethod::kFdm);
  EXPECT_EQ(result.responses().SerializeAsString(), expected.responses().SerializeAsString());
  EXPECT_EQ(result.sensitivities().SerializeAsString(),
            expected.sensitivities().SerializeAsString());
  EXPECT_EQ(result.summary().steps(), 5);
  EXPECT_EQ(result.summary().particles(), expected.summary().particles());
  EXPECT_EQ(result.summary().parameter_values(0), 1010.0);
  ASSERT_EQ(result.responses().columns_size(), 3);
  EXPECT_EQ(result.responses().time_size(), 6);
  EXPECT_EQ(result.sensitivities().columns_size(), 6);  // 3 recorders x 2 parameters
}

// The same round trip with DDM: GetResult returns the DDM sensitivity histories of every
// recorder to the chosen parameter, bit-identical to pfem::run in process.
TEST(ServiceJobs, SubmitWatchResultWithDdmReturnsTheSensitivityHistories) {
  TempDir dir("jobs_roundtrip_ddm");
  pfem::server::Server server(local_options(dir.path));
  auto stub = make_stub(server.address());

  auto request = tiny_request(pfem::v1::SENSITIVITY_METHOD_DDM);
  request.mutable_options()->add_params("rho_f");
  const std::string id = submit(*stub, request);
  const auto job = wait_for_state(*stub, id, pfem::v1::JOB_STATE_SUCCEEDED);
  ASSERT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED) << job.error().message();

  const pfem::v1::Result result = fetch(*stub, server, id);
  const auto expected = run_in_process(pfem::SensitivityMethod::kDdm, {"rho_f"});
  EXPECT_EQ(result.summary().sensitivity_method(), "ddm");
  ASSERT_EQ(result.summary().parameters_size(), 1);
  EXPECT_EQ(result.summary().parameters(0), "rho_f");
  ASSERT_EQ(result.sensitivities().columns_size(), 3);  // 3 recorders x 1 parameter
  EXPECT_EQ(result.sensitivities().columns(0).name(), "dbottom_p/drho_f");
  EXPECT_EQ(result.sensitivities().time_size(), 6);
  EXPECT_EQ(result.responses().SerializeAsString(), expected.responses().SerializeAsString());
  EXPECT_EQ(result.sensitivities().SerializeAsString(),
            expected.sensitivities().SerializeAsString());
  // Hydrostatic-like: the bottom pressure grows with the density once the water has settled.
  EXPECT_GT(result.sensitivities().columns(0).values(5), 0.0);
}

TEST(ServiceJobs, LargeResultsStreamInChunksAndReassembleExactly) {
  TempDir dir("jobs_chunks");
  FakeEngine engine;
  engine.steps = 3;
  engine.rows = 150000;  // 3 columns x 150k doubles: several chunks each
  pfem::server::Server server(local_options(dir.path), engine.function());
  auto stub = make_stub(server.address());
  const std::string id = submit(*stub, tiny_request(pfem::v1::SENSITIVITY_METHOD_DDM));
  ASSERT_EQ(wait_for_state(*stub, id, pfem::v1::JOB_STATE_SUCCEEDED).state(),
            pfem::v1::JOB_STATE_SUCCEEDED);

  grpc::ClientContext context;
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  auto reader = stub->GetResult(&context, request);
  pfem::v1::GetResultResponse message;
  int headers = 0, chunks = 0;
  long values = 0;
  while (reader->Read(&message)) {
    headers += message.has_header();
    chunks += message.has_chunk();
    values += message.chunk().values_size();
    EXPECT_LE(message.chunk().values_size(), pfem::server::GradientService::kChunkValues);
  }
  ASSERT_TRUE(reader->Finish().ok());
  const long rows = 1 + 3 + 150000;
  EXPECT_EQ(headers, 1);
  EXPECT_EQ(values, 4 * rows);  // time + x, time + dx/dp
  EXPECT_EQ(chunks, 4 * 3);     // ceil(150004 / 65536) = 3 slices per column

  const pfem::v1::Result result = fetch(*stub, server, id);
  ASSERT_EQ(result.responses().time_size(), rows);
  ASSERT_EQ(result.sensitivities().columns(0).values_size(), rows);
  EXPECT_EQ(result.responses().columns(0).values(rows - 1), 1.0 + 149999 * 1e-3);
  EXPECT_EQ(result.sensitivities().columns(0).values(rows - 1), 2 * (1.0 + 149999 * 1e-3));
}

TEST(ServiceJobs, CancelFailTimeoutAndQueueLimit) {
  TempDir dir("jobs_cancel");
  FakeEngine slow;
  slow.steps = 400;
  slow.step_seconds = 0.01;
  auto options = local_options(dir.path);
  options.workers = 1;
  options.limits.max_queued = 2;
  pfem::server::Server server(options, slow.function());
  auto stub = make_stub(server.address());
  auto request = tiny_request(pfem::v1::SENSITIVITY_METHOD_NONE);

  const std::string running = submit(*stub, request);
  ASSERT_EQ(wait_for_state(*stub, running, pfem::v1::JOB_STATE_RUNNING).state(),
            pfem::v1::JOB_STATE_RUNNING);
  const std::string queued1 = submit(*stub, request);
  const std::string queued2 = submit(*stub, request);
  grpc::Status status;
  submit(*stub, request, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(mentions(status, "max-queued"));

  // A queued job is cancelled at once; a running one stops at its next step.
  pfem::v1::JobRequest cancel;
  pfem::v1::Job job;
  cancel.set_job_id(queued1);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->CancelJob(&c, cancel, &job).ok());
    EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_CANCELLED);
  }
  // Cancelled only once it has recorded a step (else it would stop before its first one).
  for (int polls = 0; polls < 3000 && job.progress().step() < 1; ++polls) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    grpc::ClientContext c;
    pfem::v1::JobRequest get;
    get.set_job_id(running);
    ASSERT_TRUE(stub->GetJob(&c, get, &job).ok());
  }
  cancel.set_job_id(running);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->CancelJob(&c, cancel, &job).ok());
  }
  job = wait_for_state(*stub, running, pfem::v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(job.error().message(), "cancelled by a client");
  EXPECT_GT(job.error().step(), 0);
  EXPECT_LT(job.error().step(), 400);
  {  // cancelling a finished job
    grpc::ClientContext c;
    EXPECT_EQ(stub->CancelJob(&c, cancel, &job).error_code(),
              grpc::StatusCode::FAILED_PRECONDITION);
  }
  pfem::v1::Result partial;
  pfem::client::ConnectionOptions connection;
  connection.server = server.address();
  ASSERT_TRUE(pfem::client::fetch_result(*stub, connection, running, &partial).ok());
  EXPECT_EQ(partial.summary().status(), pfem::v1::RUN_STATUS_CANCELLED);
  EXPECT_GT(partial.responses().time_size(), 1);
  EXPECT_EQ(pfem::client::fetch_result(*stub, connection, queued1, &partial).error_code(),
            grpc::StatusCode::NOT_FOUND);  // never ran: no result

  cancel.set_job_id(queued2);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->CancelJob(&c, cancel, &job).ok());
  }
  wait_for_state(*stub, queued2, pfem::v1::JOB_STATE_CANCELLED);

  // A wall-time limit.
  request.set_timeout_seconds(0.1);
  const std::string timed = submit(*stub, request);
  job = wait_for_state(*stub, timed, pfem::v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(job.error().message(), "timeout_seconds exceeded");

  // Unknown ids; GetResult of an unfinished job.
  cancel.set_job_id("0000000000000000");
  {
    grpc::ClientContext c;
    EXPECT_EQ(stub->GetJob(&c, cancel, &job).error_code(), grpc::StatusCode::NOT_FOUND);
  }
  request.clear_timeout_seconds();
  const std::string busy = submit(*stub, request);
  wait_for_state(*stub, busy, pfem::v1::JOB_STATE_RUNNING);
  EXPECT_EQ(pfem::client::fetch_result(*stub, connection, busy, &partial).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);

  // ListJobs: newest first, filter by state.
  pfem::v1::ListJobsRequest list;
  pfem::v1::ListJobsResponse jobs;
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->ListJobs(&c, list, &jobs).ok());
  }
  ASSERT_EQ(jobs.jobs_size(), 5);
  EXPECT_EQ(jobs.jobs(0).id(), busy);
  EXPECT_EQ(jobs.jobs(4).id(), running);
  list.set_state(pfem::v1::JOB_STATE_CANCELLED);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->ListJobs(&c, list, &jobs).ok());
  }
  EXPECT_EQ(jobs.jobs_size(), 4);
  cancel.set_job_id(busy);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->CancelJob(&c, cancel, &job).ok());
  }
}

TEST(ServiceJobs, AFailedSimulationStoresItsErrorAndPartialResult) {
  TempDir dir("jobs_failed");
  FakeEngine failing;
  failing.steps = 10;
  failing.fail_at = 7;
  pfem::server::Server server(local_options(dir.path), failing.function());
  auto stub = make_stub(server.address());
  const std::string id = submit(*stub, tiny_request(pfem::v1::SENSITIVITY_METHOD_DDM));
  const auto job = wait_for_state(*stub, id, pfem::v1::JOB_STATE_FAILED);
  ASSERT_EQ(job.state(), pfem::v1::JOB_STATE_FAILED);
  EXPECT_EQ(job.error().message(), "Newton did not converge");
  EXPECT_EQ(job.error().step(), 7);
  EXPECT_DOUBLE_EQ(job.error().time(), 0.007);
  const pfem::v1::Result result = fetch(*stub, server, id);
  EXPECT_EQ(result.summary().status(), pfem::v1::RUN_STATUS_FAILED);
  EXPECT_EQ(result.summary().failed_step(), 7);
  EXPECT_EQ(result.responses().time_size(), 7);  // t = 0 and steps 1..6
}

}  // namespace
