// Evaluate: functionals and gradients bit-identical to pfem::run on the same model, the
// cache, stored models, deadlines.
#include "tests/integration/service_test_support.h"

#include "engine/analysis/functional.h"

namespace {

using namespace pfem::testing;

pfem::v1::EvaluateRequest tiny_evaluate(pfem::v1::SensitivityMethod method, double rho) {
  pfem::v1::EvaluateRequest request;
  *request.mutable_model() = tiny_model();
  request.set_sensitivity(method);
  auto* v = request.add_parameter_values();
  v->set_name("rho_f");
  v->set_value(rho);
  const auto add = [&](const char* recorder, pfem::v1::Functional::Kind kind, double t = 0.0) {
    auto* f = request.add_functionals();
    f->set_recorder(recorder);
    f->set_kind(kind);
    f->set_time(t);
  };
  add("bottom_p", pfem::v1::Functional::KIND_MAX);
  add("bottom_p", pfem::v1::Functional::KIND_VALUE_AT, 0.005);
  add("bottom_p", pfem::v1::Functional::KIND_MIN);
  add("fluid_area", pfem::v1::Functional::KIND_MAX_ABS);
  add("front_x", pfem::v1::Functional::KIND_FINAL);
  return request;
}

// The same functionals computed from an in-process run.
std::vector<pfem::FunctionalValue> reference(pfem::SensitivityMethod method, double rho) {
  auto model = tiny_model();
  model.mutable_parameters(0)->set_value(rho);
  pfem::RunOptions options;
  options.sensitivity = method;
  const auto r = pfem::run(model, options);
  const std::vector<pfem::FunctionalSpec> specs = {
      {"bottom_p", pfem::FunctionalKind::kMax, 0.0},
      {"bottom_p", pfem::FunctionalKind::kValueAt, 0.005},
      {"bottom_p", pfem::FunctionalKind::kMin, 0.0},
      {"fluid_area", pfem::FunctionalKind::kMaxAbs, 0.0},
      {"front_x", pfem::FunctionalKind::kFinal, 0.0}};
  std::vector<pfem::FunctionalValue> out;
  for (const auto& s : specs) {
    out.push_back(pfem::evaluate_functional(r.responses, r.sensitivities, r.summary.parameters, s));
  }
  return out;
}

void expect_bit_identical(pfem::v1::SensitivityMethod wire, pfem::SensitivityMethod engine) {
  TempDir dir("evaluate_exact");
  pfem::server::Server server(local_options(dir.path));
  auto stub = make_stub(server.address());
  grpc::ClientContext context;
  pfem::v1::EvaluateResponse response;
  const auto status = stub->Evaluate(&context, tiny_evaluate(wire, 1005.0), &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_FALSE(response.cached());
  ASSERT_EQ(response.parameters_size(), 2);
  EXPECT_EQ(response.parameters(0), "rho_f");
  EXPECT_EQ(response.parameters(1), "kappa");
  EXPECT_EQ(response.parameter_values(0), 1005.0);
  EXPECT_GT(response.wall_seconds(), 0.0);
  EXPECT_EQ(response.summary().steps(), 5);
  const auto expected = reference(engine, 1005.0);
  ASSERT_EQ(response.values_size(), static_cast<int>(expected.size()));
  for (int i = 0; i < response.values_size(); ++i) {
    const auto& got = response.values(i);
    SCOPED_TRACE(got.name());
    EXPECT_EQ(got.value(), expected[i].value);  // bit-identical, not merely close
    EXPECT_EQ(got.time(), expected[i].time);
    ASSERT_EQ(got.gradient_size(), 2);
    EXPECT_EQ(got.gradient(0), expected[i].gradient[0]);
    EXPECT_EQ(got.gradient(1), expected[i].gradient[1]);
  }
  EXPECT_EQ(response.values(0).name(), "bottom_p:max");
  EXPECT_DOUBLE_EQ(response.values(1).time(), 0.005);
  // Hydrostatic-like: the bottom pressure grows with the density (about g * depth per kg/m^3).
  EXPECT_GT(response.values(0).value(), 0.0);
  EXPECT_GT(response.values(0).gradient(0), 0.0);
}

TEST(ServiceEvaluate, FdmGradientsAreBitIdenticalToAnInProcessRun) {
  expect_bit_identical(pfem::v1::SENSITIVITY_METHOD_FDM, pfem::SensitivityMethod::kFdm);
}

TEST(ServiceEvaluate, DdmGradientsAreBitIdenticalToAnInProcessRun) {
  expect_bit_identical(pfem::v1::SENSITIVITY_METHOD_UNSPECIFIED, pfem::SensitivityMethod::kDdm);
}

// An Evaluate builds its model once: its checks build the run's problem, with the DDM's seeds,
// and hand it to the engine (RunOptions::prepared), which neither validates nor builds again
// (prepared_run_test).
TEST(ServiceEvaluate, TheEngineIsHandedTheProblemTheChecksBuilt) {
  TempDir dir("evaluate_prepared");
  auto runs = std::make_shared<std::atomic<int>>(0);
  auto prepared = std::make_shared<std::atomic<int>>(0);
  const auto engine = [runs, prepared](const pfem::v1::Model& m, const pfem::RunOptions& o) {
    ++*runs;
    if (o.prepared) ++*prepared;
    return pfem::run(m, o);
  };
  pfem::server::Server server(local_options(dir.path), engine);
  auto stub = make_stub(server.address());
  for (const auto method : {pfem::v1::SENSITIVITY_METHOD_DDM, pfem::v1::SENSITIVITY_METHOD_NONE}) {
    grpc::ClientContext context;
    pfem::v1::EvaluateResponse response;
    const auto status = stub->Evaluate(&context, tiny_evaluate(method, 1005.0), &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  EXPECT_EQ(runs->load(), 2);
  EXPECT_EQ(prepared->load(), 2);
}

TEST(ServiceEvaluate, RepeatedRequestsHitTheCache) {
  TempDir dir("evaluate_cache");
  FakeEngine engine;
  engine.steps = 20;
  pfem::server::Server server(local_options(dir.path), engine.function());
  auto stub = make_stub(server.address());
  pfem::v1::EvaluateRequest request = tiny_evaluate(pfem::v1::SENSITIVITY_METHOD_DDM, 1000.0);
  request.clear_functionals();
  auto* f = request.add_functionals();  // the fake engine records one history, "x"
  f->set_kind(pfem::v1::Functional::KIND_MAX);
  auto model = tiny_model();
  model.mutable_recorders(0)->set_name("x");
  model.mutable_recorders(0)->set_quantity("p");
  *request.mutable_model() = model;
  f->set_recorder("x");

  pfem::v1::EvaluateResponse first, second, third;
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->Evaluate(&c, request, &first).ok());
  }
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->Evaluate(&c, request, &second).ok());
  }
  EXPECT_FALSE(first.cached());
  EXPECT_TRUE(second.cached());
  EXPECT_EQ(first.run_key(), second.run_key());
  EXPECT_EQ(second.values(0).value(), 0.02);  // x = t, max at t_end = 20 * 1 ms
  EXPECT_EQ(second.values(0).gradient(0), 0.04);
  EXPECT_EQ(engine.runs->load(), 1);
  EXPECT_EQ(server.cache().hits(), 1);

