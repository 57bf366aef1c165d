// What a central difference that is not the slope looks like, and that the run says so
// (engine/analysis/run.cpp, one_sided_spreads): where the two one-sided differences
// r+ - r0 and r0 - r- differ by more than kFdmNoise of r+ - r-. And what check-gradients leaves
// out of its verdict for it (engine/analysis/gradient_check.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "engine/analysis/gradient_check.h"
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

// Largest |a - b| over time relative to the largest |b| in column name (NaN, failing any
// comparison, where there is none).
double relative_difference(const Histories& a, const Histories& b, const std::string& name) {
  const int j = a.column(name);
  EXPECT_GE(j, 0) << name;
  if (j < 0) return std::numeric_limits<double>::quiet_NaN();
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
  const int tip = parted.sensitivities.column("dtip_ux/drho_f");
  ASSERT_GE(tip, 0);
  ASSERT_EQ(parted.fdm_spread.size(), parted.sensitivities.columns.size());
  EXPECT_GT(parted.fdm_spread[tip], kFdmParted);
  options.fdm_eps = 1e-8;
  const RunResult alike = run(model, options);
  ASSERT_EQ(alike.summary.status, RunStatus::kCompleted) << alike.summary.message;
  EXPECT_TRUE(alike.summary.warnings.empty());
  for (const double spread : alike.fdm_spread) EXPECT_LE(spread, kFdmNoise);
  options.sensitivity = SensitivityMethod::kDdm;
  const RunResult ddm = run(model, options);
  ASSERT_EQ(ddm.summary.status, RunStatus::kCompleted) << ddm.summary.message;
  EXPECT_LT(relative_difference(alike.sensitivities, ddm.sensitivities, "dtip_ux/drho_f"), 1e-5);
  EXPECT_GT(relative_difference(parted.sensitivities, ddm.sensitivities, "dtip_ux/drho_f"), 1e-2);
}

// The yielding obstacle to 0.1 s, before the water reaches it: its sway and base pressure stay
// 0 in every run (their FDM too), and its base moment is round-off (2e-19 N m against a fiber
// stress of 3 kPa: its perturbed runs differ by noise). check-gradients marks those columns and
// compares the rest, which agree.
TEST(FdmNoise, CheckGradientsLeavesOutColumnsWithoutASlope) {
  const auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/dam-break-obstacle.json");
  RunOptions options;
  options.t_end = 0.1;
  options.params = {"E", "rho_f"};
  const GradientCheck c = check_gradients(model, options, false);
  ASSERT_EQ(c.rows.size(), 12u);
  const auto row = [&](const std::string& recorder, const std::string& parameter) {
    const auto it = std::find_if(c.rows.begin(), c.rows.end(),
                                 [&](const auto& r) { return r.recorder == recorder && r.parameter == parameter; });
    EXPECT_NE(it, c.rows.end()) << recorder << "/" << parameter;
    return it == c.rows.end() ? GradientCheckRow{} : *it;
  };
  for (const auto& r : c.rows)
    std::printf("%-18s %-6s max |FDM| %.4e  DDM %.2e%s%s%s\n", r.recorder.c_str(), r.parameter.c_str(), r.max_fdm,
                r.ddm, r.negligible ? " negligible" : "", r.not_a_slope ? " not a slope" : "",
                r.unmoved ? " unmoved" : "");
  for (const char* p : {"E", "rho_f"}) {
    EXPECT_TRUE(row("tip_ux", p).unmoved) << p;
    EXPECT_TRUE(row("base_p", p).unmoved) << p;
  }
  EXPECT_TRUE(row("base_moment", "E").not_a_slope);
  EXPECT_FALSE(row("base_moment", "E").negligible);
  int compared = 0;
  for (const auto& r : c.rows) {
    if (!r.compared()) continue;
    ++compared;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LT(r.ddm, 1e-4) << r.recorder << "/" << r.parameter;
  }
  EXPECT_EQ(compared, 3);  // the fiber stress w.r.t. E, the front and the area w.r.t. rho_f
}

}  // namespace
}  // namespace pfem
