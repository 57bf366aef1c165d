// FORM on the model examples in examples/reliability/, in-process with DDM gradients: each
// converges on its limit state, and a fresh simulation at the design point lies on it (README,
// "Reliability of a PFEM model").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "clients/reliability/analysis.h"
#include "clients/reliability/model_limit_state.h"
#include "clients/reliability/problem_io.h"

namespace rel = pfem::reliability;

namespace {
struct Form {
  std::unique_ptr<rel::LimitState> g;
  rel::AnalysisResult r;
};

// Runs the example's FORM and checks what holds for every model limit state with DDM: it
// converged, one simulation per evaluation, and a fresh run at the design point gives the g the
// search ended on (a run without the sensitivities takes the same path), within g_bound of 0.
Form converged_form(const std::string& example, double g_bound) {
  const rel::Problem p =
      rel::build_problem(rel::read_problem_file(std::string(PFEM_SOURCE_DIR) + "/examples/reliability/" + example));
  Form f{rel::make_limit_state(p, rel::EvaluatorOptions{}), {}};
  f.r = rel::analyze(p, *f.g, rel::analysis_options(p));
  std::printf("%s: beta %.5f pf %.4e x* = (%.6g, %.6g), %d iterations, %lld simulations, %.0f s\n", example.c_str(),
              f.r.form.beta, f.r.form.pf, f.r.form.x(0), f.r.form.x(1), f.r.form.iterations,
              f.r.simulations->simulations, f.r.wall_seconds);
  EXPECT_TRUE(f.r.form.converged) << f.r.form.message;
  const std::vector<double> x_star(f.r.form.x.data(), f.r.form.x.data() + f.r.form.x.size());
  const double g_fresh = f.g->evaluate(x_star, {});
  EXPECT_EQ(g_fresh, f.r.form.g);
  EXPECT_LT(std::abs(g_fresh), g_bound);
  EXPECT_EQ(f.r.simulations->simulations, f.r.form.evaluations);
  return f;
}
}  // namespace

// The paper's yielding obstacle to 0.3 s, E and Fy lognormal, g = 0.075 m - max |tip_ux|. About
// 11 simulations of ~8 s each; g at the design point within 0.1 % of the threshold.
TEST(ReliabilityExamples, ObstacleFormWithDdmConverges) {
  const Form f = converged_form("dam-break-obstacle.json", 1e-3 * 0.075);
  // beta moves with the engine's physics and remeshing rules (at 72 mm: 3.647 through the server
  // in session 2, 3.600 after the boundary alpha, 3.379 with the interior insertion length, 3.359
  // with the structure's tangent at every iterate; the obstacle's own weight then raised its
  // deflection by ~5 mm, and the threshold to 75 mm gives 2.772; the volume correction takes out
  // the +1.2 % of water the column's front had gained by 0.2 s, the peak at the mean values goes
  // 71.8 -> 71.4 mm and beta to 3.233; with particles put back beside walls and the wider alpha
  // inside the water (29e6c0b, 12d7d87) the peak at the mean values is 71.16 mm, beta 3.505 (the
  // old design point E = 926996, Fy = 36329 now peaks at 74.82 mm; 3.389, converged to g's
  // resolution, with the contact line's rule of 298fd8c): a band, not a reference value.
  EXPECT_NEAR(f.r.form.beta, 3.50, 0.2);
  // The yield stress drives the peak deflection: a weaker obstacle at the design point.
  EXPECT_LT(f.r.form.x(1), 5e4);
  EXPECT_GT(std::abs(f.r.form.alpha(1)), std::abs(f.r.form.alpha(0)));
}

// The closed wave flume to 3 s at h = 5 mm, the stroke S and the plate's E lognormal, g = 3.2 mm
// - max |tip_ux| over 2 <= t <= 3 s. About 14 simulations of ~80 s each; g at the design point
// within the example's tolerance, 5 % of g at the means (0.70 mm).
TEST(ReliabilityExamples, WaveFlumeFormWithDdmConverges) {
  const Form f = converged_form("wave-flume.json", 0.05 * 7.0e-4);
  // 1.806 to about 0.07 (commit 1fc26a2); at h = 10 mm (1.548 before 298fd8c) g was dominated by
  // the alpha test's events at the plate and had no one design point (README, Reliability of a
  // PFEM model). A band for the engine's remeshing rules, as above.
  EXPECT_NEAR(f.r.form.beta, 1.80, 0.15);
  // Failure needs bigger waves and a softer plate.
  EXPECT_GT(f.r.form.x(0), 0.02);
  EXPECT_LT(f.r.form.x(1), 5e7);
}
