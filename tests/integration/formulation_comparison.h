#pragma once
// The paper's comparison of its two formulations on one example (incompressible_test.cpp,
// tests/slow/incompressible_examples_test.cpp): the example run with analysis.formulation
// "quasi-incompressible" and "incompressible", their tip deflections, and each formulation's DDM
// against the central finite differences of its own response.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/analysis/gradient_check.h"
#include "engine/io/model_io.h"

namespace pfem {

inline pfem::v1::Model example_with(const std::string& name, const std::string& formulation) {
  auto model = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + name + ".json");
  model.mutable_analysis()->set_formulation(formulation);
  return model;
}

// Both DDMs against their formulations' FDM (eps 1e-8) to t_end, printed for every recorder and
// parameter; for tip_ux the quasi-incompressible one within 1e-4 of the FDM's peak and the
// incompressible (approximate) one further than that.
inline void expect_only_the_exact_ddm_matches(const std::string& name, double t_end,
                                              const std::vector<std::string>& params) {
  RunOptions options;
  options.t_end = t_end;
  options.params = params;
  options.fdm_eps = 1e-8;
  const GradientCheck exact = check_gradients(example_with(name, "quasi-incompressible"), options, false);
  const GradientCheck approximate = check_gradients(example_with(name, "incompressible"), options, false);
  for (const auto* c : {&exact, &approximate}) {
    ASSERT_EQ(c->ddm.status, RunStatus::kCompleted) << c->ddm.message;
    ASSERT_EQ(c->fdm.status, RunStatus::kCompleted) << c->fdm.message;
  }
  EXPECT_EQ(exact.ddm.sensitivity_method, "ddm");
  EXPECT_EQ(approximate.ddm.sensitivity_method, "ddm-approximate");
  ASSERT_EQ(exact.rows.size(), approximate.rows.size());
  int tips = 0;
  for (std::size_t r = 0; r < exact.rows.size(); ++r) {
    const auto &e = exact.rows[r], &a = approximate.rows[r];
    ASSERT_EQ(e.recorder + e.parameter, a.recorder + a.parameter);
    std::printf("%s to %g s, %-18s %-6s |DDM - FDM| / max |FDM|: quasi-incompressible %.2e (max |FDM| %.4e), "
                "incompressible approximate %.2e (max |FDM| %.4e)\n",
                name.c_str(), t_end, e.recorder.c_str(), e.parameter.c_str(), e.ddm, e.max_fdm, a.ddm, a.max_fdm);
    if (e.recorder != "tip_ux") continue;
    ++tips;
    EXPECT_LE(e.ddm, 1e-4) << e.parameter;
    EXPECT_GT(a.ddm, 1e-4) << a.parameter;
  }
  EXPECT_EQ(tips, static_cast<int>(params.size()));
}

}  // namespace pfem
