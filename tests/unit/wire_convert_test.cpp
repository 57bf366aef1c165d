// The wire conversions (wire/convert.h) carry every field of a run's summary: a summary with a
// distinct value in each field, sent through pfem.v1.Summary and its serialised bytes, comes back
// with the same summary.json text (engine/io/results_io.h writes every field).
#include <gtest/gtest.h>

#include "engine/io/results_io.h"
#include "wire/convert.h"

namespace pfem {
namespace {

RunSummary every_field_set() {
  RunSummary s;
  s.status = RunStatus::kFailed;
  s.message = "step 7: Newton did not converge";
  s.failed_step = 7;
  s.failed_time = 0.0071;
  s.steps = 6;
  s.t_end = 1.25;
  s.dt = 0.001;
  s.wall_seconds = 3.5;
  s.response_seconds = 2.5;
  s.sensitivity_seconds = 0.75;
  s.remesh_seconds = 0.125;
  s.assemble_seconds = 0.375;
  s.factorize_seconds = 1.0625;
  s.solve_seconds = 0.1875;
  s.newton_iterations = 41;
  s.factorizations = 13;
  s.substeps = 2;
  s.deformation_substeps = 7;
  s.removed_particles = 5;
  s.inserted_particles = 9;
  s.left_domain = 3;
  s.fluid_area_max_drift = 0.0123;
  s.warnings = {"3 particle(s) left the domain and were removed", "second warning"};
  s.particles = 406;
  s.max_elements = 731;
  s.fluid_area_initial = 0.042632;
  s.fluid_area_final = 0.041;
  s.fluid_area_left = 0.0011;
  s.sensitivity_method = "ddm";
  s.parameters = {"rho_f", "mu"};
  s.parameter_values = {1000.0, 0.001};
  return s;
}

TEST(WireConvert, ASummaryCrossesTheWireWithEveryField) {
  const RunSummary sent = every_field_set();
  pfem::v1::Summary parsed;
  ASSERT_TRUE(parsed.ParseFromString(wire::to_proto(sent).SerializeAsString()));
  const RunSummary received = wire::from_proto(parsed);
  EXPECT_EQ(summary_json(received), summary_json(sent));
  EXPECT_EQ(received.fluid_area_left, 0.0011);
}

TEST(WireConvert, EachStatusSurvivesTheWire) {
  for (RunStatus status : {RunStatus::kCompleted, RunStatus::kFailed, RunStatus::kCancelled}) {
    RunSummary s;
    s.status = status;
    EXPECT_EQ(wire::from_proto(wire::to_proto(s)).status, status);
  }
}

}  // namespace
}  // namespace pfem
