// Bad requests get exact status codes naming the field or the limit; bearer-token auth;
// health stays open.
#include "tests/integration/service_test_support.h"

#include <grpcpp/generic/generic_stub.h>

#include <cmath>
#include <fstream>

namespace {

using namespace pfem::testing;

struct Case {
  const char* what;
  std::function<void(pfem::v1::Model&)> spoil;
  const char* field;  // expected in the status message
};

pfem::v1::Functional final_of(const char* recorder) {
  pfem::v1::Functional f;
  f.set_recorder(recorder);
  f.set_kind(pfem::v1::Functional::KIND_FINAL);
  return f;
}

class ServiceErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    auto options = local_options(dir_.path);
    options.limits.max_particles = 1000;
    options.limits.max_steps = 100;
    options.limits.max_message_mb = 1;
    server_ = std::make_unique<pfem::server::Server>(options, FakeEngine{}.function());
    stub_ = make_stub(server_->address());
  }

  grpc::Status submit(const pfem::v1::SubmitJobRequest& request) {
    grpc::ClientContext c;
    pfem::v1::SubmitJobResponse response;
    return stub_->SubmitJob(&c, request, &response);
  }
  grpc::Status evaluate(const pfem::v1::EvaluateRequest& request) {
    grpc::ClientContext c;
    pfem::v1::EvaluateResponse response;
    return stub_->Evaluate(&c, request, &response);
  }

  TempDir dir_{"errors"};
  std::unique_ptr<pfem::server::Server> server_;
  std::unique_ptr<pfem::v1::GradientService::Stub> stub_;
};