  // A different parameter value is a different run; no_cache always runs.
  request.mutable_parameter_values(0)->set_value(1001.0);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->Evaluate(&c, request, &third).ok());
  }
  EXPECT_FALSE(third.cached());
  EXPECT_NE(third.run_key(), first.run_key());
  request.set_no_cache(true);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->Evaluate(&c, request, &third).ok());
  }
  EXPECT_FALSE(third.cached());
  EXPECT_EQ(engine.runs->load(), 3);

  // A stored model answers by id, from the same cache entry as the inline model.
  pfem::v1::PutModelRequest put;
  *put.mutable_model() = model;
  pfem::v1::PutModelResponse stored;
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->PutModel(&c, put, &stored).ok());
  }
  EXPECT_EQ(stored.model_id().size(), 64u);
  request.set_model_id(stored.model_id());
  request.set_no_cache(false);
  request.mutable_parameter_values(0)->set_value(1000.0);
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->Evaluate(&c, request, &third).ok());
  }
  EXPECT_TRUE(third.cached());
  EXPECT_EQ(third.run_key(), first.run_key());
  request.set_model_id("nope");
  {
    grpc::ClientContext c;
    EXPECT_EQ(stub->Evaluate(&c, request, &third).error_code(), grpc::StatusCode::NOT_FOUND);
  }
}

TEST(ServiceEvaluate, ADeadlineCancelsTheRunAndFreesTheWorker) {
  TempDir dir("evaluate_deadline");
  FakeEngine slow;
  slow.steps = 100000;
  slow.step_seconds = 0.001;
  auto options = local_options(dir.path);
  options.workers = 1;
  pfem::server::Server server(options, slow.function());
  auto stub = make_stub(server.address());
  auto model = tiny_model();
  model.mutable_recorders(0)->set_name("x");
  pfem::v1::EvaluateRequest request;
  *request.mutable_model() = model;
  auto* f = request.add_functionals();
  f->set_recorder("x");
  f->set_kind(pfem::v1::Functional::KIND_FINAL);
  const auto start = std::chrono::steady_clock::now();
  {
    grpc::ClientContext c;
    c.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(200));
    pfem::v1::EvaluateResponse response;
    EXPECT_EQ(stub->Evaluate(&c, request, &response).error_code(),
              grpc::StatusCode::DEADLINE_EXCEEDED);
  }
  // The one worker is free again: a job submitted now starts within a second.
  pfem::v1::SubmitJobRequest submit;
  *submit.mutable_model() = model;
  submit.mutable_options()->set_t_end(0.01);
  pfem::v1::SubmitJobResponse submitted;
  {
    grpc::ClientContext c;
    ASSERT_TRUE(stub->SubmitJob(&c, submit, &submitted).ok());
  }
  const auto job = wait_for_state(*stub, submitted.job_id(), pfem::v1::JOB_STATE_RUNNING, 2.0);
  EXPECT_NE(job.state(), pfem::v1::JOB_STATE_QUEUED);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  pfem::v1::JobRequest cancel;
  cancel.set_job_id(submitted.job_id());
  pfem::v1::Job cancelled;
  grpc::ClientContext c;
  stub->CancelJob(&c, cancel, &cancelled);
}

}  // namespace
