// Functionals of recorder histories and their gradients (engine/analysis/functional.h).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/analysis/functional.h"

namespace {

using pfem::FunctionalKind;
using pfem::FunctionalSpec;

struct Fixture {
  pfem::Histories responses;
  pfem::Histories sensitivities;
  std::vector<std::string> params{"E", "rho_f"};
  Fixture() {
    responses.columns = {"tip", "p"};
    responses.time = {0.0, 0.1, 0.2, 0.3};
    responses.rows = {{0.0, 5.0}, {2.0, -7.0}, {-3.0, 1.0}, {1.0, 4.0}};
    sensitivities.columns = {"dtip/dE", "dtip/drho_f", "dp/dE", "dp/drho_f"};
    sensitivities.time = responses.time;
    sensitivities.rows = {{0, 0, 0, 0}, {10, 20, 30, 40}, {11, 21, 31, 41}, {12, 22, 32, 42}};
  }
  pfem::FunctionalValue eval(const std::string& rec, FunctionalKind kind, double t = 0.0) const {
    return pfem::evaluate_functional(responses, sensitivities, params, FunctionalSpec{rec, kind, t});
  }
};

TEST(Functional, ExtremesTakeTheGradientAtTheArgExtremeTime) {
  Fixture f;
  auto v = f.eval("tip", FunctionalKind::kMax);
  EXPECT_EQ(v.value, 2.0);
  EXPECT_EQ(v.time, 0.1);
  EXPECT_EQ(v.gradient, (std::vector<double>{10, 20}));
  v = f.eval("tip", FunctionalKind::kMin);
  EXPECT_EQ(v.value, -3.0);
  EXPECT_EQ(v.time, 0.2);
  EXPECT_EQ(v.gradient, (std::vector<double>{11, 21}));
  v = f.eval("tip", FunctionalKind::kMaxAbs);  // |-3| at 0.2: gradient flips sign
  EXPECT_EQ(v.value, 3.0);
  EXPECT_EQ(v.gradient, (std::vector<double>{-11, -21}));
  v = f.eval("p", FunctionalKind::kMaxAbs);
  EXPECT_EQ(v.value, 7.0);
  EXPECT_EQ(v.gradient, (std::vector<double>{-30, -40}));
  v = f.eval("p", FunctionalKind::kFinal);
  EXPECT_EQ(v.value, 4.0);
  EXPECT_EQ(v.time, 0.3);
  EXPECT_EQ(v.gradient, (std::vector<double>{32, 42}));
}

TEST(Functional, ValueAtInterpolatesLinearlyAndHitsSamplesExactly) {
  Fixture f;
  auto v = f.eval("tip", FunctionalKind::kValueAt, 0.1);
  EXPECT_EQ(v.value, 2.0);
  EXPECT_EQ(v.gradient, (std::vector<double>{10, 20}));
  v = f.eval("tip", FunctionalKind::kValueAt, 0.125);  // a quarter of the way 0.1 -> 0.2
  EXPECT_NEAR(v.value, 2.0 + 0.25 * (-5.0), 1e-12);
  EXPECT_NEAR(v.gradient[0], 10.25, 1e-12);
  EXPECT_NEAR(v.gradient[1], 20.25, 1e-12);
  v = f.eval("tip", FunctionalKind::kValueAt, 0.3 + 1e-12);  // within tolerance of the end
  EXPECT_EQ(v.value, 1.0);
}

TEST(Functional, AWindowLeavesOutTheSamplesOutsideIt) {
  Fixture f;
  FunctionalSpec spec{"tip", FunctionalKind::kMax, 0.0};
  spec.window_start = 0.15;  // leaves out the largest tip (2 at 0.1)
  auto v = pfem::evaluate_functional(f.responses, f.sensitivities, f.params, spec);
  EXPECT_EQ(v.value, 1.0);
  EXPECT_EQ(v.time, 0.3);
  EXPECT_EQ(v.gradient, (std::vector<double>{12, 22}));
  spec.kind = FunctionalKind::kMaxAbs;  // |-3| at 0.2 is inside
  v = pfem::evaluate_functional(f.responses, f.sensitivities, f.params, spec);
  EXPECT_EQ(v.value, 3.0);
  EXPECT_EQ(v.gradient, (std::vector<double>{-11, -21}));
  spec.kind = FunctionalKind::kMin;
  spec.window_start = 0.0;
  spec.window_end = 0.1 + 1e-13;  // the end sample counts within the time tolerance
  v = pfem::evaluate_functional(f.responses, f.sensitivities, f.params, spec);
  EXPECT_EQ(v.value, 0.0);
  EXPECT_EQ(v.time, 0.0);
}

TEST(Functional, ABadWindowNamesItsField) {
  Fixture f;
  const auto field_of = [&](FunctionalSpec spec) {
    try {
      pfem::evaluate_functional(f.responses, f.sensitivities, f.params, spec);
    } catch (const pfem::FunctionalError& e) {
      return e.field() + ": " + e.what();
    }
    return std::string("no error");
  };
  FunctionalSpec spec{"tip", FunctionalKind::kMax, 0.0};
  spec.window_start = 0.22;
  spec.window_end = 0.28;  // no sample between 0.2 and 0.3
  EXPECT_EQ(field_of(spec).rfind("window_start: no recorded sample", 0), 0u) << field_of(spec);
  spec.window_end = 0.1;
  EXPECT_EQ(field_of(spec), "window_end: must be >= window_start");
  spec.window_end = std::nullopt;
  spec.kind = FunctionalKind::kFinal;
  EXPECT_EQ(field_of(spec), "window_start: only used with max, min and max_abs");
  spec.kind = FunctionalKind::kMax;
  spec.window_start = std::nan("");
  EXPECT_EQ(field_of(spec), "window_start: must be finite");
}

TEST(Functional, WithoutParametersThereIsNoGradient) {
  Fixture f;
  const auto v = pfem::evaluate_functional(f.responses, {}, {},
                                           FunctionalSpec{"p", FunctionalKind::kMax, 0.0});
  EXPECT_EQ(v.value, 5.0);
  EXPECT_TRUE(v.gradient.empty());
}

TEST(Functional, ErrorsNameTheField) {
  Fixture f;
  try {
    f.eval("nope", FunctionalKind::kMax);
    FAIL();
  } catch (const pfem::FunctionalError& e) {
    EXPECT_EQ(e.field(), "recorder");
  }
  try {
    f.eval("tip", FunctionalKind::kValueAt, 0.5);
    FAIL();
  } catch (const pfem::FunctionalError& e) {
    EXPECT_EQ(e.field(), "time");
  }
  f.params = {"kappa"};
  try {
    f.eval("tip", FunctionalKind::kMax);
    FAIL();
  } catch (const pfem::FunctionalError& e) {
    EXPECT_EQ(e.field(), "sensitivities");
  }
}

TEST(Functional, KindNamesRoundTrip) {
  for (auto k : {FunctionalKind::kValueAt, FunctionalKind::kMax, FunctionalKind::kMin,
                 FunctionalKind::kMaxAbs, FunctionalKind::kFinal}) {
    EXPECT_EQ(pfem::parse_functional_kind(pfem::functional_kind_name(k)), k);
  }
  EXPECT_EQ(pfem::parse_functional_kind("at"), FunctionalKind::kValueAt);
  EXPECT_FALSE(pfem::parse_functional_kind("mean"));
}

}  // namespace
