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
// 4 simulations of ~8 s each; g at the design point within 0.1 % of the threshold.
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
// - max |tip_ux| over 2 <= t <= 3 s. About 4 simulations of ~80 s each; g at the design point
// within the example's tolerance, 5 % of g at the means (0.70 mm).
TEST(ReliabilityExamples, WaveFlumeFormWithDdmConverges) {
  const Form f = converged_form("wave-flume.json", 0.05 * 7.0e-4);
  // 1.972 in 3 simulations with beam riders (the plate's contact line level with the water);
  // 1.788 in 4 with edges along the free surface split (1.806 to about 0.07 before, at commit
  // 1fc26a2); at h = 10 mm 1.881 with them, where before g was dominated by the alpha test's
  // events at the plate and had no one design point (1.548 before 298fd8c; README, Reliability of
  // a PFEM model). A band for the engine's remeshing rules, as above.
  EXPECT_NEAR(f.r.form.beta, 1.97, 0.15);
  // Failure needs bigger waves and a softer plate.
  EXPECT_GT(f.r.form.x(0), 0.02);
  EXPECT_LT(f.r.form.x(1), 5e7);
}

// The same limit state on the model's own mesh (h = 10 mm, the plate in 20 elements), value-only
// runs along the ray u = R (0.5648, -0.8252) through the point where this FORM stopped on the
// engine of 298fd8c (README, Reliability of a PFEM model): g falls as the waves grow
// and the plate softens. With the free surface's own edges never split, the crest running up the
// plate stretched a surface triangle until the alpha test dropped it, at times that move with the
// parameters, and g along this ray went -33, -163, +49, -209 um (R = 1.5, 1.6, 1.7, 1.8); now
// +214, +179, +90, +74 um (at h = 5 mm +77 um at R = 1.7, +45 at 1.8).
TEST(ReliabilityExamples, WaveFlumeLimitStateOnTheCoarseMeshFallsAlongARay) {
  pfem::v1::ReliabilityProblem message =
      rel::read_problem_file(std::string(PFEM_SOURCE_DIR) + "/examples/reliability/wave-flume.json");
  pfem::v1::Model& model = *message.mutable_limit_state()->mutable_model()->mutable_model();
  model.mutable_mesh()->set_h(0.01);
  model.mutable_structure()->mutable_beams(0)->set_elements(20);
  const rel::Problem p = rel::build_problem(message);
  const auto g = rel::make_limit_state(p, rel::EvaluatorOptions{});
  double previous = 0.0;
  for (const double R : {1.5, 1.6, 1.7, 1.8}) {
    Eigen::VectorXd u(2);
    u << 0.5648 * R, -0.8252 * R;
    const Eigen::VectorXd x = p.transform->to_x(u);
    const double value = g->evaluate(std::vector<double>(x.data(), x.data() + x.size()), {});
    std::printf("R = %.2f: S = %.6g, E = %.6g, g = %+.1f um\n", R, x(0), x(1), 1e6 * value);
    if (R > 1.5) {
      EXPECT_LT(value, previous) << "at R = " << R;
    }
    previous = value;
  }
}
