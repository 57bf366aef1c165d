// DDM through the whole StructureModel, against central finite differences:
//   - add_tangent() is the exact consistent tangent of resisting_force() (corotational fiber
//     beams after yielding), which the sensitivity equations need;
//   - a nonlinear static path-following analysis written here (corotational fiber cantilever
//     pushed past yield, unloaded and reverse-loaded): per converged step
//     K_T du/dtheta = dF_ext/dtheta - dFs/dtheta|u, then set_displacement_sensitivity() and
//     commit(); tip displacements and recorder quantities vs whole re-runs;
//   - the builder: seeds from sensitivity targets (parameter_seeds), checked through
//     resisting_force_sensitivity(), mass_sensitivity_times() and damping_sensitivity_times()
//     against models rebuilt with perturbed targets (set_model_target + build_structure).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "engine/io/model_io.h"
#include "engine/io/structure_builder.h"
#include "engine/structure/bilinear_material.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/finite_difference.h"
#include "engine/structure/free_dofs.h"

namespace pfem::structure {
namespace {

constexpr double kTolerance = 1e-6;
// Relative step of the central differences: truncation O(step^2), round-off O(1e-16 / step).
constexpr double kRelativeStep = 1e-5;

double check(const Eigen::MatrixXd& ddm, const Eigen::MatrixXd& fd, const std::string& what) {
  const double error = max_relative_error(ddm, fd);
  EXPECT_LT(error, kTolerance) << what << "\nDDM\n" << ddm << "\nFD\n" << fd;
  return error;
}

Eigen::MatrixXd dense(const StructureModel& m,
                      void (StructureModel::*add)(const AddEntry&, double) const) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m.num_dofs(), m.num_dofs());
  (m.*add)([&K](int i, int j, double v) { K(i, j) += v; }, 1.0);
  return K;
}

// ---------------------------------------------------------------------------------------------
// A horizontal cantilever of 4 corotational displacement-based elements (3 Gauss points),
// clamped at node 0. theta = (width, depth, E0, Fy, b) of a 10-fiber bilinear rectangle.
enum { kWidth, kDepth, kE0, kFy, kHardening, kNumParameters };
const std::vector<double> kTheta{0.05, 0.05, 1000.0, 5.0, 0.03};
constexpr int kElements = 4;
constexpr double kLength = 1.0;

StructureModel cantilever(const std::vector<double>& t) {
  BilinearMaterial steel(t[kFy], t[kE0], t[kHardening]);
  steel.set_parameter_seed(kFy, {1.0, 0.0, 0.0});
  steel.set_parameter_seed(kE0, {0.0, 1.0, 0.0});
  steel.set_parameter_seed(kHardening, {0.0, 0.0, 1.0});
  FiberSection section(steel, {t[kWidth], t[kDepth], 10});
  section.set_geometry_seed(kWidth, {1.0, 0.0});
  section.set_geometry_seed(kDepth, {0.0, 1.0});
  StructureModel m;
  for (int n = 0; n <= kElements; ++n) m.add_node(kLength * n / kElements, 0.0);
  m.fix(0, true, true, true);
  BeamOptions o;
  o.transf = TransfKind::kCorotational;
  for (int e = 0; e < kElements; ++e) m.add_disp_beam(e, e + 1, section, o, 3);
  m.set_num_parameters(kNumParameters);
  return m;
}

// Sets the tip load (a transverse load factor times the first-yield load My / L, with a
// constant axial compression) and solves by Newton to machine precision (the finite
// differences divide by a small step).
void solve_step(StructureModel& m, const FreeDofs& dofs, double load_factor) {
  const double My = kTheta[kFy] * kTheta[kWidth] * kTheta[kDepth] * kTheta[kDepth] / 6.0;
  m.set_nodal_load(kElements, -0.2 * My / kLength, load_factor * My / kLength);
  const Eigen::VectorXd f = dofs.restrict(m.external_load());
  Eigen::VectorXd u = dofs.restrict(m.committed_displacement());
  for (int it = 0; it < 40; ++it) {
    m.set_trial_displacement(dofs.expand(u));
    const Eigen::VectorXd r = f - dofs.restrict(m.resisting_force());
    const Eigen::VectorXd du = solve_free(
        dofs, [&](const AddEntry& add) { m.add_tangent(add); }, r);
    u += du;
    if (du.norm() <= 1e-15 * u.norm()) break;
  }
  m.set_trial_displacement(dofs.expand(u));
  ASSERT_LT((f - dofs.restrict(m.resisting_force())).norm(), 1e-12 * f.norm());
}

