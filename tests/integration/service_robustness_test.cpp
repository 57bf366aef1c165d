// The service when things go wrong around it: writes the store refuses (a full database, a
// failing write), corrupted store rows, an empty database file, malformed request bytes,
// timeouts too long for the clock, unknown filters and error lists too long for a status.
#include "tests/integration/service_test_support.h"

#include <grpcpp/generic/generic_stub.h>
#include <sqlite3.h>

#include <fstream>

#include "server/status.h"

namespace {

using namespace pfem::testing;

pfem::v1::SubmitJobRequest fake_request() {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = tiny_model();
  return request;
}

grpc::Status submit(pfem::v1::GradientService::Stub& stub, const pfem::v1::SubmitJobRequest& r,
                    std::string* id) {
  grpc::ClientContext context;
  pfem::v1::SubmitJobResponse response;
  const auto status = stub.SubmitJob(&context, r, &response);
  *id = response.job_id();
  return status;
}

// The last state WatchJob streams.
pfem::v1::Job watch_to_end(pfem::v1::GradientService::Stub& stub, const std::string& id) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  auto reader = stub.WatchJob(&context, request);
  pfem::v1::Job job;
  while (reader->Read(&job)) {
  }
  EXPECT_TRUE(reader->Finish().ok());
  return job;
}

// Runs SQL on the server's database through a second connection (as an operator could).
void sql(const std::filesystem::path& data_dir, const std::string& statement) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((data_dir / "pfem.sqlite3").string().c_str(), &db), SQLITE_OK);
  sqlite3_busy_timeout(db, 5000);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &error), SQLITE_OK)
      << (error ? error : "") << " in " << statement;
  sqlite3_free(error);
  sqlite3_close(db);
}

TEST(ServiceRobustness, ATimeoutTooLongForTheClockIsHonoured) {
  TempDir dir("robust_timeout");
  FakeEngine engine;
  engine.steps = 5;
  pfem::server::Server server(local_options(dir.path), engine.function());
  auto stub = make_stub(server.address());
  auto request = fake_request();
  request.set_timeout_seconds(1e10);  // now + 1e10 s overflows steady_clock's nanoseconds
  std::string id;
  ASSERT_TRUE(submit(*stub, request, &id).ok());
  const auto job = watch_to_end(*stub, id);
  EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_SUCCEEDED) << job.error().message();
  EXPECT_EQ(job.progress().step(), 5);
}

