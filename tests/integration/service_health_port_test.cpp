// --health-listen: a second plaintext port that answers grpc.health.v1.Health without the
// token and nothing else (GradientService is UNIMPLEMENTED there), with a "liveness" service
// for Kubernetes' liveness probe; --max-connection-age: the server sends GOAWAY after the
// age, so a connection goes IDLE and the next call reconnects (and re-resolves).
#include "tests/integration/service_test_support.h"

#include <fstream>

namespace {

using namespace pfem::testing;

}  // namespace

TEST(ServiceHealthPort, ServesOnlyHealthWithoutTheToken) {
  TempDir dir("health_port");
  std::ofstream(dir.path / "tokens") << "secret\n";
  auto options = local_options(dir.path / "data");
  options.token_file = dir.path / "tokens";
  options.health_listen = "127.0.0.1:0";
  pfem::server::Server server(options);
  ASSERT_GT(server.health_port(), 0);
  ASSERT_NE(server.health_port(), server.port());
  const std::string health = "127.0.0.1:" + std::to_string(server.health_port());
  for (const std::string service : {"", "liveness", "pfem.v1.GradientService"}) {
    int serving = -1;
    ASSERT_TRUE(health_check(health, service, &serving).ok()) << service;
    EXPECT_EQ(serving, 1) << service;  // SERVING
  }
  int serving = -1;
  EXPECT_EQ(health_check(health, "nope", &serving).error_code(), grpc::StatusCode::NOT_FOUND);

  // The service itself is not on the health port, and needs the token on the main one.
  pfem::v1::ValidateModelRequest request;
  *request.mutable_model() = tiny_model();
  pfem::v1::ValidateModelResponse response;
  grpc::ClientContext on_health;
  EXPECT_EQ(make_stub(health)->ValidateModel(&on_health, request, &response).error_code(),
            grpc::StatusCode::UNIMPLEMENTED);
  grpc::ClientContext on_main;
  EXPECT_EQ(make_stub(server.address())->ValidateModel(&on_main, request, &response).error_code(),
            grpc::StatusCode::UNAUTHENTICATED);
}

TEST(ServiceHealthPort, BadSettingsNameTheFlag) {
  auto o = local_options("/tmp/unused");
  o.listen = "127.0.0.1:7001";
  o.health_listen = "127.0.0.1:7001";
  o.max_connection_age_seconds = -1;
  const auto errors = o.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "--health-listen: must differ from --listen");
  EXPECT_EQ(errors[1], "--max-connection-age: must be in [0, 2147483] seconds (0 = never)");
  EXPECT_THROW(pfem::server::parse_server_options({"--health-listen"}), std::invalid_argument);
}

TEST(ServiceHealthPort, MaxConnectionAgeClosesIdleConnections) {
  TempDir dir("connection_age");
  auto options = local_options(dir.path / "data");
  options.max_connection_age_seconds = 0.5;
  pfem::server::Server server(options);
  // A pick_first channel shows the GOAWAY as READY -> IDLE (round_robin reconnects at once).
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  ASSERT_TRUE(channel->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(5)));
  EXPECT_EQ(channel->GetState(false), GRPC_CHANNEL_READY);
  // The age is jittered by +-10 % and the grace is unlimited for calls; none is in progress.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(channel->GetState(false), GRPC_CHANNEL_IDLE);
  // And the next call simply reconnects.
  pfem::v1::ValidateModelRequest request;
  *request.mutable_model() = tiny_model();
  pfem::v1::ValidateModelResponse response;
  grpc::ClientContext context;
  EXPECT_TRUE(pfem::v1::GradientService::NewStub(channel)->ValidateModel(&context, request, &response).ok());
}
