// FORM on examples/reliability/dam-break-obstacle.json (the paper's yielding obstacle to
// 0.3 s, E and Fy lognormal, g = 0.075 m - max |tip_ux|) in-process with DDM gradients: it
// converges on the limit state (README, "Reliability of a PFEM model"). About 5 simulations of
// ~8 s each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "clients/reliability/analysis.h"
#include "clients/reliability/model_limit_state.h"
#include "clients/reliability/problem_io.h"

namespace rel = pfem::reliability;

TEST(ReliabilityObstacle, FormWithDdmConverges) {
  const rel::Problem p = rel::build_problem(rel::read_problem_file(
      std::string(PFEM_SOURCE_DIR) + "/examples/reliability/dam-break-obstacle.json"));
  const auto g = rel::make_limit_state(p, rel::EvaluatorOptions{});
  const rel::AnalysisOptions o = rel::analysis_options(p);
  const rel::AnalysisResult r = rel::analyze(p, *g, o);
  std::printf("beta %.5f pf %.4e x* = (E %.6g, Fy %.6g), %d iterations, %lld simulations, %.0f s\n",
              r.form.beta, r.form.pf, r.form.x(0), r.form.x(1), r.form.iterations,
              r.simulations->simulations, r.wall_seconds);
  ASSERT_TRUE(r.form.converged) << r.form.message;
  // The design point lies on the limit state: a fresh simulation there gives g = 0 (to 0.1 % of
  // the 75 mm threshold). beta moves with the engine's physics and remeshing rules (at 72 mm:
  // 3.647 through the server in session 2, 3.600 after the boundary alpha, 3.379 with the
  // interior insertion length, 3.359 with the structure's tangent at every iterate; the
  // obstacle's own weight then raised its deflection by ~5 mm, and the threshold to 75 mm gives
  // 2.772; the volume correction takes out the +1.2 % of water the column's front had gained by
  // 0.2 s, the peak at the mean values goes 71.8 -> 71.4 mm and beta to 3.233): a band, not a
  // reference value.
  const std::vector<double> x_star(r.form.x.data(), r.form.x.data() + r.form.x.size());
  EXPECT_LT(std::abs(g->evaluate(x_star, {})), 1e-3 * 0.075);
  EXPECT_NEAR(r.form.beta, 3.23, 0.2);
  // The yield stress drives the peak deflection: a weaker obstacle at the design point.
  EXPECT_LT(r.form.x(1), 5e4);
  EXPECT_GT(std::abs(r.form.alpha(1)), std::abs(r.form.alpha(0)));
  EXPECT_EQ(r.simulations->simulations, r.form.evaluations);  // DDM: one run per evaluation
}
