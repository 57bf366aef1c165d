// DDM against central finite differences on the paper's two examples as shipped (issue 4):
//  - sloshing-beam to 0.45 s: tip_ux and base_p w.r.t. E and rho_f;
//  - dam-break-obstacle to 0.34 s (impact and yielding included): tip_ux w.r.t. E and Fy.
// The largest |DDM - FDM| over time relative to the largest |FDM| must be at most 1e-3, and the
// DDM without H and T must fail that check. The finite-difference step is the one at which the
// perturbed runs keep the base run's discrete path (the mesh connectivity is piecewise constant
// in the parameters, theory §6): at 1e-7 a remeshing decision of the sloshing run differs
// between the perturbed runs at 0.42 s, so both checks use the paper's 1e-8; at 1e-8 the
// rho_f-perturbed sloshing runs part between 0.45 and 0.5 s since the free surface carries a
// pressure (engine of commit 135902c; to 0.45 s the DDM is within 9.1e-7 of the FDM for the
// tip and 5.0e-6 for the base pressure, to 0.5 s the FDM jumps), so the check stops at 0.45 s. The obstacle's
// perturbed runs part at 0.344 s (Fy) and 0.351 s (E), at 1e-10 too, while at 1e-12 the FDM is
// the Newton tolerance's noise: the check stops at 0.34 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "engine/analysis/gradient_check.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

void expect_exact(const std::string& example, double t_end, double fdm_eps, const std::vector<std::string>& params,
                  const std::vector<std::string>& recorders) {
  RunOptions options;
  options.t_end = t_end;
  options.params = params;
  options.fdm_eps = fdm_eps;
  const auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + example + ".json");
  const GradientCheck c = check_gradients(model, options, true);
  ASSERT_EQ(c.ddm.status, RunStatus::kCompleted) << c.ddm.message;
  ASSERT_EQ(c.fdm.status, RunStatus::kCompleted) << c.fdm.message;
  int checked = 0;
  for (const auto& r : c.rows) {
    std::printf("%-18s %-6s max|FDM| %.4e  DDM %.2e  without H,T %.2e\n", r.recorder.c_str(), r.parameter.c_str(),
                r.max_fdm, r.ddm, r.without_geometric);
    if (std::find(recorders.begin(), recorders.end(), r.recorder) == recorders.end()) continue;
    ++checked;
    EXPECT_GT(r.max_fdm, 0.0) << r.recorder << "/" << r.parameter;
    EXPECT_LE(r.ddm, 1e-3) << r.recorder << "/" << r.parameter;
    EXPECT_GT(r.without_geometric, 1e-2) << r.recorder << "/" << r.parameter;
  }
  EXPECT_EQ(checked, static_cast<int>(params.size() * recorders.size()));
}

TEST(DdmExamples, SloshingBeamToPointFourFiveSeconds) {
  expect_exact("sloshing-beam", 0.45, 1e-8, {"E", "rho_f"}, {"tip_ux", "base_p"});
}

TEST(DdmExamples, DamBreakObstacleToPointThreeFourSeconds) {
  expect_exact("dam-break-obstacle", 0.34, 1e-8, {"E", "Fy"}, {"tip_ux"});
}

}  // namespace
}  // namespace pfem
