// What a central difference that is not the slope looks like, and that the run says so
// (engine/analysis/run.cpp, warn_noisy_differences): where the two one-sided differences
// r+ - r0 and r0 - r- differ by more than kFdmNoise of r+ - r-.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

// The warnings that name column `name` and contain `why`.
long warnings_of(const RunResult& r, const std::string& name, const std::string& why) {
  return std::count_if(r.summary.warnings.begin(), r.summary.warnings.end(), [&](const std::string& w) {
    return w.rfind(name + ": ", 0) == 0 && w.find(why) != std::string::npos;
  });
}

// Largest |a - b| over time relative to the largest |b| in column name.
double relative_difference(const Histories& a, const Histories& b, const std::string& name) {
  const int j = a.column(name);
  EXPECT_GE(j, 0) << name;
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    diff = std::max(diff, std::abs(a.rows[i][j] - b.rows[i][j]));
    scale = std::max(scale, std::abs(b.rows[i][j]));
  }
  return diff / scale;
}

// A water column collapsing for 0.05 s (h = 1 cm; the README's tutorial): its wall pressure
// moves with mu = 1e-3 by only 4e-11 of itself at a relative step of 1e-8, as little as the
// runs' Newton errors, and that column is then 5e-3 off the DDM; at 1e-6 it is within 1e-4
// and no warning is given.
TEST(FdmNoise, ANewtonErrorSizedDifferenceIsWarnedOf) {
  const auto model = parse_model_json(R"({
    "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": 0.01},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.1, "y": 0.1}}}],
    "walls": [{"closed": true, "points": [{"x": 0.0, "y": 0.0}, {"x": 0.3, "y": 0.0}, {"x": 0.3, "y": 0.2},
                                          {"x": 0.0, "y": 0.2}]}],
    "analysis": {"dt": 0.001, "t_end": 0.05},
    "recorders": [{"name": "wall_p", "quantity": "p", "point": {"x": 0.0, "y": 0.01}},
                  {"name": "front_x", "quantity": "front_x"}],
    "parameters": [{"name": "rho_f", "targets": ["fluid.rho"]}, {"name": "mu", "targets": ["fluid.mu"]}]})");
  RunOptions options;
  options.sensitivity = SensitivityMethod::kDdm;
  const RunResult ddm = run(model, options);
  ASSERT_EQ(ddm.summary.status, RunStatus::kCompleted) << ddm.summary.message;
  options.sensitivity = SensitivityMethod::kFdm;
  options.fdm_eps = 1e-8;
  const RunResult small = run(model, options);
  ASSERT_EQ(small.summary.status, RunStatus::kCompleted) << small.summary.message;
  for (const auto& w : small.summary.warnings) std::printf("eps 1e-8: %s\n", w.c_str());
  EXPECT_GT(relative_difference(small.sensitivities, ddm.sensitivities, "dwall_p/dmu"), 1e-3);
  EXPECT_EQ(warnings_of(small, "dwall_p/dmu", "Newton errors"), 1);
  EXPECT_EQ(small.summary.warnings.size(), 1u);  // the other columns are the slope
  options.fdm_eps = 1e-6;
  const RunResult larger = run(model, options);
  ASSERT_EQ(larger.summary.status, RunStatus::kCompleted) << larger.summary.message;
  EXPECT_LT(relative_difference(larger.sensitivities, ddm.sensitivities, "dwall_p/dmu"), 1e-4);
  EXPECT_TRUE(larger.summary.warnings.empty());
}

// The sloshing beam to 0.5 s: at the default step 1e-7 the runs perturbed in rho_f take a
// remeshing decision differently and part (the FDM jumps: the one-sided differences are of
// opposite sizes); at 1e-8 they stay alike and the FDM is the DDM's to 1e-5.
TEST(FdmNoise, PerturbedRunsThatPartAreWarnedOf) {
  const auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/sloshing-beam.json");
  RunOptions options;
  options.t_end = 0.5;
  options.params = {"rho_f"};
  options.sensitivity = SensitivityMethod::kFdm;
  const RunResult parted = run(model, options);
  ASSERT_EQ(parted.summary.status, RunStatus::kCompleted) << parted.summary.message;
  for (const auto& w : parted.summary.warnings) std::printf("eps 1e-7: %s\n", w.c_str());
  EXPECT_EQ(warnings_of(parted, "dtip_ux/drho_f", "the perturbed runs parted"), 1);
  options.fdm_eps = 1e-8;
  const RunResult alike = run(model, options);
  ASSERT_EQ(alike.summary.status, RunStatus::kCompleted) << alike.summary.message;
  EXPECT_TRUE(alike.summary.warnings.empty());
  options.sensitivity = SensitivityMethod::kDdm;
  const RunResult ddm = run(model, options);
  ASSERT_EQ(ddm.summary.status, RunStatus::kCompleted) << ddm.summary.message;
  EXPECT_LT(relative_difference(alike.sensitivities, ddm.sensitivities, "dtip_ux/drho_f"), 1e-5);
  EXPECT_GT(relative_difference(parted.sensitivities, ddm.sensitivities, "dtip_ux/drho_f"), 1e-2);
}

}  // namespace
}  // namespace pfem
