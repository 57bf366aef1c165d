// What `pfem validate` tells a user beyond the field rules (engine/io/model_io.cpp,
// engine/io/model_warnings.cpp, engine/analysis/run_estimate.cpp): the line and column of a JSON
// syntax error, "did you mean" for a misspelt field and the right place for a field in the wrong
// message, every unknown field at once; warnings for implausible values; the run's estimated
// size and time.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/analysis/run_estimate.h"
#include "engine/io/model_io.h"
#include "engine/io/model_size.h"
#include "engine/io/model_warnings.h"

namespace pfem {
namespace {

std::string source(const std::string& relative) { return std::string(PFEM_SOURCE_DIR) + "/" + relative; }

std::vector<std::string> parse_errors(const std::string& json) {
  try {
    parse_model_json(json);
  } catch (const ModelError& e) {
    std::vector<std::string> out;
    for (const auto& err : e.errors()) out.push_back(err.to_string());
    return out;
  }
  return {};
}

std::vector<std::string> warnings(const pfem::v1::Model& m) {
  std::vector<std::string> out;
  for (const auto& w : model_warnings(m)) out.push_back(w.to_string());
  return out;
}

// A valid model: a 0.1 x 0.1 m water column in a tank, h = 1 cm, dt = 1 ms.
pfem::v1::Model column() {
  return parse_model_json(R"({
    "fluid": {"rho": 1000, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.01},
    "fluid_regions": [{"name": "w", "rectangle": {"min": {"x": 0, "y": 0}, "max": {"x": 0.1, "y": 0.1}}}],
    "walls": [{"name": "tank", "points": [{"x": 0, "y": 0.3}, {"x": 0, "y": 0}, {"x": 0.3, "y": 0}, {"x": 0.3, "y": 0.3}]}],
    "analysis": {"dt": 0.001, "t_end": 0.1},
    "recorders": [{"name": "wall_p", "quantity": "p", "point": {"x": 0.0, "y": 0.01}}]})");
}

// The column is that of the end of the offending token ("mu" ends at column 28).
TEST(ModelMessages, JsonSyntaxErrorHasLineAndColumn) {
  EXPECT_EQ(parse_errors("{\n  \"fluid\": {\"rho\": 1000 \"mu\": 0.001}\n}"),
            std::vector<std::string>{"model: invalid JSON at line 2, column 28: syntax error while parsing object - "
                                     "unexpected string literal; expected '}'"});
  EXPECT_EQ(parse_errors("{\"fluid\": "),
            std::vector<std::string>{"model: invalid JSON at line 1, column 11: syntax error while parsing value - "
                                     "unexpected end of input; expected '[', '{', or a literal"});
}

TEST(ModelMessages, MisspeltFieldGetsASuggestion) {
  EXPECT_EQ(parse_errors(R"({"fluid": {"rhoo": 1000}})"),
            std::vector<std::string>{"fluid.rhoo: unknown field of Fluid; did you mean 'rho'?"});
  EXPECT_EQ(parse_errors(R"({"analysis": {"tend": 1}})"),
            std::vector<std::string>{"analysis.tend: unknown field of Analysis; did you mean 't_end'?"});
}

TEST(ModelMessages, FieldInTheWrongMessageSaysWhereItBelongs) {
  EXPECT_EQ(parse_errors(R"({"self_weight": false})"),
            std::vector<std::string>{"self_weight: unknown field of Model; it belongs in structure.self_weight"});
  EXPECT_EQ(parse_errors(R"({"fluid": {"dt": 0.001}})"),
            std::vector<std::string>{"fluid.dt: unknown field of Fluid; it belongs in analysis.dt"});
  EXPECT_EQ(parse_errors(R"({"structure": {"materials": [{"name": "m", "fy": 1}]}})"),
            std::vector<std::string>{"structure.materials[0].fy: unknown field of Material; it belongs in "
                                     "structure.materials[].bilinear.fy"});
}

TEST(ModelMessages, EveryUnknownFieldAtOnce) {
  EXPECT_EQ(parse_errors(R"({"fluid": {"rhoo": 1}, "mesh": {"hh": 0.01}, "walls": [{}, {"closd": true}]})"),
            (std::vector<std::string>{"fluid.rhoo: unknown field of Fluid; did you mean 'rho'?",
                                      "mesh.hh: unknown field of Mesh; did you mean 'h'?",
                                      "walls[1].closd: unknown field of Wall; did you mean 'closed'?"}));
}

// A value of the wrong kind is named by its path with what the field takes (protobuf's own
// message was "(fluid.rho): invalid value "heavy" for type TYPE_DOUBLE" or "Proto field is not
// repeating, cannot start list"), every one at once, inside lists too.
TEST(ModelMessages, AValueOfTheWrongKindSaysWhatTheFieldTakes) {
  EXPECT_EQ(parse_errors(R"({"fluid": [1000, 0.001]})"),
            std::vector<std::string>{"fluid: expected an object (Fluid), found a list"});
  EXPECT_EQ(parse_errors(R"({"walls": "box"})"),
            std::vector<std::string>{"walls: expected a list, found the string \"box\""});
  EXPECT_EQ(parse_errors(R"({"fluid": {"rho": "heavy", "mu": [1]}, "mesh": {"h": {"v": 1}},
      "walls": [{"name": "w", "points": [{"x": 0, "y": "0"}, {"x": "a", "y": 1}], "closed": 1}],
      "analysis": {"newton_max_iterations": 2.5}, "recorders": [{"name": 7, "point": 5}]})"),
            (std::vector<std::string>{"fluid.rho: expected a number, found the string \"heavy\"",
                                      "fluid.mu: expected a number, found a list",
                                      "mesh.h: expected a number, found an object",
                                      "walls[0].points[1].x: expected a number, found the string \"a\"",
                                      "walls[0].closed: expected true or false, found the number 1",
                                      "analysis.newton_max_iterations: expected a whole number, found the number 2.5",
                                      "recorders[0].name: expected a string, found the number 7",
                                      "recorders[0].point: expected an object (Vec2), found the number 5"}));
  // What proto3 JSON accepts stays accepted: numbers as strings, null for a default.
  EXPECT_TRUE(parse_errors(R"({"mesh": {"h": "0.01", "alpha": null}, "analysis": {"record_every": "2"}})").empty());
}

