// The server's ValidateModel answers what `pfem validate` prints: the same warnings (word for
// word), the same particle, element and step estimates, and a run time from its own measured
// speed. A real server on 127.0.0.1 against the real `pfem` command.
#include "tests/integration/service_test_support.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace {

using namespace pfem::testing;

struct CliValidation {
  std::vector<std::string> warnings;  // "path: message"
  long particles = -1, elements = -1, steps = -1;
  double seconds_per_particle_step = 0.0;
};

std::string contents(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliValidation pfem_validate(const pfem::v1::Model& model, const TempDir& dir) {
  const auto file = dir.path / "model.json", out = dir.path / "stdout", err = dir.path / "stderr";
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(model, &json, options).ok());
  std::ofstream(file) << json;
  const std::string command = std::string(PFEM_BINARY_DIR) + "/bin/pfem validate " + file.string() + " >" +
                              out.string() + " 2>" + err.string();
  EXPECT_EQ(std::system(command.c_str()), 0) << contents(err);
  CliValidation v;
  std::istringstream lines(contents(err));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("warning: ", 0) == 0) v.warnings.push_back(line.substr(9));
  const std::regex estimate(R"(estimate: (\d+) particles, about (\d+) elements, (\d+) steps, about .* at ([0-9.e+-]+) us per particle and step measured here\))");
  std::smatch m;
  const std::string text = contents(out);
  EXPECT_TRUE(std::regex_search(text, m, estimate)) << text;
  if (m.size() == 5) {
    v.particles = std::stol(m[1]), v.elements = std::stol(m[2]), v.steps = std::stol(m[3]);
    v.seconds_per_particle_step = std::stod(m[4]) * 1e-6;
  }
  return v;
}

TEST(ServiceValidate, TheSameWarningsAndEstimateAsPfemValidate) {
  TempDir dir{"validate"};
  pfem::server::Server server(local_options(dir.path));
  auto stub = make_stub(server.address());
  ASSERT_EQ(server.address().rfind("127.0.0.1:", 0), 0u);

  auto model = tiny_model();
  model.mutable_fluid()->set_rho(1.0);    // outside [100, 30000] kg/m^3
  model.mutable_fluid()->set_kappa(5.0);  // sound at 2.2 m/s, below 10 sqrt(2 g H) = 8.9 m/s
  model.mutable_analysis()->set_dt(0.02);  // above h / sqrt(2 g H) = 0.011 s
  model.mutable_analysis()->set_t_end(0.2);
  model.mutable_recorders(0)->mutable_point()->set_y(0.07);  // 3 cm above the water: no node near
  const CliValidation cli = pfem_validate(model, dir);
  ASSERT_GE(cli.warnings.size(), 3u);

  grpc::ClientContext context;
  pfem::v1::ValidateModelRequest request;
  *request.mutable_model() = model;
  pfem::v1::ValidateModelResponse answer;
  ASSERT_TRUE(stub->ValidateModel(&context, request, &answer).ok());
  EXPECT_TRUE(answer.valid());
  std::vector<std::string> warnings;
  for (const auto& w : answer.warnings()) warnings.push_back(w.path() + ": " + w.message());
  EXPECT_EQ(warnings, cli.warnings);
  for (const char* field : {"fluid.rho", "fluid.kappa", "analysis.dt", "recorders[0]"})
    EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [&](const auto& w) { return w.rfind(field, 0) == 0; }))
        << field;
  EXPECT_EQ(answer.estimated_particles(), 20);
  EXPECT_EQ(answer.estimated_particles(), cli.particles);
  EXPECT_EQ(answer.estimated_elements(), cli.elements);
  EXPECT_EQ(answer.steps(), 10);
  EXPECT_EQ(answer.steps(), cli.steps);
  // The speed is measured in each process: the same machine within a factor of 3 (shared cores).
  EXPECT_GT(answer.seconds_per_particle_step(), cli.seconds_per_particle_step / 3);
  EXPECT_LT(answer.seconds_per_particle_step(), cli.seconds_per_particle_step * 3);
  EXPECT_DOUBLE_EQ(answer.estimated_seconds(), answer.seconds_per_particle_step() * 20 * 10);

  // An invalid model: errors, no warnings (as pfem validate), still the estimate.
  model.mutable_mesh()->set_h(-1.0);
  grpc::ClientContext again;
  *request.mutable_model() = model;
  pfem::v1::ValidateModelResponse invalid;
  ASSERT_TRUE(stub->ValidateModel(&again, request, &invalid).ok());
  EXPECT_FALSE(invalid.valid());
  EXPECT_EQ(invalid.warnings_size(), 0);
}

}  // namespace
