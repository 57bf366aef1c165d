// A run validates and builds its model once (engine/analysis/run.h): run() given a prepared
// problem simulates that problem and builds nothing, and a prepare_run of a model said to be
// validated does not validate it again. A second build or validation brought back into either
// path fails these tests.
#include <gtest/gtest.h>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

// Still water in a small closed box: 5 x 4 particles, 5 steps of 2 ms.
const char* kBox = R"({
  "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
  "mesh": {"h": 0.01},
  "fluid_regions": [{"name": "water", "rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.04}}}],
  "walls": [{"name": "box", "points": [{"x": 0.0, "y": 0.0}, {"x": 0.05, "y": 0.0}, {"x": 0.05, "y": 0.08},
                                       {"x": 0.0, "y": 0.08}], "closed": true}],
  "analysis": {"dt": 0.002, "t_end": 0.01},
  "recorders": [{"name": "bottom_p", "quantity": "p", "point": {"x": 0.025, "y": 0.0}}],
  "parameters": [{"name": "rho_f", "targets": ["fluid.rho"]}]
})";

TEST(PreparedRun, RunSimulatesThePreparedProblemAndBuildsNothing) {
  const pfem::v1::Model model = parse_model_json(kBox);
  pfem::v1::Model denser = model;
  denser.mutable_parameters(0)->set_value(1100.0);
  RunOptions options;
  options.sensitivity = SensitivityMethod::kDdm;
  const RunResult own = run(model, options);
  const RunResult built = run(denser, options);
  ASSERT_NE(built.responses.rows.back(), own.responses.rows.back());  // the two models differ

  options.prepared = prepare_run(model, options);
  const RunResult given = run(denser, options);  // the prepared problem is the model's, not denser's
  EXPECT_EQ(given.summary.parameter_values, std::vector<double>{1000.0});
  EXPECT_EQ(given.responses.rows, own.responses.rows);
  EXPECT_EQ(given.sensitivities.rows, own.sensitivities.rows);
}

TEST(PreparedRun, AValidatedModelIsNotValidatedAgain) {
  pfem::v1::Model model = parse_model_json(kBox);
  model.mutable_analysis()->set_newton_tolerance(-1.0);  // only validation looks at it
  ASSERT_FALSE(validate_model(model).empty());
  EXPECT_THROW(prepare_run(model, {}), ModelError);
  EXPECT_NE(prepare_run(model, {}, /*validated=*/true), nullptr);
}

}  // namespace
}  // namespace pfem