// Every write of a finished state fails (a trigger raising an error, as a failing disk would):
// the job ends FAILED naming why, for its watcher and GetJob, instead of RUNNING forever.
TEST(ServiceRobustness, AJobWhoseEndCannotBeStoredEndsFailedForItsWatchers) {
  TempDir dir("robust_unstored");
  FakeEngine engine;
  engine.steps = 20;
  engine.step_seconds = 0.01;
  pfem::server::Server server(local_options(dir.path), engine.function());
  sql(dir.path,
      "CREATE TRIGGER refuse_ends BEFORE UPDATE OF state ON jobs WHEN NEW.state >= 3 "
      "BEGIN SELECT RAISE(FAIL, 'writes refused by the test'); END");
  auto stub = make_stub(server.address());
  std::string id;
  ASSERT_TRUE(submit(*stub, fake_request(), &id).ok());
  const auto watched = watch_to_end(*stub, id);
  EXPECT_EQ(watched.state(), pfem::v1::JOB_STATE_FAILED);
  EXPECT_TRUE(mentions(grpc::Status(grpc::StatusCode::UNKNOWN, watched.error().message()),
                       "the job's end could not be stored: writes refused by the test"));
  const auto got = wait_for_state(*stub, id, pfem::v1::JOB_STATE_FAILED, 5);
  EXPECT_EQ(got.state(), pfem::v1::JOB_STATE_FAILED);
  // Cancelling it now says it has finished.
  grpc::ClientContext context;
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  pfem::v1::Job job;
  EXPECT_EQ(stub->CancelJob(&context, request, &job).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
}

// A cancel acknowledged while the run takes its last step is kept: the job ends CANCELLED (with
// its whole result), not SUCCEEDED (the soak test saw 4 in 3 710 acknowledged cancels end
// SUCCEEDED). Once the run's end is being decided, a cancel is FAILED_PRECONDITION.
TEST(ServiceRobustness, ACancelAcknowledgedAtTheRunsLastStepIsKept) {
  TempDir dir("robust_late_cancel");
  std::atomic<bool> at_end{false}, release{false};
  const auto run = [&](const pfem::v1::Model&, const pfem::RunOptions&) {
    at_end = true;  // past the last check of the cancel flag
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    pfem::RunResult r;
    r.summary.status = pfem::RunStatus::kCompleted;
    r.summary.steps = 5;
    return r;
  };
  pfem::server::Server server(local_options(dir.path), run);
  auto stub = make_stub(server.address());
  std::string id;
  ASSERT_TRUE(submit(*stub, fake_request(), &id).ok());
  while (!at_end) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  pfem::v1::Job job;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(stub->CancelJob(&context, request, &job).ok());
  }
  release = true;
  const auto ended = watch_to_end(*stub, id);
  EXPECT_EQ(ended.state(), pfem::v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(ended.error().message(), "cancelled by a client (the run had reached its end)");
  EXPECT_EQ(ended.error().step(), 5);
  grpc::ClientContext context;
  EXPECT_EQ(stub->CancelJob(&context, request, &job).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
}

// A database at its cap (--max-store-mb; SQLite answers SQLITE_FULL as for a full disk): a
// result too big to store ends its job FAILED (stored, without the result: a restart finds it
// FAILED instead of running it again), and a request too big to store is RESOURCE_EXHAUSTED,
// not INTERNAL.
TEST(ServiceRobustness, AFullStoreIsResourceExhaustedAndJobsEndFailed) {
  TempDir dir("robust_full");
  FakeEngine engine;
  engine.steps = 2;
  engine.rows = 200000;  // 200k rows x 2 columns: a result of about 3 MB
  auto options = local_options(dir.path);
  options.max_store_mb = 1;
  std::string id;
  {
    pfem::server::Server server(options, engine.function());
    auto stub = make_stub(server.address());
    ASSERT_TRUE(submit(*stub, fake_request(), &id).ok());
    const auto job = watch_to_end(*stub, id);
    EXPECT_EQ(job.state(), pfem::v1::JOB_STATE_FAILED);
    EXPECT_NE(job.error().message().find("database or disk is full"), std::string::npos)
        << job.error().message();

    auto big = fake_request();
    big.mutable_model()->set_description(std::string(2 << 20, 'x'));
    std::string big_id;
    const auto status = submit(*stub, big, &big_id);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
    EXPECT_TRUE(mentions(status, "full"));
  }
  // The FAILED end is in the store, not only in the server that ran the job (issue 20: such a
  // job stayed RUNNING and ran again after a restart).
  pfem::server::Server restarted(options, engine.function());
  auto stub = make_stub(restarted.address());
  pfem::v1::JobRequest request;
  request.set_job_id(id);
  pfem::v1::Job stored;
  grpc::ClientContext context;
  ASSERT_TRUE(stub->GetJob(&context, request, &stored).ok());
  EXPECT_EQ(stored.state(), pfem::v1::JOB_STATE_FAILED) << pfem::v1::JobState_Name(stored.state());
  EXPECT_EQ(stored.attempts(), 1);
  EXPECT_NE(stored.error().message().find("the job's end could not be stored: database or disk "
                                          "is full"),
            std::string::npos)
      << stored.error().message();
  EXPECT_EQ(restarted.jobs().queued() + restarted.jobs().running(), 0);
  EXPECT_EQ(engine.runs->load(), 1);
}

// One unreadable finished row and one unreadable queued row: the server starts, ListJobs lists
// every job (the bad one flagged), and the queued job still runs from its stored request.
TEST(ServiceRobustness, CorruptedRowsNeitherStopTheServerNorFailListJobs) {
  TempDir dir("robust_corrupt");
  FakeEngine engine;
  engine.steps = 3;
  std::string finished_id, queued_id;
  {
    pfem::server::Server server(local_options(dir.path), engine.function());
    auto stub = make_stub(server.address());
    ASSERT_TRUE(submit(*stub, fake_request(), &finished_id).ok());
    ASSERT_TRUE(submit(*stub, fake_request(), &queued_id).ok());
    wait_for_state(*stub, finished_id, pfem::v1::JOB_STATE_SUCCEEDED);
    wait_for_state(*stub, queued_id, pfem::v1::JOB_STATE_SUCCEEDED);
  }
  sql(dir.path, "UPDATE jobs SET job = X'ffffffff0a' WHERE id = '" + finished_id + "'");
  sql(dir.path,
      "UPDATE jobs SET job = X'ffffffff0a', state = 1 WHERE id = '" + queued_id + "'");
  pfem::server::Server server(local_options(dir.path), engine.function());
  auto stub = make_stub(server.address());
  const auto rerun = wait_for_state(*stub, queued_id, pfem::v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(rerun.state(), pfem::v1::JOB_STATE_SUCCEEDED) << rerun.error().message();

  grpc::ClientContext context;
  pfem::v1::ListJobsRequest request;
  pfem::v1::ListJobsResponse response;
  const auto status = stub->ListJobs(&context, request, &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(response.jobs_size(), 2);
  EXPECT_EQ(response.jobs(1).id(), finished_id);
  EXPECT_EQ(response.jobs(1).state(), pfem::v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(response.jobs(1).error().message(), "stored job record is corrupt");
}

TEST(ServiceRobustness, AnEmptyDatabaseFileIsRefusedNotStartedEmpty) {
  TempDir dir("robust_empty");
  std::ofstream(dir.path / "pfem.sqlite3").close();
  try {
    pfem::server::Server server(local_options(dir.path));
    FAIL() << "the server started on an empty database file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exists but is empty (0 bytes)"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(std::filesystem::file_size(dir.path / "pfem.sqlite3"), 0u);  // left as it was
}

TEST(ServiceRobustness, MalformedRequestBytesAreInvalidArgument) {
  TempDir dir("robust_malformed");
  pfem::server::Server server(local_options(dir.path), FakeEngine{}.function());
  pfem::client::ConnectionOptions connection;
  connection.server = server.address();
  grpc::GenericStub stub(pfem::client::make_channel(connection));
  const char bytes[] = "\xff\xff\xff\xff\x0f";  // a field tag with an invalid wire type
  grpc::Slice slice(bytes, sizeof bytes - 1);
  grpc::ByteBuffer request(&slice, 1);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  grpc::CompletionQueue queue;
  auto call = stub.PrepareUnaryCall(&context, "/pfem.v1.GradientService/SubmitJob", request, &queue);
  call->StartCall();
  grpc::ByteBuffer response;
  grpc::Status status;
  call->Finish(&response, &status, reinterpret_cast<void*>(1));
  void* tag = nullptr;
  bool ok = false;
  ASSERT_TRUE(queue.Next(&tag, &ok));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_TRUE(mentions(status, "/pfem.v1.GradientService/SubmitJob"));
  queue.Shutdown();
  while (queue.Next(&tag, &ok)) {
  }
}

TEST(ServiceRobustness, UnknownListJobsStateFilterIsInvalidArgument) {
  TempDir dir("robust_filter");
  pfem::server::Server server(local_options(dir.path), FakeEngine{}.function());
  auto stub = make_stub(server.address());
  grpc::ClientContext context;
  pfem::v1::ListJobsRequest request;
  request.set_state(static_cast<pfem::v1::JobState>(42));
  pfem::v1::ListJobsResponse response;
  const auto status = stub->ListJobs(&context, request, &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(mentions(status, "state: unknown job state 42"));
}

// 300 bad walls and a 1 MiB job id: INVALID_ARGUMENT naming the fields, the message cut to its
// first errors and a count (a status longer than the client's 8 KiB metadata cap would come
// back as RESOURCE_EXHAUSTED "received initial metadata size exceeds limit").
TEST(ServiceRobustness, LongErrorListsAreTruncatedIntoTheStatusMessage) {
  TempDir dir("robust_long");
  pfem::server::Server server(local_options(dir.path), FakeEngine{}.function());
  auto stub = make_stub(server.address());
  auto request = fake_request();
  for (int i = 0; i < 300; ++i) {
    auto* wall = request.mutable_model()->add_walls();
    wall->set_name("w" + std::to_string(i));  // no points: an error each
  }
  std::string id;
  const auto status = submit(*stub, request, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_TRUE(mentions(status, "walls[1]."));
  EXPECT_TRUE(mentions(status, " more ("));
  EXPECT_LE(status.error_message().size(), pfem::server::kMaxStatusMessageBytes);

  // 150 unknown parameter values: an error each, the first ones kept and the count of all.
  auto values = fake_request();
  for (int i = 0; i < 150; ++i) {
    auto* v = values.add_parameter_values();
    v->set_name("q" + std::to_string(i));
    v->set_value(1.0);
  }
  const auto unknown = submit(*stub, values, &id);
  EXPECT_EQ(unknown.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << unknown.error_message();
  EXPECT_TRUE(mentions(unknown, "parameter_values[0].name: no parameter 'q0' in the model\n"));
  EXPECT_TRUE(mentions(unknown, " more (150 in all)"));
  EXPECT_LE(unknown.error_message().size(), pfem::server::kMaxStatusMessageBytes);

  grpc::ClientContext context;
  pfem::v1::JobRequest job_request;
  job_request.set_job_id(std::string(1 << 20, 'a'));
  pfem::v1::Job job;
  const auto get = stub->GetJob(&context, job_request, &job);
  EXPECT_EQ(get.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << get.error_message().size();
  EXPECT_TRUE(mentions(get, "job_id: too long (1048576 characters"));
}

// What validating and building costs is bounded before that work starts: 300 wall points
// (3.4 CPU-s to validate before) and fiber beams of 200 000 section states are refused at
// once naming the limit; a bow-tie polygon (shoelace area 0, so 0 particles estimated) is an
// invalid field instead of a run of 1 327 particles.
TEST(ServiceRobustness, ModelCostIsBoundedBeforeValidationStarts) {
  TempDir dir("robust_cost");
  pfem::server::Server server(local_options(dir.path), FakeEngine{}.function());
  auto stub = make_stub(server.address());

  auto walls = fake_request();
  auto* wall = walls.mutable_model()->add_walls();
  for (int i = 0; i < 300; ++i) {
    auto* p = wall->add_points();
    p->set_x(0.001 * i);
    p->set_y(0.01 * (i % 2));
  }
  std::string id;
  auto status = submit(*stub, walls, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_TRUE(mentions(status, "max-geometry-points limit exceeded: the walls and fluid polygons have 304 points"));
  {
    grpc::ClientContext context;
    pfem::v1::ValidateModelRequest request;
    *request.mutable_model() = walls.model();
    pfem::v1::ValidateModelResponse response;
    status = stub->ValidateModel(&context, request, &response);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  }

  // Two points far apart are few points but many wall nodes (found by the request fuzzer: a
  // wall point at y = -1.9e57 passed every check, and building it overflowed an int).
  auto long_wall = fake_request();
  auto* far = long_wall.mutable_model()->mutable_walls(0)->mutable_points(1);
  far->set_y(-1.9e57);
  status = submit(*stub, long_wall, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_TRUE(mentions(status, "max-wall-nodes limit exceeded: the walls make 1000000000000000 "
                               "wall nodes (their length / mesh.h), the limit is 20000"));
  far->set_y(-100.0);  // two 100 m walls at h = 0.01: just past the 20 000
  status = submit(*stub, long_wall, &id);
  EXPECT_TRUE(mentions(status, "max-wall-nodes limit exceeded"));

  auto fibers = fake_request();
  auto* structure = fibers.mutable_model()->mutable_structure();
  auto* section = structure->add_sections();
  section->set_name("s");
  section->mutable_fiber_rectangle()->set_fibers(100);
  auto* beam = structure->add_beams();
  beam->set_section("s");
  beam->set_element_type("displacement-based");
  beam->set_elements(1000);
  status = submit(*stub, fibers, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << status.error_message();
  EXPECT_TRUE(mentions(status, "max-fiber-points limit exceeded: the fiber beams have 200000"));

  auto bow_tie = fake_request();
  auto* polygon = bow_tie.mutable_model()->add_fluid_regions()->mutable_polygon();
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.04, 0.04}, {0.04, 0.0}, {0.0, 0.04}}) {
    auto* p = polygon->add_points();
    p->set_x(x);
    p->set_y(y);
  }
  status = submit(*stub, bow_tie, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_TRUE(mentions(status, "fluid_regions[1].polygon: edges 0 and 2 cross"));
}

// Two wall points 1e-9 m apart (1e-7 h) validated, then every run failed in the remesher
// ("constraint 0 (0, 0) needs two different node indices") and Evaluate answered INTERNAL.
// The real engine, so that a model the checks let through would reach the remesher.
TEST(ServiceRobustness, NearDuplicateWallPointsAreAFieldError) {
  TempDir dir("robust_near");
  auto options = local_options(dir.path);
  options.workers = 1;
  pfem::server::Server server(options);
  auto stub = make_stub(server.address());
  auto request = fake_request();
  auto* points = request.mutable_model()->mutable_walls(0)->mutable_points();
  auto* near = points->Add();
  near->set_x(1e-9);
  near->set_y(0.0);
  for (int i = points->size() - 1; i > 1; --i) points->SwapElements(i, i - 1);  // second point
  std::string id;
  const auto status = submit(*stub, request, &id);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_TRUE(mentions(status, "walls[0].points[1]: is only 1e-09 m from the previous point"));

  grpc::ClientContext context;
  pfem::v1::EvaluateRequest evaluate;
  *evaluate.mutable_model() = request.model();
  auto* f = evaluate.add_functionals();
  f->set_recorder("bottom_p");
  f->set_kind(pfem::v1::Functional::KIND_MAX);
  pfem::v1::EvaluateResponse response;
  const auto evaluated = stub->Evaluate(&context, evaluate, &response);
  EXPECT_EQ(evaluated.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
      << evaluated.error_message();
  EXPECT_TRUE(mentions(evaluated, "walls[0].points[1]: is only 1e-09 m from the previous point"));
}

}  // namespace
