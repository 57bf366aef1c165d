// Bearer tokens, resource limits and the status mapping of the server.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "server/auth.h"
#include "server/hashing.h"
#include "server/limits.h"
#include "server/options.h"
#include "server/status.h"
#include "wire/status_name.h"

namespace {

using pfem::server::TokenAuth;

TEST(ServerAuth, AcceptsOnlyKnownBearerTokens) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("pfem_tokens_" + std::to_string(::getpid()));
  {
    std::ofstream out(file);
    out << "# tokens\n\n  s3cret-one  \nsecond\n";
  }
  const auto auth = TokenAuth::from_file(file);
  std::filesystem::remove(file);
  EXPECT_TRUE(auth.enabled());
  EXPECT_TRUE(auth.accepts("Bearer s3cret-one"));
  EXPECT_TRUE(auth.accepts("bearer second"));
  EXPECT_FALSE(auth.accepts("Bearer s3cret-on"));
  EXPECT_FALSE(auth.accepts("Bearer "));
  EXPECT_FALSE(auth.accepts("s3cret-one"));
  EXPECT_FALSE(auth.accepts("Basic s3cret-one"));
  EXPECT_FALSE(auth.accepts("Bearer # tokens"));
  EXPECT_FALSE(TokenAuth().enabled());
  EXPECT_THROW(TokenAuth::from_file("/nonexistent/tokens"), std::runtime_error);
}

TEST(ServerAuth, ConstantTimeEqualAndHashes) {
  EXPECT_TRUE(pfem::server::constant_time_equal("abc", "abc"));
  EXPECT_FALSE(pfem::server::constant_time_equal("abc", "abd"));
  EXPECT_FALSE(pfem::server::constant_time_equal("abc", "abcd"));
  EXPECT_EQ(pfem::server::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(ServerLimits, ParticlesAndSteps) {
  pfem::v1::Model model;
  model.mutable_mesh()->set_h(0.01);
  auto* rect = model.add_fluid_regions()->mutable_rectangle();
  rect->mutable_min()->set_x(0.0);
  rect->mutable_min()->set_y(0.0);
  rect->mutable_max()->set_x(0.2);
  rect->mutable_max()->set_y(0.1);
  auto* poly = model.add_fluid_regions()->mutable_polygon();  // a right triangle, area 0.005
  for (auto [x, y] : {std::pair{0.0, 0.0}, {0.1, 0.0}, {0.0, 0.1}}) {
    auto* p = poly->add_points();
    p->set_x(x);
    p->set_y(y);
  }
  EXPECT_EQ(pfem::estimate_particles(model), 200 + 50);
  model.mutable_analysis()->set_t_end(0.5);
  model.mutable_analysis()->set_dt(0.002);
  EXPECT_EQ(pfem::count_steps(model, std::nullopt, std::nullopt), 250);
  EXPECT_EQ(pfem::count_steps(model, 0.01, std::nullopt), 5);
  EXPECT_EQ(pfem::count_steps(model, std::nullopt, 0.003), 167);

  pfem::server::Limits limits;
  limits.max_particles = 249;
  try {
    pfem::server::check_run_limits(model, std::nullopt, std::nullopt, limits);
    FAIL();
  } catch (const pfem::server::ServiceError& e) {
    EXPECT_EQ(e.code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(std::string(e.what()).find("max-particles"), std::string::npos);
  }
  limits.max_particles = 250;
  limits.max_steps = 249;
  try {
    pfem::server::check_run_limits(model, std::nullopt, std::nullopt, limits);
    FAIL();
  } catch (const pfem::server::ServiceError& e) {
    EXPECT_EQ(e.code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(std::string(e.what()).find("max-steps"), std::string::npos);
  }
  EXPECT_NO_THROW(pfem::server::check_run_limits(model, 0.2, std::nullopt, limits));
}

TEST(ServerStatus, OneMappingForEveryException) {
  using pfem::server::guarded;
  EXPECT_EQ(guarded([]() -> grpc::Status {
              throw pfem::server::ServiceError(grpc::StatusCode::NOT_FOUND, "no job");
            }).error_code(),
            grpc::StatusCode::NOT_FOUND);
  const auto invalid = guarded([]() -> grpc::Status {
    pfem::server::throw_invalid({{"fluid.rho", "must be > 0"}, {"mesh.h", "must be > 0"}});
  });
  EXPECT_EQ(invalid.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(invalid.error_message(), "fluid.rho: must be > 0\nmesh.h: must be > 0");
  const auto internal = guarded([]() -> grpc::Status { throw std::runtime_error("secret"); });
  EXPECT_EQ(internal.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_EQ(internal.error_message(), "internal error");  // details stay in the log
  EXPECT_EQ(pfem::wire::status_code_name(grpc::StatusCode::UNAUTHENTICATED), "UNAUTHENTICATED");
}

TEST(ServerOptions, ValidationNamesTheFlag) {
  auto o = pfem::server::parse_server_options(
      {"--listen", "127.0.0.1:0", "--data-dir", "/tmp/x", "--workers", "3", "--max-steps", "10"});
  EXPECT_EQ(o.workers, 3);
  EXPECT_EQ(o.limits.max_steps, 10);
  EXPECT_TRUE(o.validate().empty());
  o.tls_cert = "cert.pem";
  o.data_dir.clear();
  const auto errors = o.validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "--data-dir: required");
  EXPECT_EQ(errors[1], "--tls-cert/--tls-key: give both or neither");
  EXPECT_THROW(pfem::server::parse_server_options({"--bogus", "1"}), std::invalid_argument);
  EXPECT_THROW(pfem::server::parse_server_options({"--workers", "x"}), std::invalid_argument);
}

}  // namespace
