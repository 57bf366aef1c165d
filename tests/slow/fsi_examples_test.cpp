// The paper's two examples (theory §7), run in full to t = 1.0 s as shipped: each completes,
// the water reaches and moves the beam, and the dam break hits the obstacle near 0.15 s.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace pfem
