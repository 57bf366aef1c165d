// Still water held by a cantilever (theory §7, issue 3): a tank whose right side is a clamped
// vertical beam of height L, water up to its tip. The hydrostatic load on the beam grows
// linearly from 0 at the tip to q0 = rho g L t at the base, and the small-deflection tip
// deflection is q0 L^4 / (30 EI) and the base moment q0 L^2 / 6. The beam is stiff (deflection ~ 1e-3 L) so that the
// linear theory holds; the monolithic step must carry the pressure into the beam's nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kL = 0.05, kB = 0.012, kE = 1e7, kRho = 1000.0, kG = 9.81;

std::string still_water_model() {
  return R"({
    "name": "still-water-cantilever", "thickness": 0.012,
    "fluid": {"rho": 1000.0, "mu": 0.01, "kappa": 2.15e9},
    "mesh": {"h": 0.0025},
    "fluid_regions": [{"rectangle": {"min": {"x": 0.0, "y": 0.0}, "max": {"x": 0.05, "y": 0.05}}}],
    "walls": [{"points": [{"x": 0.0, "y": 0.08}, {"x": 0.0, "y": 0.0}, {"x": 0.05, "y": 0.0}]}],
    "structure": {
      "nodes": [{"name": "base", "x": 0.05, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
                {"name": "tip", "x": 0.05, "y": 0.05}],
      "materials": [{"name": "stiff", "elastic": {"e": 1e7}}],
      "sections": [{"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.012, "fibers": 10, "material": "stiff"}}],
      "beams": [{"name": "beam", "from_node": "base", "to_node": "tip", "elements": 20,
                 "element_type": "elastic", "section": "square", "rho": 2500.0}]
    },
    "analysis": {"dt": 0.001, "t_end": 0.3},
    "recorders": [{"name": "tip_ux", "quantity": "ux", "node": "tip"},
                  {"name": "base_p", "quantity": "p", "node": "beam/1"},
                  {"name": "base_moment", "quantity": "basic_force", "element": "beam/1", "component": 1}]
  })";
}

TEST(FsiStillWater, CantileverSettlesToTheHydrostaticDeflection) {
  const RunResult r = run(parse_model_json(still_water_model()), RunOptions{});
  ASSERT_EQ(r.summary.status, RunStatus::kCompleted) << r.summary.message;
  const double inertia = kB * std::pow(kB, 3) / 12.0;
  const double q0 = kRho * kG * kL * kB;
  const double expected = q0 * std::pow(kL, 4) / (30.0 * kE * inertia);
  const auto& last = r.responses.rows.back();
  std::printf("tip deflection %.6e m, q0 L^4/(30 EI) = %.6e m (%.2f %%)\n", last[0], expected,
              100.0 * (last[0] / expected - 1.0));
  EXPECT_NEAR(last[0], expected, 0.03 * expected);
  // The pressure at the beam's first node above the base (y = 2.5 mm) is hydrostatic.
  const double p_expected = kRho * kG * (kL - 0.0025);
  EXPECT_NEAR(last[1], p_expected, 0.02 * p_expected);
  // The bending moment at the clamped end carries the whole triangular load: q0 L^2 / 6.
  const double m_expected = q0 * kL * kL / 6.0;
  std::printf("base moment %.6e N m, q0 L^2/6 = %.6e N m\n", last[2], m_expected);
  EXPECT_NEAR(std::abs(last[2]), m_expected, 0.03 * m_expected);
}

}  // namespace
}  // namespace pfem
