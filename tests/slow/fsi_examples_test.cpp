// The paper's two examples (theory §7) and the elastic-obstacle benchmark, run in full to
// t = 1.0 s as shipped: each completes, the water reaches and moves the beam, and the dam break
// hits the obstacle near 0.15 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

RunResult run_example(const std::string& name) {
  return run(read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + name), RunOptions{});
}

// Time at which |tip_ux| first exceeds threshold, or -1.
double first_time_above(const RunResult& r, double threshold) {
  for (std::size_t i = 0; i < r.responses.time.size(); ++i)
    if (std::abs(r.responses.rows[i][0]) > threshold) return r.responses.time[i];
  return -1.0;
}

TEST(FsiExamples, SloshingBeamRunsToOneSecond) {
  const RunResult r = run_example("sloshing-beam.json");
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  EXPECT_NEAR(r.responses.time.back(), 1.0, 1e-9);
  const double hit = first_time_above(r, 1e-4);
  std::printf("water reaches the beam at %.3f s\n", hit);
  EXPECT_GT(hit, 0.05);  // the column has to cross the tank first
  EXPECT_LT(hit, 0.3);
}

TEST(FsiExamples, DamBreakObstacleRunsToOneSecondWithImpactNearPointFifteen) {
  const RunResult r = run_example("dam-break-obstacle.json");
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  EXPECT_NEAR(r.responses.time.back(), 1.0, 1e-9);
  const double impact = first_time_above(r, 1e-3);
  std::printf("impact at %.3f s, final tip deflection %.1f mm\n", impact, 1e3 * r.responses.rows.back()[0]);
  EXPECT_NEAR(impact, 0.15, 0.02);
}

// Water at mu = 1e-3 splashes over the obstacle: the hardest run for the remeshing. The elastic
// benchmark's first peak stays inside the published band (41-49 mm at 0.23-0.255 s; 44.8 mm at
// 0.239 s) and the fluid area within 3 % over the whole second, as the issue asks (1.3 % with the
// volume correction; 6.4 % without, which the remeshing alone leaves).
// Before gaps between surfaces closed only where their particles move as water does
// (mesh::RemeshOptions::previous_triangles), the splash falling back on the pool made water of
// the air it enclosed: +35 % by 1 s.
TEST(FsiExamples, DamBreakElasticObstacleRunsToOneSecond) {
  const RunResult r = run_example("dam-break-elastic-obstacle.json");
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  EXPECT_NEAR(r.responses.time.back(), 1.0, 1e-9);
  const int tip = 0, area = 3;  // time, tip_ux, base_p, front_x, fluid_area
  ASSERT_EQ(r.responses.columns[area], "fluid_area");
  double low = 1.0, high = 1.0, peak = 0.0, peak_time = 0.0, drift_to_06 = 0.0;
  for (std::size_t i = 0; i < r.responses.rows.size(); ++i) {
    const auto& row = r.responses.rows[i];
    const double t = r.responses.time[i], ratio = row[area] / r.summary.fluid_area_initial;
    low = std::min(low, ratio), high = std::max(high, ratio);
    if (t <= 0.6) drift_to_06 = std::max(drift_to_06, std::abs(ratio - 1.0));
    if (t <= 0.3 && row[tip] > peak) peak = row[tip], peak_time = t;
  }
  std::printf("first peak %.1f mm at %.3f s; fluid area within %.1f %% to 0.6 s, between %+.1f %% and %+.1f %% to 1 s\n",
              1e3 * peak, peak_time, 100 * drift_to_06, 100 * (low - 1), 100 * (high - 1));
  EXPECT_GT(peak, 0.041);
  EXPECT_LT(peak, 0.049);
  EXPECT_GT(peak_time, 0.23);
  EXPECT_LT(peak_time, 0.255);
  EXPECT_LT(drift_to_06, 0.03);
  EXPECT_LT(r.summary.fluid_area_max_drift, 0.03);
}

}  // namespace
}  // namespace pfem
