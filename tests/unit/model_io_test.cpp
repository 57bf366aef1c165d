// Model files: bad input is reported with the exact field path and a clear message, valid
// examples validate cleanly, and the `pfem` command turns bad input into exit code 2 with one
// `path: message` line per error on stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_checks.h"
#include "engine/io/model_io.h"
#include "engine/io/model_size.h"

namespace pfem {
namespace {

namespace fs = std::filesystem;

std::string source(const std::string& relative) { return std::string(PFEM_SOURCE_DIR) + "/" + relative; }

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The hydrostatic example as a message, for mutation.
pfem::v1::Model valid_model() { return read_model_file(source("examples/hydrostatic.json")); }

// The example's JSON text with the first occurrence of `from` replaced by `to`.
std::string edited_json(const std::string& from, const std::string& to) {
  std::string json = read_text(source("examples/hydrostatic.json"));
  const auto at = json.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in examples/hydrostatic.json";
  if (at != std::string::npos) json.replace(at, from.size(), to);
  return json;
}

std::string describe(const std::vector<FieldError>& errors) {
  std::string out;
  for (const auto& e : errors) out += "\n  " + e.to_string();
  return out.empty() ? " (none)" : out;
}

// Exactly one error, at `path`, whose message contains `fragment`.
void expect_single_error(const std::vector<FieldError>& errors, const std::string& path,
                         const std::string& fragment) {
  ASSERT_EQ(errors.size(), 1u) << "errors:" << describe(errors);
  EXPECT_EQ(errors[0].path, path);
  EXPECT_NE(errors[0].message.find(fragment), std::string::npos)
      << "message '" << errors[0].message << "' lacks '" << fragment << "'";
}

TEST(ModelValidation, ValidExamplesHaveNoErrors) {
  for (const char* name : {"examples/hydrostatic.json", "examples/dam-break.json"}) {
    const auto model = read_model_file(source(name));
    EXPECT_TRUE(validate_model(model).empty()) << name << ":" << describe(validate_model(model));
  }
}

TEST(ModelValidation, NegativeDensity) {
  auto m = valid_model();
  m.mutable_fluid()->set_rho(-1000.0);
  expect_single_error(validate_model(m), "fluid.rho", "must be > 0");
}

TEST(ModelValidation, ZeroParticleSpacing) {
  auto m = valid_model();
  m.mutable_mesh()->set_h(0.0);
  expect_single_error(validate_model(m), "mesh.h", "must be > 0");
}

// Wall length / h, not the points, is what building costs: two points 1e57 m apart validated
// and overflowed an int in the builder (found by the request fuzzer).
TEST(ModelValidation, WallsOfTooManyNodes) {
  auto m = valid_model();
  EXPECT_EQ(count_wall_nodes(m), 100);  // the 0.2 m x 0.3 m box at h = 0.01
  m.mutable_walls(0)->mutable_points(3)->set_y(-1.9e57);
  EXPECT_EQ(count_wall_nodes(m), 1'000'000'000'000'000);
  expect_single_error(validate_model(m), "mesh.h",
                      "gives 1000000000000000 wall nodes (wall length / mesh.h), more than the "
                      "100000 a model may have");
}

// A beam node 6.6e197 m away: the advice on the element count had cast that count to a long
// (undefined behaviour, found by the request fuzzer).
TEST(ModelValidation, ABeamTooLongForAnyElementCountSaysSo) {
  auto m = read_model_file(source("examples/sloshing-beam.json"));
  m.mutable_structure()->mutable_nodes(0)->set_x(6.6e197);
  const auto errors = validate_model(m);
  const auto it = std::find_if(errors.begin(), errors.end(), [](const FieldError& e) {
    return e.path == "structure.beams[0].elements";
  });
  ASSERT_NE(it, errors.end()) << describe(errors);
  EXPECT_NE(it->message.find("it would need more than the 10000 elements a beam may have"),
            std::string::npos)
      << it->message;
}

TEST(ModelValidation, BoundaryAlphaOutOfRange) {
  auto m = valid_model();
  m.mutable_mesh()->set_boundary_alpha(0.3);
  expect_single_error(validate_model(m), "mesh.boundary_alpha", "must be 0 (same as alpha) or in [0.6, 3]");
  m.mutable_mesh()->set_boundary_alpha(0.0);
  EXPECT_TRUE(validate_model(m).empty());
}

TEST(ModelValidation, InteriorInsertionLengthOutOfRange) {
  auto m = valid_model();
  m.mutable_mesh()->set_interior_insertion_length(1.2);
  expect_single_error(validate_model(m), "mesh.interior_insertion_length",
                      "must be 0 (same as insertion_length) or in [1.5, 3]");
  m.mutable_mesh()->set_interior_insertion_length(0.0);
  EXPECT_TRUE(validate_model(m).empty());
}

TEST(ModelValidation, VolumeRelaxationStepsOutOfRange) {
  auto m = valid_model();
  for (const double bad : {0.5, -1.0, 1001.0, std::nan("")}) {
    m.mutable_mesh()->set_volume_relaxation_steps(bad);
    expect_single_error(validate_model(m), "mesh.volume_relaxation_steps", "must be 0 (off) or in [1, 1000]");
  }
  m.mutable_mesh()->set_volume_relaxation_steps(0.0);
  EXPECT_TRUE(validate_model(m).empty());
}

TEST(ModelValidation, FluidRegionOutsideEveryWall) {
  auto m = valid_model();
  auto* r = m.mutable_fluid_regions(0)->mutable_rectangle();
  r->mutable_min()->set_x(1.0), r->mutable_min()->set_y(1.0);
  r->mutable_max()->set_x(1.2), r->mutable_max()->set_y(1.2);
  expect_single_error(validate_model(m), "fluid_regions[0]", "reaches beyond the walls");
}

// JSON has no NaN literal; the proto3 JSON mapping accepts the strings "NaN", "Infinity" and
// "-Infinity" for doubles. They must parse, and validation must reject them.
TEST(ModelValidation, NaNAndInfinityFromJsonStringsAreRejected) {
  const auto nan_rho = parse_model_json(edited_json("\"rho\": 1000.0", "\"rho\": \"NaN\""));
  EXPECT_TRUE(std::isnan(nan_rho.fluid().rho()));
  expect_single_error(validate_model(nan_rho), "fluid.rho", "must be a finite number");

  const auto inf_h = parse_model_json(edited_json("\"h\": 0.01", "\"h\": \"Infinity\""));
  EXPECT_TRUE(std::isinf(inf_h.mesh().h()));
  const auto errors = validate_model(inf_h);
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors[0].path, "mesh.h");
  EXPECT_NE(errors[0].message.find("must be a finite number"), std::string::npos) << describe(errors);
}

// An empty model says so, and every other error comes back with it.
TEST(ModelValidation, EmptyModel) {
  const auto errors = validate_model(parse_model_json("{}"));
  ASSERT_GE(errors.size(), 1u);
  EXPECT_EQ(errors[0].path, "model");
  EXPECT_EQ(errors[0].message.rfind("is empty", 0), 0u) << errors[0].message;
  const auto with_rho = validate_model(parse_model_json(R"({"fluid": {"rho": -1}})"));
  EXPECT_TRUE(std::any_of(with_rho.begin(), with_rho.end(), [](const FieldError& e) {
    return e.to_string() == "fluid.rho: must be > 0";
  })) << describe(with_rho);
}

TEST(ModelValidation, UnknownRecorderNode) {
  auto m = valid_model();
  auto* r = m.add_recorders();
  r->set_name("beam_tip_ux");
  r->set_quantity("ux");
  r->set_node("beam_tip");
  const std::string path = "recorders[" + std::to_string(m.recorders_size() - 1) + "].node";
  expect_single_error(validate_model(m), path, "unknown node 'beam_tip'");
}

TEST(ModelValidation, UnknownQuantity) {
  auto m = valid_model();
  auto* r = m.add_recorders();
  r->set_name("vorticity");
  r->set_quantity("vorticity");
  const std::string path = "recorders[" + std::to_string(m.recorders_size() - 1) + "].quantity";
  expect_single_error(validate_model(m), path, "unknown quantity 'vorticity'");
}

// A force or moment recorder names one wall or beam; `about` belongs to moments only.
TEST(ModelValidation, BoundaryRecorders) {
  auto m = valid_model();
  auto* r = m.add_recorders();
  r->set_name("gate_fx");
  r->set_quantity("force_x");
  const std::string path = "recorders[" + std::to_string(m.recorders_size() - 1) + "]";
  expect_single_error(validate_model(m), path, "quantity 'force_x' needs a target: boundary (a wall or beam name)");
  r->set_boundary("gate");
  expect_single_error(validate_model(m), path + ".boundary", "no wall or beam is named 'gate'");
  m.mutable_walls(0)->set_name("gate");
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
  r->mutable_about()->set_x(0.0);
  expect_single_error(validate_model(m), path + ".about", "only for the quantity moment");
  r->set_quantity("moment");
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
}

TEST(ModelValidation, UnknownParameterTarget) {
  auto m = valid_model();
  auto* p = m.add_parameters();
  p->set_name("E");
  p->add_targets("structure.materials[0].E");
  const std::string path = "parameters[" + std::to_string(m.parameters_size() - 1) + "].targets[0]";
  expect_single_error(validate_model(m), path, "unknown target 'structure.materials[0].E'");
}

TEST(ModelValidation, DirectionalParameters) {
  auto m = valid_model();  // parameters rho_f, mu, kappa
  const auto add = [&m](const std::string& name,
                        const std::vector<std::pair<std::string, double>>& weights) {
    auto* p = m.add_parameters();
    p->set_name(name);
    for (const auto& [parameter, weight] : weights) {
      auto* w = p->add_direction();
      w->set_parameter(parameter);
      w->set_weight(weight);
    }
    return p;
  };
  add("along", {{"rho_f", 0.5}, {"kappa", -2e6}, {"mu", 0.0}});
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
  add("bad", {{"nu", 1.0}, {"along", 1.0}, {"mu", NAN}, {"rho_f", 1.0}, {"rho_f", 2.0}});
  add("both", {{"mu", 1.0}})->add_targets("fluid.mu");
  add("valued", {{"mu", 1.0}})->set_value(1.0);
  const auto errors = validate_model(m);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"parameters[4].direction[0].parameter", "no parameter 'nu' in the model"},
      {"parameters[4].direction[1].parameter", "'along' is directional"},
      {"parameters[4].direction[2].weight", "must be a finite number"},
      {"parameters[4].direction[4].parameter", "'rho_f' is listed twice"},
      {"parameters[5].targets", "a directional parameter has no targets"},
      {"parameters[6].value", "a directional parameter has no value of its own"}};
  ASSERT_EQ(errors.size(), expected.size()) << describe(errors);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(errors[i].path, expected[i].first);
    EXPECT_NE(errors[i].message.find(expected[i].second), std::string::npos) << errors[i].message;
  }
}

