// Free surfaces that meet (issue "Water that behaves like water"): a block of water dropped
// 0.1 m into a pool at mu = 1e-3 hits it at 1.4 m/s and splashes. The alpha test alone closed
// every gap between the two surfaces as soon as it was narrower than about alpha h, and the air
// in it became water (+8 % of the area by 0.8 s); gaps now close only where their particles move
// as water does, or meet within the step (mesh::RemeshOptions::previous_triangles); 2.8 % was
// left, 1.1 % with the volume correction.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

TEST(GapClosing, ABlockDroppedIntoAPoolKeepsItsArea) {
  const auto model = parse_model_json(R"({
    "name": "drop", "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9}, "mesh": {"h": 0.005},
    "domain": {"min": {"x": -0.1, "y": -0.1}, "max": {"x": 0.5, "y": 1.0}},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.4, "y": 0.08}}},
                      {"rectangle": {"min": {"x": 0.15, "y": 0.18}, "max": {"x": 0.25, "y": 0.26}}}],
    "walls": [{"points": [{"x": 0.0, "y": 0.5}, {"x": 0.0, "y": 0.0}, {"x": 0.4, "y": 0.0}, {"x": 0.4, "y": 0.5}]}],
    "analysis": {"dt": 0.001, "t_end": 0.8, "record_every": 10},
    "recorders": [{"name": "fluid_area", "quantity": "fluid_area"}]
  })");
  const RunResult r = run(model, RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  std::printf("fluid area drift at most %.2f %%, at the end %+.2f %%\n", 100 * r.summary.fluid_area_max_drift,
              100 * (r.summary.fluid_area_final / r.summary.fluid_area_initial - 1.0));
  EXPECT_LT(r.summary.fluid_area_max_drift, 0.03);
}

// The dam break as shipped (examples/dam-break.json) to 1 s: the front along the floor, the
// run-up on the far wall, the jet plunging back onto the pool. The remeshing alone drifts the area
// by up to 4.9 % (+2.3 % at 0.3 s, -4.7 % at 0.8 s, +4.5 % at 1 s); with the volume correction
// (mesh.volume_relaxation_steps) the issue asks for 2 % over the whole run (measured 0.9 %).
TEST(GapClosing, TheDamBreakKeepsItsAreaWithinTwoPercentToOneSecond) {
  auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/dam-break.json");
  RunOptions options;
  options.t_end = 1.0;
  const RunResult r = run(model, options);
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  std::printf("fluid area drift at most %.2f %%, at the end %+.2f %%\n", 100 * r.summary.fluid_area_max_drift,
              100 * (r.summary.fluid_area_final / r.summary.fluid_area_initial - 1.0));
  EXPECT_LT(r.summary.fluid_area_max_drift, 0.02);
}

}  // namespace
}  // namespace pfem
