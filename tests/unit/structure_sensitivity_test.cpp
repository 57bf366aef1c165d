// DDM sensitivities of the structural library, object by object, against central finite
// differences of re-runs with a perturbed parameter:
//   bilinear material  total stress sensitivity along a cyclic strain path (w.r.t. E0, Fy, b),
//                      with the path independent of and dependent on the parameters;
//   fiber section      conditional resultant sensitivity after a plastic history (b, d, E0, Fy,
//   b_h); elements           basic force sensitivity, conditional force sensitivity after a plastic
//                      history, mass and initial stiffness sensitivities (elastic and
//                      displacement-based; Linear and Corotational with a large rotation).
// All parameters are differentiated in one run (seed k = unit vector k), so that the
// per-parameter storage is exercised too.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "engine/structure/bilinear_material.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/elastic_beam_column.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/finite_difference.h"

namespace pfem::structure {
namespace {

using Theta = std::vector<double>;
constexpr double kTolerance = 1e-6;
constexpr double kRelativeStep = 1e-6;

// d g / d theta_k by central differences with a step relative to theta_k.
template <typename G>
auto fd(G&& g, const Theta& theta, int k) {
  return central_difference(
      [&](double value) {
        Theta t = theta;
        t[k] = value;
        return g(t);
      },
      theta[k], kRelativeStep * std::abs(theta[k]));
}

// A loading path scaled by s(theta) = prod_k (theta_k / theta0_k)^c_k (c = 0: independent of
// theta), so that ds/dtheta_k = c_k / theta0_k at theta0.
struct PathScale {
  Theta theta0;
  std::vector<double> c;
  double operator()(const Theta& t) const {
    double s = 1.0;
    for (std::size_t k = 0; k < c.size(); ++k) s *= std::pow(t[k] / theta0[k], c[k]);
    return s;
  }
  double sensitivity(int k) const { return c[k] / theta0[k]; }
};

// Records the largest error seen by a test (printed for the report) and checks it.
void expect_close(const Eigen::MatrixXd& ddm, const Eigen::MatrixXd& fd, const std::string& what,
                  double& worst) {
  const double error = max_relative_error(ddm, fd);
  worst = std::max(worst, error);
  EXPECT_LT(error, kTolerance) << what << "\nDDM\n" << ddm << "\nFD\n" << fd;
}

// ---------------------------------------------------------------------------------------------
// Bilinear material: theta = (E0, Fy, b).
const Theta kMaterialTheta{200e3, 250.0, 0.05};
// elastic, yielding, elastic unloading, reverse yielding, elastic reloading, yielding again.
const std::vector<double> kStrainPath{0.0005, 0.001,   0.0017,  0.0024,  0.003,
                                      0.0021, 0.0008,  -0.0006, -0.0019, -0.0031,
                                      -0.002, -0.0004, 0.0012,  0.0026,  0.0036};

BilinearMaterial seeded_bilinear(double e0, double fy, double b, int e0_k, int fy_k, int b_k,
                                 int P) {
  BilinearMaterial m(fy, e0, b);
  m.set_parameter_seed(e0_k, {0.0, 1.0, 0.0});
  m.set_parameter_seed(fy_k, {1.0, 0.0, 0.0});
  m.set_parameter_seed(b_k, {0.0, 0.0, 1.0});
  m.set_num_parameters(P);
  return m;
}

// Stresses, then the committed plastic strain and back stress at the end.
Eigen::VectorXd run_material(const Theta& t, const PathScale& scale) {
  BilinearMaterial m(t[1], t[0], t[2]);
  const int n = static_cast<int>(kStrainPath.size());
  Eigen::VectorXd out(n + 2);
  for (int i = 0; i < n; ++i) {
    m.set_trial_strain(kStrainPath[i] * scale(t));
    out(i) = m.stress();
    m.commit();
  }
  out(n) = m.committed_history().plastic_strain;
  out(n + 1) = m.committed_history().back_stress;
  return out;
}

void check_material_path(const PathScale& scale) {
  const int n = static_cast<int>(kStrainPath.size());
  const Theta& t = kMaterialTheta;
  BilinearMaterial m = seeded_bilinear(t[0], t[1], t[2], 0, 1, 2, 3);
  Eigen::MatrixXd ddm(n + 2, 3);
  bool yielded_forward = false, yielded_reverse = false;
  for (int i = 0; i < n; ++i) {
    m.set_trial_strain(kStrainPath[i]);
    (m.stress() > 0 ? yielded_forward : yielded_reverse) |= m.is_plastic();
    for (int k = 0; k < 3; ++k) {
      const double dstrain = kStrainPath[i] * scale.sensitivity(k);
      m.set_strain_sensitivity(k, dstrain);
      EXPECT_EQ(m.strain_sensitivity(k), dstrain);
      ddm(i, k) = m.stress_sensitivity(k);
    }
    m.commit();
  }
  ASSERT_TRUE(yielded_forward && yielded_reverse);
  double worst = 0.0;
  for (int k = 0; k < 3; ++k) {
    ddm(n, k) = m.committed_history_sensitivity(k).plastic_strain;
    ddm(n + 1, k) = m.committed_history_sensitivity(k).back_stress;
    const Eigen::VectorXd reference =
        fd([&](const Theta& p) { return run_material(p, scale); }, t, k);
    expect_close(ddm.col(k), reference, "parameter " + std::to_string(k), worst);
  }
  std::cout << "max relative error " << worst << "\n";
}

TEST(BilinearSensitivity, CyclicPathIndependentOfTheParameters) {
  check_material_path({kMaterialTheta, {0.0, 0.0, 0.0}});
}

TEST(BilinearSensitivity, CyclicPathThatDependsOnTheParameters) {
  check_material_path({kMaterialTheta, {0.3, -0.2, 0.5}});
}

TEST(BilinearSensitivity, ElasticStressSensitivityIsStrainTimesSeedPlusEDstrain) {
  BilinearMaterial m = seeded_bilinear(200e3, 250.0, 0.05, 0, 1, 2, 3);
  m.set_trial_strain(0.001);
  m.set_strain_sensitivity(0, 2e-9);
  EXPECT_DOUBLE_EQ(m.stress_sensitivity(0), 0.001 + 200e3 * 2e-9);
  EXPECT_EQ(m.conditional_stress_sensitivity(1), 0.0);  // Fy does not act while elastic
}

TEST(BilinearSensitivity, RevertDropsTheTrialHistorySensitivity) {
  BilinearMaterial m = seeded_bilinear(200e3, 250.0, 0.05, 0, 1, 2, 3);
  m.set_trial_strain(0.003);
  m.set_strain_sensitivity(1, 0.0);
  EXPECT_NE(m.trial_history_sensitivity(1).plastic_strain, 0.0);
  m.revert_to_last_commit();
  EXPECT_EQ(m.trial_history_sensitivity(1).plastic_strain, 0.0);
  m.set_trial_strain(0.003);
  m.set_strain_sensitivity(1, 0.0);
  m.commit();
  EXPECT_NE(m.committed_history_sensitivity(1).plastic_strain, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Fiber section: theta = (width, depth, E0, Fy, b).
const Theta kSectionTheta{0.05, 0.1, 200e3, 250.0, 0.03};

std::unique_ptr<FiberSection> seeded_fiber_section(const Theta& t, int P) {
  const BilinearMaterial m = seeded_bilinear(t[2], t[3], t[4], 2, 3, 4, P);
  auto s = std::make_unique<FiberSection>(m, FiberSectionGeometry{t[0], t[1], 10});
  s->set_geometry_seed(0, {1.0, 0.0});
  s->set_geometry_seed(1, {0.0, 1.0});
  s->set_num_parameters(P);
  return s;
}

// A plastic history along e_n(theta) = base_n s(theta), then a trial at a fixed deformation.
const std::vector<Vec2> kDeformationPath{{0.002, 0.08}, {0.0, 0.15}, {-0.001, -0.06}};
const Vec2 kFinalDeformation{0.0005, 0.02};
const PathScale kSectionScale{kSectionTheta, {0.2, -0.3, 0.1, 0.4, -0.5}};

Vec2 run_section(const Theta& t) {
  auto s = seeded_fiber_section(t, 0);
  for (const Vec2& e : kDeformationPath) {
    s->set_trial_deformation(e * kSectionScale(t));
    s->commit();
  }
  s->set_trial_deformation(kFinalDeformation);
  return s->resultant();
}

TEST(FiberSectionSensitivity, ConditionalResultantAfterAPlasticHistory) {
  const Theta& t = kSectionTheta;
  auto s = seeded_fiber_section(t, 5);
  for (const Vec2& e : kDeformationPath) {
    s->set_trial_deformation(e);
    for (int k = 0; k < 5; ++k) s->set_deformation_sensitivity(k, e * kSectionScale.sensitivity(k));
    s->commit();
  }
  s->set_trial_deformation(kFinalDeformation);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const Vec2 reference = fd(run_section, t, k);
    expect_close(s->conditional_resultant_sensitivity(k), reference,
                 "parameter " + std::to_string(k), worst);
  }
  std::cout << "max relative error " << worst << "\n";
}

TEST(FiberSectionSensitivity, AreaAndInitialTangent) {
  const Theta& t = kSectionTheta;
  auto s = seeded_fiber_section(t, 5);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const auto area = [](const Theta& p) { return seeded_fiber_section(p, 0)->area(); };
    const auto k0 = [](const Theta& p) { return seeded_fiber_section(p, 0)->initial_tangent(); };
    expect_close(Eigen::Matrix<double, 1, 1>(s->area_sensitivity(k)),
                 Eigen::Matrix<double, 1, 1>(fd(area, t, k)), "area", worst);
    expect_close(s->initial_tangent_sensitivity(k), fd(k0, t, k), "initial tangent", worst);
  }
  std::cout << "max relative error " << worst << "\n";
}

// ---------------------------------------------------------------------------------------------
// Elements on the reference chord (0.3, 0.1) -> (1.9, 1.3), L0 = 2.
const Vec2 kXi{0.3, 0.1}, kXj{1.9, 1.3};

// End displacements: a rigid rotation phi about node i, an elongation and end rotations
// relative to the chord.
Vec6 end_displacement(double phi, double elongation, double ri, double rj) {
  const Vec2 d = kXj - kXi;
  const Vec2 rotated = Eigen::Rotation2D<double>(phi) * d * (1.0 + elongation / d.norm());
  Vec6 u;
  u << 0.0, 0.0, phi + ri, rotated - d, phi + rj;
  return u;
}

struct ElementCase {
  std::string name;
  Theta theta0;
  std::function<std::unique_ptr<BeamColumn2d>(const Theta&, const BeamOptions&)> make;
};

void PrintTo(const ElementCase& c, std::ostream* os) { *os << c.name; }

// theta = (E, A, I, rho).
std::unique_ptr<BeamColumn2d> elastic_beam(const Theta& t, const BeamOptions& o) {
  Seeds<ElasticSectionProperties> seeds;
  seeds.set(0, {1.0, 0.0, 0.0});
  seeds.set(1, {0.0, 1.0, 0.0});
  seeds.set(2, {0.0, 0.0, 1.0});
  BeamOptions options = o;
  options.rho = t[3];
  options.rho_seeds.set(3, 1.0);
  return std::make_unique<ElasticBeamColumn2d>(std::array<int, 2>{0, 1}, kXi, kXj,
                                               ElasticSectionProperties{t[0], t[1], t[2]}, options,
                                               seeds);
}

// theta = (width, depth, E0, Fy, b, rho).
std::unique_ptr<BeamColumn2d> fiber_beam(const Theta& t, const BeamOptions& o) {
  BeamOptions options = o;
  options.rho = t[5];
  options.rho_seeds.set(5, 1.0);
  return std::make_unique<DispBeamColumn2d>(std::array<int, 2>{0, 1}, kXi, kXj,
                                            *seeded_fiber_section(t, 0), options, 3);
}

// theta = (E, A, I, rho) on an elastic section of a displacement-based element.
std::unique_ptr<BeamColumn2d> elastic_section_beam(const Theta& t, const BeamOptions& o) {
  ElasticSection section({t[0], t[1], t[2]});
  section.set_property_seed(0, {1.0, 0.0, 0.0});
  section.set_property_seed(1, {0.0, 1.0, 0.0});
  section.set_property_seed(2, {0.0, 0.0, 1.0});
  BeamOptions options = o;
  options.rho = t[3];
  options.rho_seeds.set(3, 1.0);
  return std::make_unique<DispBeamColumn2d>(std::array<int, 2>{0, 1}, kXi, kXj, section, options);
}

const Theta kElasticTheta{200e3, 5e-3, 4e-6, 7.8};
const Theta kFiberTheta{0.05, 0.1, 200e3, 250.0, 0.03, 7.8};

class ElementSensitivity
    : public ::testing::TestWithParam<std::tuple<ElementCase, TransfKind, MassKind>> {
 protected:
  BeamOptions options() const {
    BeamOptions o;
    o.transf = std::get<1>(GetParam());
    o.mass = std::get<2>(GetParam());
    return o;
  }
  const ElementCase& element_case() const { return std::get<0>(GetParam()); }
  // A plastic first step (large rigid rotation for the corotational transformation) whose
  // displacement depends on theta; the second step's trial displacement is fixed.
  bool corotational() const { return std::get<1>(GetParam()) == TransfKind::kCorotational; }
  Vec6 first_step() const {
    return end_displacement(corotational() ? 0.9 : 0.0, 0.002, 0.03, -0.01);
  }
  Vec6 second_step() const {
    return end_displacement(corotational() ? 1.0 : 0.0, 0.0005, 0.01, 0.004);
  }
  PathScale scale() const {
    const Theta& t0 = element_case().theta0;
    std::vector<double> c(t0.size());
    for (std::size_t k = 0; k < c.size(); ++k) c[k] = 0.1 * (static_cast<double>(k) - 2.0);
    return {t0, c};
  }
};

TEST_P(ElementSensitivity, BasicAndConditionalForcesAfterAPlasticStep) {
  const ElementCase& c = element_case();
  const int P = static_cast<int>(c.theta0.size());
  const Vec6 u1 = first_step(), u2 = second_step();
  const PathScale s = scale();
  // The first step is a displacement scaled about node i's position: u1(theta) = u1 s(theta).
  auto e = c.make(c.theta0, options());
  e->set_num_parameters(P);
  e->set_trial_displacement(u1);
  for (int k = 0; k < P; ++k) e->set_displacement_sensitivity(k, u1 * s.sensitivity(k));
  std::vector<Vec3> basic(P);
  for (int k = 0; k < P; ++k) basic[k] = e->basic_force_sensitivity(k);
  e->commit();
  e->set_trial_displacement(u2);

  const auto first = [&](const Theta& t) {
    auto x = c.make(t, options());
    x->set_trial_displacement(u1 * s(t));
    return x;
  };
  const auto basic_force = [&](const Theta& t) -> Vec3 { return first(t)->basic_force(); };
  const auto second_force = [&](const Theta& t) -> Vec6 {
    auto x = first(t);
    x->commit();
    x->set_trial_displacement(u2);
    return x->resisting_force();
  };
  double worst = 0.0;
  for (int k = 0; k < P; ++k) {
    const std::string what = c.name + " parameter " + std::to_string(k);
    expect_close(basic[k], fd(basic_force, c.theta0, k), what + " basic force", worst);
    expect_close(e->conditional_force_sensitivity(k), fd(second_force, c.theta0, k),
                 what + " conditional force", worst);
  }
  std::cout << c.name << " max relative error " << worst << "\n";
}

TEST_P(ElementSensitivity, MassAndInitialStiffness) {
  const ElementCase& c = element_case();
  auto e = c.make(c.theta0, options());
  const auto mass = [&](const Theta& t) -> Mat6 { return c.make(t, options())->mass_matrix(); };
  const auto k0 = [&](const Theta& t) -> Mat6 { return c.make(t, options())->initial_stiffness(); };
  double worst = 0.0;
  for (int k = 0; k < static_cast<int>(c.theta0.size()); ++k) {
    expect_close(e->mass_sensitivity(k), fd(mass, c.theta0, k), c.name + " mass", worst);
    expect_close(e->initial_stiffness_sensitivity(k), fd(k0, c.theta0, k), c.name + " K0", worst);
  }
  std::cout << c.name << " max relative error " << worst << "\n";
}

INSTANTIATE_TEST_SUITE_P(
    Elements, ElementSensitivity,
    ::testing::Combine(::testing::Values(ElementCase{"elastic", kElasticTheta, elastic_beam},
                                         ElementCase{"fiber", kFiberTheta, fiber_beam},
                                         ElementCase{"elastic_section", kElasticTheta,
                                                     elastic_section_beam}),
                       ::testing::Values(TransfKind::kLinear, TransfKind::kCorotational),
                       ::testing::Values(MassKind::kLumped, MassKind::kConsistent)),
    [](const auto& test) {
      return std::get<0>(test.param).name +
             (std::get<1>(test.param) == TransfKind::kLinear ? "_linear" : "_corotational") +
             (std::get<2>(test.param) == MassKind::kLumped ? "_lumped" : "_consistent");
    });

}  // namespace
}  // namespace pfem::structure