// What the FDM checks in the models it moves: the parameters' values alone, as validate_model
// says them when nothing else is wrong.
TEST(ModelValidation, ParameterValuesAloneAsTheWholeValidationSaysThem) {
  auto m = valid_model();  // parameters rho_f, mu, kappa
  m.mutable_parameters(0)->set_value(1010.0);
  m.mutable_parameters(1)->set_value(-1e-3);
  m.mutable_parameters(2)->set_value(NAN);
  EXPECT_TRUE(validate_parameter_values(valid_model()).empty());
  const auto errors = validate_model(m);
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_EQ(describe(validate_parameter_values(m)), describe(errors));
}

TEST(ModelValidation, TimeStepLongerThanTheAnalysis) {
  auto m = valid_model();
  m.mutable_analysis()->set_dt(1.0);
  m.mutable_analysis()->set_t_end(0.5);
  expect_single_error(validate_model(m), "analysis.dt", "must not exceed analysis.t_end");
}

TEST(ModelValidation, EveryErrorIsReportedInFieldOrder) {
  auto m = valid_model();
  m.mutable_fluid()->set_rho(-1.0);
  m.mutable_mesh()->set_h(0.0);
  const auto errors = validate_model(m);
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_EQ(errors[0].path, "fluid.rho");
  EXPECT_EQ(errors[1].path, "mesh.h");
}