// Load factors: elastic, yielding, unloading, reverse yielding.
const std::vector<double> kLoadFactors{0.4, 0.8, 1.0,  1.1,  1.2,  1.3, 1.1,
                                       0.6, 0.0, -0.6, -1.0, -1.2, -1.3};

// Per step: tip (ux, uy, rz), basic forces of the clamped element, stress and strain of the
// outermost fiber at its first Gauss point. With sensitivities: their DDM derivatives, one
// column per parameter.
struct PathResult {
  Eigen::VectorXd response;
  Eigen::MatrixXd sensitivity;
  int plastic_steps = 0;
};

PathResult run_path(const std::vector<double>& t, bool ddm) {
  StructureModel m = cantilever(t);
  const FreeDofs dofs(m);
  const int steps = static_cast<int>(kLoadFactors.size());
  PathResult out{Eigen::VectorXd(8 * steps), Eigen::MatrixXd(8 * steps, kNumParameters)};
  const auto& beam = dynamic_cast<const DispBeamColumn2d&>(m.element(0));
  const auto& fiber = dynamic_cast<const FiberSection&>(beam.section(0)).fiber_material(0);
  const int tip = 3 * kElements;
  for (int s = 0; s < steps; ++s) {
    solve_step(m, dofs, kLoadFactors[s]);
    out.response.segment<8>(8 * s) << m.trial_displacement().segment<3>(tip), beam.basic_force(),
        fiber.stress(), fiber.strain();
    out.plastic_steps += dynamic_cast<const BilinearMaterial&>(fiber).is_plastic();
    for (int k = 0; ddm && k < kNumParameters; ++k) {
      const Eigen::VectorXd rhs = -dofs.restrict(m.resisting_force_sensitivity(k));  // dF_ext = 0
      const Eigen::VectorXd du = dofs.expand(solve_free(
          dofs, [&](const AddEntry& add) { m.add_tangent(add); }, rhs));
      m.set_displacement_sensitivity(k, du);
      out.sensitivity.col(k).segment<8>(8 * s) << du.segment<3>(tip),
          beam.basic_force_sensitivity(k), fiber.stress_sensitivity(k), fiber.strain_sensitivity(k);
    }
    m.commit();
  }
  return out;
}

TEST(StructureModelSensitivity, TangentIsTheDerivativeOfTheForceAfterYielding) {
  StructureModel m = cantilever(kTheta);
  const FreeDofs dofs(m);
  for (double factor : {0.4, 0.8, 1.0, 1.1, 1.2}) {
    solve_step(m, dofs, factor);
    m.commit();
  }
  const Eigen::VectorXd u = m.committed_displacement() + 0.05 * m.committed_displacement();
  m.set_trial_displacement(u);
  const Eigen::MatrixXd K = dense(m, &StructureModel::add_tangent);
  const Eigen::MatrixXd fd = central_difference_jacobian(
      [&](const Eigen::VectorXd& x) {
        m.set_trial_displacement(x);
        return m.resisting_force();
      },
      u, 1e-7);
  std::cout << "max relative error " << check(K, fd, "tangent") << "\n";
}

