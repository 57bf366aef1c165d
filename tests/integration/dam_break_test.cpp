// The collapsing water column of examples/dam-break.json against the experiment of Martin &
// Moyce (1952), Phil. Trans. R. Soc. A 244, 312-324, column n^2 = 2 (height 2a, a = 0.146 m
// here). The experimental surge-front points are in tests/data/martin_moyce_1952_n2.csv
// (source and cross-check in its header line).
//
// The example runs as it is (h = 0.005 m, ~1700 particles, 400 steps, ~25 s).
//
// Checks: front position Z = x/a against the experiment at its times T = t sqrt(2g/a) up to
// Z = 3, within 10 %; the fluid area within 3 % of its initial value up to t = 0.4 s.
// Release delay: the experiment's column was released by removing a retaining gate, which takes
// a finite time, while the simulated column is released instantly at t = 0. As is usual we shift
// the experiment by a fixed dT = 0.175 (the gate-release shift of the Lethe project's Martin &
// Moyce benchmark, within the 0.2 allowed here): Z_sim(T - 0.175) is compared with Z_exp(T).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

constexpr double kReleaseDelay = 0.175;   // in T = t sqrt(2g/a), applied to the experiment
constexpr double kFrontTolerance = 0.10;  // relative, on Z = x/a
constexpr double kAreaTolerance = 0.03;   // relative, up to t = 0.4 s

struct Series {
  std::vector<double> x, y;
};

Series read_experiment() {
  const std::string path = std::string(PFEM_SOURCE_DIR) + "/tests/data/martin_moyce_1952_n2.csv";
  std::ifstream in(path);
  Series s;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("T,", 0) == 0) continue;
    std::istringstream row(line);
    double t = 0, z = 0;
    char comma = 0;
    if (row >> t >> comma >> z && comma == ',') s.x.push_back(t), s.y.push_back(z);
  }
  return s;
}

// Linear interpolation of y(x) at x = at (x increasing); NaN outside the sampled range.
double interpolate(const Series& s, double at) {
  for (std::size_t i = 1; i < s.x.size(); ++i)
    if (s.x[i - 1] <= at && at <= s.x[i])
      return s.y[i - 1] + (s.y[i] - s.y[i - 1]) * (at - s.x[i - 1]) / (s.x[i] - s.x[i - 1]);
  return std::numeric_limits<double>::quiet_NaN();
}

class DamBreak : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = std::make_unique<pfem::v1::Model>(
        read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/dam-break.json"));
    const auto& column_shape = model_->fluid_regions(0).rectangle();
    a_ = column_shape.max().x() - column_shape.min().x();
    RunOptions options;
    options.t_end = 0.4;
    result_ = std::make_unique<RunResult>(run(*model_, options));
  }
  static void TearDownTestSuite() { result_.reset(), model_.reset(); }

  static std::unique_ptr<pfem::v1::Model> model_;
  static std::unique_ptr<RunResult> result_;
  static double a_;
};
std::unique_ptr<pfem::v1::Model> DamBreak::model_;
std::unique_ptr<RunResult> DamBreak::result_;
double DamBreak::a_ = 0.0;

TEST_F(DamBreak, RunsToTheEnd) {
  const auto& s = result_->summary;
  std::printf("h = %.5f m, %d particles, up to %d elements, %d steps (%d halved), %ld Newton iterations, %.2f s\n",
              model_->mesh().h(), s.particles, s.max_elements, s.steps, s.substeps, s.newton_iterations,
              s.wall_seconds);
  EXPECT_EQ(s.status, RunStatus::kCompleted) << s.message;
  EXPECT_NEAR(result_->responses.time.back(), 0.4, 1e-9);
}

TEST_F(DamBreak, FrontFollowsMartinMoyceUpToThreeColumnWidths) {
  ASSERT_NEAR(a_, 0.146, 1e-12);
  const double g = model_->has_gravity() ? std::hypot(model_->gravity().x(), model_->gravity().y()) : 9.81;
  const auto& h = result_->responses;
  const int front = h.column("front_x");
  ASSERT_GE(front, 0);
  Series sim;  // Z(T) of the simulation
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    sim.x.push_back(h.time[i] * std::sqrt(2.0 * g / a_));
    sim.y.push_back(h.rows[i][front] / a_);
  }
  const Series exp = read_experiment();
  ASSERT_GE(exp.x.size(), 8u) << "tests/data/martin_moyce_1952_n2.csv not read";

  std::printf("Martin & Moyce (1952) n^2 = 2 vs simulation (h = %.5f m), release delay dT = %.3f\n",
              model_->mesh().h(), kReleaseDelay);
  std::printf("%8s %8s %8s %8s\n", "T", "Z_exp", "Z_sim", "error");
  int compared = 0;
  for (std::size_t k = 0; k < exp.x.size(); ++k) {
    if (exp.y[k] > 3.0 + 1e-9) continue;
    const double z_sim = interpolate(sim, exp.x[k] - kReleaseDelay);
    const double error = z_sim / exp.y[k] - 1.0;
    std::printf("%8.2f %8.2f %8.3f %+7.1f%%\n", exp.x[k], exp.y[k], z_sim, 100 * error);
    EXPECT_TRUE(std::isfinite(z_sim)) << "no simulated front at T = " << exp.x[k] - kReleaseDelay;
    EXPECT_LE(std::abs(error), kFrontTolerance) << "at T = " << exp.x[k] << ": Z_exp = " << exp.y[k]
                                                << ", Z_sim = " << z_sim;
    ++compared;
  }
  EXPECT_GE(compared, 8);
}

TEST_F(DamBreak, FluidAreaIsConserved) {
  const auto& h = result_->responses;
  const int area = h.column("fluid_area");
  ASSERT_GE(area, 0);
  const double area0 = h.rows.front()[area];
  ASSERT_GT(area0, 0.0);
  double worst = 0.0, worst_t = 0.0;
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    const double d = std::abs(h.rows[i][area] / area0 - 1.0);
    if (d > worst) worst = d, worst_t = h.time[i];
  }
  std::printf("fluid area %.6f m^2 at t = 0; largest change %.2f %% at t = %.3f s (run reached t = %.3f s)\n",
              area0, 100 * worst, worst_t, h.time.back());
  EXPECT_LT(worst, kAreaTolerance);
  EXPECT_NEAR(h.time.back(), 0.4, 1e-9) << "the area could only be checked up to the failure";
}

}  // namespace
}  // namespace pfem