TEST(ModelParsing, UnknownJsonFieldIsAnErrorNamingTheField) {
  const std::string json = edited_json("\"mu\": 0.001", "\"mu\": 0.001, \"viscosity\": 0.001");
  try {
    parse_model_json(json);
    FAIL() << "an unknown field was accepted";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].to_string(), "fluid.viscosity: unknown field of Fluid");
  }
}

// A number beyond a double made the JSON diagnosis throw nlohmann's out_of_range, which no
// caller expects (found by the model fuzzer: `pfem validate` would abort).
TEST(ModelParsing, ANumberBeyondADoubleIsAFieldError) {
  try {
    parse_model_json(R"({"name": "x", "fluid": {"rho": 1000.0, "kappa": 2.1e555}})");
    FAIL() << "parsed";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].path, "model");
    EXPECT_EQ(e.errors()[0].message, "invalid JSON: number overflow parsing '2.1e555'");
  }
}

TEST(ModelParsing, RunRejectsAnInvalidModelWithTheFieldPath) {
  auto m = valid_model();
  m.mutable_fluid()->set_rho(-1000.0);
  try {
    run(m, RunOptions{});
    FAIL() << "run() accepted a negative density";
  } catch (const ModelError& e) {
    ASSERT_FALSE(e.errors().empty());
    EXPECT_EQ(e.errors()[0].path, "fluid.rho");
  }
}