TEST(ModelMessages, ExamplesAndAPlainColumnHaveNoWarnings) {
  EXPECT_EQ(warnings(column()), std::vector<std::string>{});
  for (const char* name : {"hydrostatic", "dam-break", "sloshing-beam", "dam-break-obstacle", "dam-break-elastic-obstacle"})
    EXPECT_EQ(warnings(read_model_file(source("examples/") + name + ".json")), std::vector<std::string>{}) << name;
}

TEST(ModelMessages, ImplausibleDensityAndSpeedOfSound) {
  auto m = column();
  m.mutable_fluid()->set_rho(1.0);
  m.mutable_fluid()->set_kappa(2.15);
  EXPECT_EQ(warnings(m),
            (std::vector<std::string>{
                "fluid.rho: 1 kg/m^3 is outside the plausible [100, 30000] kg/m^3 (water: 1000)",
                "fluid.kappa: the speed of sound sqrt(kappa/rho) = 1.47 m/s is below 10 x the expected flow speed "
                "sqrt(2 g H) = 1.4 m/s (H = 0.1 m of water): the fluid is far from incompressible (water: kappa = "
                "2.15e9 Pa)"}));
  m.mutable_fluid()->set_rho(40000.0);
  m.mutable_fluid()->set_kappa(2.15e9);
  EXPECT_EQ(warnings(m), std::vector<std::string>{
                             "fluid.rho: 4e+04 kg/m^3 is outside the plausible [100, 30000] kg/m^3 (water: 1000)"});
}

TEST(ModelMessages, TimeStepAboveTheFlowBound) {
  auto m = column();
  m.mutable_analysis()->set_dt(0.5);
  m.mutable_analysis()->set_t_end(1.0);
  // h / sqrt(2 g H) = 0.01 / sqrt(2 * 9.81 * 0.1) = 0.00714 s
  EXPECT_EQ(warnings(m), std::vector<std::string>{
                             "analysis.dt: 0.5 s is above h / sqrt(2 g H) = 0.00714 s: a particle at the expected flow "
                             "speed crosses more than one spacing per step (remeshing and contact need dt <= that "
                             "bound)"});
}

TEST(ModelMessages, SoftBeamHoldingWater) {
  auto m = read_model_file(source("examples/sloshing-beam.json"));
  // E = 10 Pa instead of 1 MPa: q0 L^4 / (30 E I), q0 = rho g min(H, L) t
  m.mutable_structure()->mutable_materials(0)->mutable_elastic()->set_e(10.0);
  const auto w = warnings(m);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].rfind("structure.beams[0]: as a cantilever under the hydrostatic load of 0.08 m of water it would "
                       "deflect ", 0), 0u) << w[0];
  EXPECT_NE(w[0].find("more than its length 0.1 m"), std::string::npos) << w[0];
}

TEST(ModelMessages, RecorderPointFarFromWaterAndStructure) {
  auto m = column();
  m.mutable_recorders(0)->mutable_point()->set_y(0.14);  // 4 cm above the water
  EXPECT_EQ(warnings(m), std::vector<std::string>{
                             "recorders[0].point: is 0.04 m from the water at t = 0 and from the structure (more than "
                             "h = 0.01 m): it is bound to the nearest node, which may be a wall node or a particle "
                             "far away"});
  m.mutable_recorders(0)->mutable_point()->set_y(0.105);  // within h of the surface
  EXPECT_EQ(warnings(m), std::vector<std::string>{});
}

TEST(ModelMessages, EstimateOfSizeAndTime) {
  const RunEstimate e = estimate_run(column());
  EXPECT_EQ(e.particles, 100);
  EXPECT_EQ(e.elements, 200);
  EXPECT_EQ(e.steps, 100);
  EXPECT_GT(e.seconds_per_particle_step, 0.0);
  EXPECT_DOUBLE_EQ(e.seconds, e.seconds_per_particle_step * 100 * 100);
}

}  // namespace
}  // namespace pfem