TEST(StructureModelSensitivity, StaticPathFollowingMatchesWholeReRuns) {
  const PathResult ddm = run_path(kTheta, true);
  ASSERT_GE(ddm.plastic_steps, 4);
  double worst = 0.0;
  for (int k = 0; k < kNumParameters; ++k) {
    const double h = kRelativeStep * kTheta[k];
    std::vector<double> plus = kTheta, minus = kTheta;
    plus[k] += h;
    minus[k] -= h;
    const Eigen::VectorXd fd =
        (run_path(plus, false).response - run_path(minus, false).response) / (2 * h);
    const double error = check(ddm.sensitivity.col(k), fd, "parameter " + std::to_string(k));
    std::cout << "parameter " << k << " max relative error " << error << "\n";
    worst = std::max(worst, error);
  }
  std::cout << "max relative error " << worst << "\n";
}

}  // namespace
}  // namespace pfem::structure

// ---------------------------------------------------------------------------------------------
namespace pfem {
namespace {

// Three beams: "flex" elastic on a rectangle of the elastic material "soft"; "plastic"
// displacement-based on a rectangle of the bilinear "steel" (consistent mass); "arm" elastic on
// an elastic section. Rayleigh damping on M and K0.
constexpr const char* kFrame = R"({
  "structure": {
    "nodes": [
      {"name": "base", "x": 0.0, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
      {"name": "mid", "x": 0.0, "y": 0.1},
      {"name": "tip", "x": 0.0, "y": 0.2, "mass": {"x": 0.01, "y": 0.01}},
      {"name": "side", "x": 0.1, "y": 0.25}
    ],
    "materials": [
      {"name": "soft", "elastic": {"e": 1.0e6}},
      {"name": "steel", "bilinear": {"fy": 2.0e3, "e0": 2.0e6, "hardening_ratio": 0.02}}
    ],
    "sections": [
      {"name": "rect", "fiber_rectangle": {"width": 0.012, "depth": 0.015, "fibers": 10, "material": "soft"}},
      {"name": "fib", "fiber_rectangle": {"width": 0.01, "depth": 0.02, "fibers": 20, "material": "steel"}},
      {"name": "el", "elastic": {"e": 1.5e6, "area": 2.0e-4, "inertia": 5.0e-9}}
    ],
    "beams": [
      {"name": "flex", "from_node": "base", "to_node": "mid", "elements": 2, "section": "rect",
       "rho": 2500.0, "element_type": "elastic"},
      {"name": "plastic", "from_node": "mid", "to_node": "tip", "elements": 2, "section": "fib",
       "rho": 7800.0, "element_type": "displacement-based", "mass": "consistent", "integration_points": 3},
      {"name": "arm", "from_node": "tip", "to_node": "side", "elements": 1, "section": "el",
       "rho": 1000.0, "element_type": "elastic", "transformation": "linear"}
    ],
    "rayleigh": {"a0": 0.3, "a1": 0.002}
  }
})";

const std::vector<std::vector<SeedTarget>> kTargets{
    {{"material.soft.e"}, {"material.steel.e"}},  // one parameter, two materials
    {{"section.rect.width"}},                     // elastic beams from a rectangle: A, I
    {{"section.fib.depth"}, {"fluid.rho"}},       // the fluid target is not the structure's
    {{"material.steel.fy"}},
    {{"material.steel.hardening_ratio"}},
    {{"section.el.e"}},
    {{"section.el.area"}},
    {{"section.el.inertia"}},
    {{"beam.plastic.rho"}, {"beam.arm.rho"}},
    {{"section.rect.depth"}, {"section.rect.width"}}};

// A displacement of every dof that yields the steel (the clamped base at 0).
Eigen::VectorXd frame_displacement(const structure::StructureModel& m) {
  Eigen::VectorXd u(m.num_dofs());
  for (int n = 0; n < m.num_nodes(); ++n) {
    const double x = m.node(n).x(0), y = m.node(n).x(1);
    u.segment<3>(3 * n) << 0.4 * y * y + 0.02 * x, -0.3 * x * y + 0.001 * y, 0.8 * y + 0.2 * x;
  }
  return u;
}

TEST(StructureBuilderSensitivity, SeedsFromTargetsMatchRebuiltModels) {
  const pfem::v1::Model model = parse_model_json(kFrame);
  const StructureBuild build = build_structure(model, parameter_seeds(model, kTargets));
  structure::StructureModel m = build.model;
  ASSERT_EQ(m.num_parameters(), static_cast<int>(kTargets.size()));
  const Eigen::VectorXd u = frame_displacement(m);
  m.set_trial_displacement(u);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(m.num_dofs(), -1.0, 2.0);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(m.num_dofs(), 0.5, -1.5);

  const auto rebuilt = [&](int k, double shift) {
    pfem::v1::Model changed = model;
    for (const auto& seed : kTargets[k])
      set_model_target(changed, seed.target, model_target_value(model, seed.target) + shift);
    structure::StructureModel r = build_structure(changed).model;
    r.set_trial_displacement(u);
    Eigen::MatrixXd out(m.num_dofs(), 3);
    out << r.resisting_force(), r.mass_times(a), r.damping_times(v);
    return out;
  };
  double worst = 0.0;
  for (int k = 0; k < m.num_parameters(); ++k) {
    double h = 1e300;
    for (const auto& seed : kTargets[k])
      if (seed.target != "fluid.rho")
        h = std::min(h, structure::kRelativeStep * model_target_value(model, seed.target));
    const Eigen::MatrixXd fd = (rebuilt(k, h) - rebuilt(k, -h)) / (2 * h);
    const std::string what = "parameter " + std::to_string(k);
    EXPECT_GT(fd.col(0).norm() + fd.col(1).norm(), 0.0) << what;  // every parameter acts
    worst = std::max(
        {worst, structure::check(m.resisting_force_sensitivity(k), fd.col(0), what + " force"),
         structure::check(m.mass_sensitivity_times(k, a), fd.col(1), what + " mass"),
         structure::check(m.damping_sensitivity_times(k, v), fd.col(2), what + " damping")});
  }
  std::cout << "max relative error " << worst << "\n";
}

// A directional parameter's seeds: every target of kTargets[k] with weight w_k, in one
// parameter. Its force, mass and damping sensitivities are sum_k w_k of kTargets[k]'s (the
// seeds enter linearly), to rounding.
TEST(StructureBuilderSensitivity, WeightedSeedsGiveTheWeightedSumOfTheSensitivities) {
  const pfem::v1::Model model = parse_model_json(kFrame);
  const std::vector<double> w = {0.7, -2.5, 1e-3, 4.0, -0.3, 1.5, 0.0, -1.25, 3.0, 0.2};
  ASSERT_EQ(w.size(), kTargets.size());
  std::vector<SeedTarget> combined;
  for (std::size_t k = 0; k < kTargets.size(); ++k)
    for (const auto& seed : kTargets[k]) combined.push_back({seed.target, w[k]});
  structure::StructureModel each = build_structure(model, parameter_seeds(model, kTargets)).model;
  structure::StructureModel one = build_structure(model, parameter_seeds(model, {combined})).model;
  ASSERT_EQ(one.num_parameters(), 1);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(each.num_dofs(), -1.0, 2.0);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(each.num_dofs(), 0.5, -1.5);
  for (auto* m : {&each, &one}) m->set_trial_displacement(frame_displacement(*m));
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(each.num_dofs(), 3);
  for (int k = 0; k < each.num_parameters(); ++k) {
    expected.col(0) += w[k] * each.resisting_force_sensitivity(k);
    expected.col(1) += w[k] * each.mass_sensitivity_times(k, a);
    expected.col(2) += w[k] * each.damping_sensitivity_times(k, v);
  }
  Eigen::MatrixXd got(one.num_dofs(), 3);
  got << one.resisting_force_sensitivity(0), one.mass_sensitivity_times(0, a),
      one.damping_sensitivity_times(0, v);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(expected.col(c).norm(), 0.0) << c;
    EXPECT_LE((got.col(c) - expected.col(c)).norm(), 1e-13 * expected.col(c).norm()) << c;
  }
}

TEST(StructureBuilderSensitivity, NoTargetsNoParameters) {
  EXPECT_EQ(build_structure(parse_model_json(kFrame)).model.num_parameters(), 0);
}

}  // namespace
}  // namespace pfem