// --- the `pfem` command -------------------------------------------------------------------

struct Command {
  int exit_code = -1;
  std::vector<std::string> stderr_lines;
};

class PfemCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("pfem_model_io_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }

  Command pfem(const std::string& arguments) {
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd = "'" + std::string(PFEM_BINARY_DIR) + "/bin/pfem' " + arguments + " >'" +
                            (dir_ / "stdout.txt").string() + "' 2>'" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    Command c;
    c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::istringstream lines(read_text(err));
    for (std::string line; std::getline(lines, line);) c.stderr_lines.push_back(line);
    return c;
  }

  std::string bad_model_text() {
    // Two errors: a negative density and a zero particle spacing.
    std::string json = edited_json("\"rho\": 1000.0", "\"rho\": -1000.0");
    json.replace(json.find("\"h\": 0.01"), 9, "\"h\": 0");
    return json;
  }

  fs::path dir_;
};

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += "\n  | " + l;
  return s;
}

TEST_F(PfemCommand, ValidateAndRunExitWithTwoAndOneLinePerError) {
  ASSERT_TRUE(fs::exists(std::string(PFEM_BINARY_DIR) + "/bin/pfem")) << "build the pfem target first";
  const fs::path bad = write("bad.json", bad_model_text());
  const std::vector<std::string> expected{"fluid.rho: must be > 0", "mesh.h: must be > 0"};

  const Command v = pfem("validate '" + bad.string() + "'");
  EXPECT_EQ(v.exit_code, 2);
  EXPECT_EQ(v.stderr_lines, expected) << "stderr:" << joined(v.stderr_lines);

  const Command r = pfem("run '" + bad.string() + "' --out '" + (dir_ / "out").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_lines, expected) << "stderr:" << joined(r.stderr_lines);
}

TEST_F(PfemCommand, UnknownFieldIsOneLineAndExitTwo) {
  const fs::path bad = write("unknown.json", edited_json("\"mu\": 0.001", "\"mu\": 0.001, \"viscosity\": 0.001"));
  const Command v = pfem("validate '" + bad.string() + "'");
  EXPECT_EQ(v.exit_code, 2);
  ASSERT_EQ(v.stderr_lines.size(), 1u) << "stderr:" << joined(v.stderr_lines);
  EXPECT_EQ(v.stderr_lines[0], "fluid.viscosity: unknown field of Fluid");
}