TEST_F(ServiceErrors, EveryBadModelIsInvalidArgumentNamingTheField) {
  const std::vector<Case> cases = {
      {"negative density", [](auto& m) { m.mutable_fluid()->set_rho(-1000.0); }, "fluid.rho: must be > 0"},
      {"zero spacing", [](auto& m) { m.mutable_mesh()->set_h(0.0); }, "mesh.h: must be > 0"},
      {"NaN", [](auto& m) { m.mutable_analysis()->set_dt(std::nan("")); }, "analysis.dt"},
      {"empty model", [](auto& m) { m = pfem::v1::Model(); }, "model: is empty"},
      {"unknown recorder target",
       [](auto& m) { m.mutable_recorders(0)->set_node("nowhere"); }, "recorders[0].node: unknown node 'nowhere'"},
      {"unknown quantity", [](auto& m) { m.mutable_recorders(1)->set_quantity("vorticity"); },
       "recorders[1].quantity"},
      {"bad parameter target", [](auto& m) { m.mutable_parameters(0)->set_targets(0, "fluid.colour"); },
       "parameters[0].targets[0]"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    pfem::v1::SubmitJobRequest request;
    *request.mutable_model() = tiny_model();
    c.spoil(*request.mutable_model());
    auto status = submit(request);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(mentions(status, c.field));

    pfem::v1::EvaluateRequest eval;
    *eval.mutable_model() = request.model();
    *eval.add_functionals() = final_of("bottom_p");
    status = evaluate(eval);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(mentions(status, c.field));

    grpc::ClientContext context;
    pfem::v1::ValidateModelRequest validate;
    *validate.mutable_model() = request.model();
    pfem::v1::ValidateModelResponse answer;
    ASSERT_TRUE(stub_->ValidateModel(&context, validate, &answer).ok());
    EXPECT_FALSE(answer.valid());
    ASSERT_GE(answer.errors_size(), 1);
  }
}

TEST_F(ServiceErrors, AllErrorsOfARequestComeTogether) {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = tiny_model();
  request.mutable_model()->mutable_fluid()->set_rho(-1.0);
  request.mutable_model()->mutable_mesh()->set_h(0.0);
  auto* v = request.add_parameter_values();
  v->set_name("gamma");
  v->set_value(1.0);
  request.mutable_options()->set_t_end(-1.0);
  request.mutable_options()->add_params("nu");
  const auto status = submit(request);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(mentions(status, "parameter_values[0].name: no parameter 'gamma' in the model"));
  EXPECT_TRUE(mentions(status, "fluid.rho: must be > 0"));
  EXPECT_TRUE(mentions(status, "mesh.h: must be > 0"));
  EXPECT_TRUE(mentions(status, "options.t_end: must be > 0 and finite"));
  EXPECT_TRUE(mentions(status, "options.params[0]: no parameter 'nu' in the model"));

  // A run's step longer than the run, through the options or against the model's analysis.
  request = {};
  *request.mutable_model() = tiny_model();  // dt 0.002, t_end 0.01
  request.mutable_options()->set_dt(0.1);
  EXPECT_TRUE(mentions(submit(request), "options.dt: must not exceed t_end (0.01)"));
  request.mutable_options()->clear_dt();
  request.mutable_options()->set_t_end(0.001);
  EXPECT_TRUE(mentions(submit(request), "options.t_end: must not be less than dt (0.002)"));
  request.mutable_options()->set_dt(0.0005);
  EXPECT_TRUE(submit(request).ok());

  // A parameter value that breaks the model's rules, and an infinite one.
  request = {};
  *request.mutable_model() = tiny_model();
  v = request.add_parameter_values();
  v->set_name("rho_f");
  v->set_value(-5.0);
  EXPECT_TRUE(mentions(submit(request), "parameters[0].value: must be > 0 for fluid.rho"));
  v->set_value(INFINITY);
  EXPECT_TRUE(mentions(submit(request), "parameter_values[0].value: must be finite"));

  pfem::v1::EvaluateRequest eval;
  *eval.mutable_model() = tiny_model();
  EXPECT_TRUE(mentions(evaluate(eval), "functionals: at least one is required"));
  *eval.add_functionals() = final_of("tip");
  auto* at = eval.add_functionals();
  at->set_recorder("bottom_p");
  at->set_kind(pfem::v1::Functional::KIND_VALUE_AT);
  at->set_time(NAN);
  eval.add_functionals()->set_recorder("bottom_p");
  auto* window = eval.add_functionals();
  window->set_recorder("bottom_p");
  window->set_kind(pfem::v1::Functional::KIND_MAX);
  window->set_window_start(0.2);
  window->set_window_end(0.1);
  *eval.add_functionals() = final_of("bottom_p");
  eval.mutable_functionals(4)->set_window_start(0.1);
  const auto status2 = evaluate(eval);
  EXPECT_EQ(status2.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(mentions(status2, "functionals[0].recorder: no recorder 'tip' in the model"));
  EXPECT_TRUE(mentions(status2, "functionals[1].time: must be finite"));
  EXPECT_TRUE(mentions(status2, "functionals[2].kind"));
  EXPECT_TRUE(mentions(status2, "functionals[3].window_end: must be >= window_start"));
  EXPECT_TRUE(mentions(status2, "functionals[4].window_start: only used with max, min and max_abs"));
  pfem::v1::EvaluateRequest nothing;
  EXPECT_TRUE(mentions(evaluate(nothing), "model: required"));

  pfem::v1::JobRequest empty;
  pfem::v1::Job job;
  grpc::ClientContext c;
  const auto status3 = stub_->GetJob(&c, empty, &job);
  EXPECT_EQ(status3.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(mentions(status3, "job_id: required"));
}

TEST_F(ServiceErrors, LimitsAreResourceExhaustedNamingTheLimit) {
  pfem::v1::SubmitJobRequest request;
  *request.mutable_model() = tiny_model();
  // 0.5 m x 0.4 m at h = 0.01: about 2000 particles > 1000.
  auto* big = request.mutable_model()->mutable_fluid_regions(0)->mutable_rectangle();
  big->mutable_max()->set_x(0.5);
  big->mutable_max()->set_y(0.4);
  auto* wall = request.mutable_model()->mutable_walls(0);
  wall->mutable_points(1)->set_x(0.5);
  wall->mutable_points(2)->set_x(0.5);
  wall->mutable_points(2)->set_y(0.8);
  wall->mutable_points(3)->set_y(0.8);
  auto status = submit(request);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(mentions(status, "max-particles limit exceeded: the model has about 2000"));
  // ValidateModel finds the model valid and says which limit it exceeds here.
  for (const bool over : {true, false}) {
    grpc::ClientContext c;
    pfem::v1::ValidateModelRequest validate;
    *validate.mutable_model() = over ? request.model() : tiny_model();
    pfem::v1::ValidateModelResponse answer;
    ASSERT_TRUE(stub_->ValidateModel(&c, validate, &answer).ok());
    EXPECT_TRUE(answer.valid());
    EXPECT_EQ(answer.over_limit().rfind("max-particles limit exceeded: the model has about 2000", 0),
              over ? 0u : std::string::npos)
        << answer.over_limit();
  }

  pfem::v1::EvaluateRequest eval;
  *eval.mutable_model() = request.model();
  *eval.add_functionals() = final_of("bottom_p");
  EXPECT_EQ(evaluate(eval).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);

  *request.mutable_model() = tiny_model();
  request.mutable_options()->set_t_end(1.0);  // 500 steps of 2 ms > 100
  status = submit(request);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(mentions(status, "max-steps limit exceeded: the run has 500 steps"));

  // A message over --max-message-mb 1.
  *request.mutable_model() = tiny_model();
  request.clear_options();
  request.mutable_model()->set_description(std::string(1100 * 1024, 'x'));
  status = submit(request);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
}

// The names of the services listed by server reflection (grpc.reflection.v1alpha), read from
// the raw response bytes.
std::string reflection_list(const std::string& address) {
  auto channel = grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
  grpc::GenericStub stub(channel);
  grpc::CompletionQueue cq;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  auto call = stub.PrepareCall(&context,
                               "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo", &cq);
  void* tag = nullptr;
  bool ok = false;
  call->StartCall(reinterpret_cast<void*>(1));
  cq.Next(&tag, &ok);
  const char list_services[] = {0x3a, 0x00};  // ServerReflectionRequest{list_services: ""}
  grpc::Slice slice(list_services, sizeof list_services);
  grpc::ByteBuffer request(&slice, 1);
  call->Write(request, reinterpret_cast<void*>(2));
  cq.Next(&tag, &ok);
  grpc::ByteBuffer response;
  call->Read(&response, reinterpret_cast<void*>(3));
  cq.Next(&tag, &ok);
  std::string bytes;
  std::vector<grpc::Slice> slices;
  if (ok && response.Dump(&slices).ok()) {
    for (const auto& s : slices) bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  call->WritesDone(reinterpret_cast<void*>(4));
  cq.Next(&tag, &ok);
  grpc::Status status;
  call->Finish(&status, reinterpret_cast<void*>(5));
  cq.Next(&tag, &ok);
  cq.Shutdown();
  while (cq.Next(&tag, &ok)) {
  }
  return bytes;
}

TEST(ServiceReflection, ListsTheServicesWhenEnabled) {
  TempDir dir("reflection");
  auto options = local_options(dir.path);
  options.reflection = true;
  pfem::server::Server server(options, FakeEngine{}.function());
  const std::string listed = reflection_list(server.address());
  EXPECT_NE(listed.find("pfem.v1.GradientService"), std::string::npos);
  EXPECT_NE(listed.find("grpc.health.v1.Health"), std::string::npos);
}

// Reflection lists every method and the model schema to anyone: off unless --reflection.
TEST(ServiceReflection, IsOffByDefault) {
  TempDir dir("no_reflection");
  pfem::server::Server server(local_options(dir.path), FakeEngine{}.function());
  EXPECT_EQ(reflection_list(server.address()).find("pfem.v1.GradientService"), std::string::npos);
}

TEST(ServiceAuth, MissingOrWrongTokensAreUnauthenticatedHealthIncluded) {
  TempDir dir("auth");
  const auto token_file = dir.path / "tokens";
  std::ofstream(token_file) << "right-token\n";
  auto options = local_options(dir.path / "data");
  options.token_file = token_file;
  pfem::server::Server server(options, FakeEngine{}.function());
  auto stub = make_stub(server.address());

  pfem::v1::ValidateModelRequest validate;
  *validate.mutable_model() = tiny_model();
  pfem::v1::ValidateModelResponse answer;
  pfem::v1::JobRequest job_request;
  job_request.set_job_id("0123456789abcdef");
  pfem::v1::Job job;
  pfem::v1::ListJobsResponse jobs;
  pfem::v1::SubmitJobRequest submit;
  *submit.mutable_model() = tiny_model();
  pfem::v1::SubmitJobResponse submitted;

  for (const char* header : {"", "Bearer wrong-token", "right-token", "Bearer right-token "}) {
    SCOPED_TRACE(header);
    const auto with = [&](grpc::ClientContext& c) {
      if (*header) c.AddMetadata("authorization", header);
    };
    const bool good = std::string(header) == "Bearer right-token ";  // trailing blanks trimmed
    const auto expect = good ? grpc::StatusCode::OK : grpc::StatusCode::UNAUTHENTICATED;
    {
      grpc::ClientContext c;
      with(c);
      const auto s = stub->ValidateModel(&c, validate, &answer);
      EXPECT_EQ(s.error_code(), expect);
      if (!good) {
        EXPECT_EQ(s.error_message(), "missing or invalid bearer token");
      }
    }
    {
      grpc::ClientContext c;
      with(c);
      EXPECT_EQ(stub->ListJobs(&c, {}, &jobs).error_code(), expect);
    }
    {
      grpc::ClientContext c;
      with(c);  // an unknown job: NOT_FOUND only once authenticated
      EXPECT_EQ(stub->GetJob(&c, job_request, &job).error_code(),
                good ? grpc::StatusCode::NOT_FOUND : grpc::StatusCode::UNAUTHENTICATED);
    }
    {
      grpc::ClientContext c;
      with(c);
      EXPECT_EQ(stub->SubmitJob(&c, submit, &submitted).error_code(), expect);
    }
    {
      grpc::ClientContext c;
      with(c);
      auto reader = stub->WatchJob(&c, job_request);
      while (reader->Read(&job)) {
      }
      EXPECT_EQ(reader->Finish().error_code(),
                good ? grpc::StatusCode::NOT_FOUND : grpc::StatusCode::UNAUTHENTICATED);
    }
  }
  // The health service of the main port needs the token too (without one: --health-listen).
  for (const std::string service : {"", "pfem.v1.GradientService"}) {
    int serving = -1;
    const auto refused = health_check(server.address(), service, &serving);
    EXPECT_EQ(refused.error_code(), grpc::StatusCode::UNAUTHENTICATED) << service;
    EXPECT_EQ(refused.error_message(), "missing or invalid bearer token");
    ASSERT_TRUE(health_check(server.address(), service, &serving, "right-token").ok()) << service;
    EXPECT_EQ(serving, 1) << service;
  }
  int serving = -1;
  EXPECT_EQ(health_check(server.address(), "pfem.v1.NoSuchService", &serving, "right-token")
                .error_code(),
            grpc::StatusCode::NOT_FOUND);
}

// A second server may neither share the first one's port (gRPC would let both listen and
// split the calls) nor its data dir (it would run the first one's jobs again).
TEST(ServiceStart, ASecondServerOnTheSamePortOrDataDirDoesNotStart) {
  TempDir dir("second");
  auto first = std::make_unique<pfem::server::Server>(local_options(dir.path / "one"),
                                                      FakeEngine{}.function());
  const std::string address = first->address();
  auto same_port = local_options(dir.path / "two");
  same_port.listen = address;
  try {
    pfem::server::Server second(same_port, FakeEngine{}.function());
    ADD_FAILURE() << "a second server started on " << address;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--listen: cannot listen on " + address), std::string::npos)
        << e.what();
  }
  try {
    pfem::server::Server second(local_options(dir.path / "one"), FakeEngine{}.function());
    ADD_FAILURE() << "a second server started on the same data dir";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is in use by another server"), std::string::npos) << e.what();
  }
  // The first still answers; its data dir is free once it is gone.
  auto stub = make_stub(address);
  pfem::v1::ListJobsRequest list;
  pfem::v1::ListJobsResponse jobs;
  grpc::ClientContext c;
  EXPECT_TRUE(stub->ListJobs(&c, list, &jobs).ok());
  first.reset();
  EXPECT_NO_THROW(pfem::server::Server(local_options(dir.path / "one"), FakeEngine{}.function()));
}

}  // namespace
