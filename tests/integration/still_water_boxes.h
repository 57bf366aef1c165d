#pragma once
// Still water in a closed box (see still_water_boxes_test.cpp): the model and the checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {

struct StillBox {
  double width, height, depth, h, t_end;
};

inline std::string box_model(const StillBox& b) {
  char json[2048];
  std::snprintf(json, sizeof json, R"({
    "name": "still-water-box",
    "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
    "mesh": {"h": %.17g},
    "fluid_regions": [{"rectangle": {"min": {"x": 0, "y": 0}, "max": {"x": %.17g, "y": %.17g}}}],
    "walls": [{"points": [{"x": 0, "y": 0}, {"x": %.17g, "y": 0}, {"x": %.17g, "y": %.17g}, {"x": 0, "y": %.17g}],
               "closed": true}],
    "analysis": {"dt": 0.002, "t_end": %.17g, "record_every": 25},
    "recorders": [{"name": "fluid_area", "quantity": "fluid_area"},
                  {"name": "max_speed", "quantity": "max_speed"},
                  {"name": "bottom_p", "quantity": "p", "point": {"x": %.17g, "y": 0}}]
  })", b.h, b.width, b.depth, b.width, b.width, b.height, b.height, b.t_end, b.width / 2);
  return json;
}

inline void expect_still(const StillBox& b) {
  const RunResult r = run(parse_model_json(box_model(b)), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  // The water's depth is that of its top row of particles (the grid starts at the floor).
  const double depth = std::floor(b.depth / b.h + 1e-9) * b.h;
  const auto& last = r.responses.rows.back();
  const double area0 = r.responses.rows.front()[0];
  const double p_expected = 1000.0 * 9.81 * depth;
  std::printf("box %g x %g, h %g, %g s: area %+.2e, max |A/A0 - 1| %.2e, max speed %.2e m/s, bottom p %.2f Pa (rho g d %.2f)\n",
              b.width, b.height, b.h, b.t_end, last[0] / area0 - 1.0, r.summary.fluid_area_max_drift, last[1],
              last[2], p_expected);
  EXPECT_LT(r.summary.fluid_area_max_drift, 1e-3);
  EXPECT_LT(last[1], 1e-3);
  EXPECT_NEAR(last[2], p_expected, 0.01 * p_expected);
}

}  // namespace pfem