// A file that is not JSON at all (truncated): still exit 2 and a single `path: message` line.
TEST_F(PfemCommand, MalformedJsonIsOneLineAndExitTwo) {
  const fs::path bad = write("truncated.json", "{\"fluid\": ");
  for (const std::string verb : {"validate", "run"}) {
    const std::string extra = verb == "run" ? " --out '" + (dir_ / "out").string() + "'" : "";
    const Command c = pfem(verb + " '" + bad.string() + "'" + extra);
    EXPECT_EQ(c.exit_code, 2) << verb;
    ASSERT_EQ(c.stderr_lines.size(), 1u) << "pfem " << verb << " stderr:" << joined(c.stderr_lines);
    EXPECT_EQ(c.stderr_lines[0].rfind("model: invalid JSON", 0), 0u) << c.stderr_lines[0];
  }
}

// Bad options and outputs are refused before any simulation, naming the flag or field.
TEST_F(PfemCommand, BadOptionsAndOutputsAreRefusedUpFront) {
  const std::string model = "'" + source("examples/hydrostatic.json") + "'";
  const std::string out = " --out '" + (dir_ / "out").string() + "'";
  for (const std::string threads : {"0", "-1", "100000"}) {
    const Command c = pfem("run " + model + out + " --threads " + threads);
    EXPECT_EQ(c.exit_code, 2) << threads;
    EXPECT_EQ(c.stderr_lines, std::vector<std::string>{"threads: must be in [1, 256]"}) << joined(c.stderr_lines);
  }
  Command c = pfem("run " + model + out + " --t-end 1e300");
  EXPECT_EQ(c.exit_code, 2);
  ASSERT_EQ(c.stderr_lines.size(), 1u) << joined(c.stderr_lines);
  EXPECT_EQ(c.stderr_lines[0].rfind("t_end: is ", 0), 0u) << c.stderr_lines[0];
  c = pfem("run " + model + out + " --params rho_f");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_EQ(c.stderr_lines.at(0), "pfem: --params needs --sensitivity ddm or fdm");
  const fs::path file = write("a_file", "");
  c = pfem("run " + model + " --out '" + file.string() + "'");
  EXPECT_EQ(c.exit_code, 2);
  ASSERT_EQ(c.stderr_lines.size(), 1u) << joined(c.stderr_lines);
  EXPECT_EQ(c.stderr_lines[0].rfind("pfem: --out: cannot create " + file.string(), 0), 0u) << c.stderr_lines[0];
  c = pfem("validate '" + dir_.string() + "'");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_EQ(c.stderr_lines, std::vector<std::string>{dir_.string() + ": is a directory, not a model file"});
}

// What only building the model finds is reported by validate too (exit 2, one line each).
TEST_F(PfemCommand, ValidateReportsWhatTheBuildFinds) {
  const fs::path bad = write("small_domain.json", edited_json("\"mesh\"", "\"domain\": {\"min\": {\"x\": 0.0, \"y\": 0.0}, \"max\": {\"x\": 0.15, \"y\": 0.15}}, \"mesh\""));
  const Command c = pfem("validate '" + bad.string() + "'");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_EQ(c.stderr_lines, (std::vector<std::string>{"domain: does not contain every wall and structure node",
                                                      "domain: does not contain every fluid particle"}))
      << joined(c.stderr_lines);
}

TEST_F(PfemCommand, ValidExampleValidates) {
  const Command v = pfem("validate '" + source("examples/hydrostatic.json") + "'");
  EXPECT_EQ(v.exit_code, 0) << "stderr:" << joined(v.stderr_lines);
  EXPECT_TRUE(v.stderr_lines.empty()) << joined(v.stderr_lines);
}

}  // namespace
}  // namespace pfem
