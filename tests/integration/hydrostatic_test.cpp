// Still water (examples/hydrostatic.json): 0.2 m of water at rest in a closed box must stay at
// rest, keep its area, and carry the hydrostatic pressure rho*g*h at the bottom.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

TEST(Hydrostatic, StillWaterStaysStillWithRhoGHAtTheBottom) {
  const auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
  RunOptions options;
  options.t_end = 0.5;
  const RunResult r = run(model, options);
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;

  const auto& h = r.responses;
  const int bottom_p = h.column("bottom_p"), area = h.column("fluid_area"), speed = h.column("max_speed");
  ASSERT_GE(bottom_p, 0);
  ASSERT_GE(area, 0);
  ASSERT_GE(speed, 0);
  ASSERT_GE(h.time.size(), 2u);
  ASSERT_NEAR(h.time.back(), 0.5, 1e-9);

  // rho g h with h = 0.2 m (the water region is 0.2 m deep), rho and |g| from the model.
  const double g = model.has_gravity() ? std::hypot(model.gravity().x(), model.gravity().y()) : 9.81;
  const double depth = model.fluid_regions(0).rectangle().max().y() - model.fluid_regions(0).rectangle().min().y();
  ASSERT_NEAR(depth, 0.2, 1e-12);
  const double rho_g_h = model.fluid().rho() * g * depth;

  const double area0 = h.rows.front()[area];
  ASSERT_GT(area0, 0.0);
  double worst_p = 0.0, worst_area = 0.0;
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    if (h.time[i] >= 0.05) worst_p = std::max(worst_p, std::abs(h.rows[i][bottom_p] / rho_g_h - 1.0));
    worst_area = std::max(worst_area, std::abs(h.rows[i][area] / area0 - 1.0));
  }
  const auto& last = h.rows.back();
  std::printf("rho g h = %.2f Pa, bottom_p(0.5 s) = %.2f Pa, largest deviation after 0.05 s %.4f %%\n",
              rho_g_h, last[bottom_p], 100 * worst_p);
  std::printf("max_speed(0.5 s) = %.3e m/s, largest fluid_area change %.4f %%\n", last[speed], 100 * worst_area);

  EXPECT_NEAR(last[bottom_p], rho_g_h, 0.02 * rho_g_h);
  EXPECT_LT(worst_p, 0.02) << "bottom pressure left the 2 % band after it settled";
  EXPECT_LT(last[speed], 1e-3);
  EXPECT_LT(worst_area, 0.01);
}

// A step dt that does not divide t_end: the last step is shortened so that the run ends at
// t_end (not one dt past it), and the water is still at rest with its pressure.
TEST(Hydrostatic, TheLastStepEndsAtTEnd) {
  const auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
  RunOptions options;
  options.t_end = 0.05;
  options.dt = 0.02;
  const RunResult r = run(model, options);
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  EXPECT_EQ(r.summary.steps, 3);
  ASSERT_EQ(r.responses.time.size(), 4u);
  EXPECT_DOUBLE_EQ(r.responses.time[2], 0.04);
  EXPECT_DOUBLE_EQ(r.responses.time[3], 0.05);
  const int bottom_p = r.responses.column("bottom_p");
  ASSERT_GE(bottom_p, 0);
  EXPECT_NEAR(r.responses.rows.back()[bottom_p], model.fluid().rho() * 9.81 * 0.2, 2.0);
}

// Central differences of the bottom pressure with respect to rho: g h. With a Newton tolerance
// not far below the FDM step (each run's Newton error is divided by the step) the run says so.
TEST(Hydrostatic, FdmOfTheBottomPressureIsGHAndALooseNewtonToleranceIsWarnedOf) {
  auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/hydrostatic.json");
  RunOptions options;
  options.t_end = 0.02;
  options.sensitivity = SensitivityMethod::kFdm;
  options.params = {"rho_f"};
  const auto fdm_tolerance_warnings = [](const RunResult& r) {
    return std::count_if(r.summary.warnings.begin(), r.summary.warnings.end(),
                         [](const std::string& w) { return w.rfind("analysis.newton_tolerance: ", 0) == 0; });
  };
  const RunResult tight = run(model, options);
  ASSERT_EQ(tight.summary.status, RunStatus::kCompleted) << tight.summary.message;
  const int dp = tight.sensitivities.column("dbottom_p/drho_f");
  ASSERT_GE(dp, 0);
  EXPECT_NEAR(tight.sensitivities.rows.back()[dp], 9.81 * 0.2, 0.02 * 9.81 * 0.2);
  EXPECT_EQ(fdm_tolerance_warnings(tight), 0);

  model.mutable_analysis()->set_newton_tolerance(1e-7);  // the FDM step is 1e-7
  const RunResult loose = run(model, options);
  ASSERT_EQ(loose.summary.status, RunStatus::kCompleted) << loose.summary.message;
  ASSERT_EQ(fdm_tolerance_warnings(loose), 1);
  for (const auto& w : loose.summary.warnings) std::printf("%s\n", w.c_str());
  options.fdm_eps = 1e-5;  // a larger step leaves room for that tolerance
  EXPECT_EQ(fdm_tolerance_warnings(run(model, options)), 0);
}

}  // namespace
}  // namespace pfem
