// model.structure -> StructureModel: a cantilever given as JSON reaches the structural library
// intact (node names and positions, supports, masses, and a static tip deflection equal to
// P L^3 / (3 EI)); bad input is reported with the exact field path; parameter targets set the
// values the builder uses; the sloshing-beam example validates, and its recorders and
// parameters resolve against the structure's names.
#include "engine/io/structure_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "engine/io/model_checks.h"
#include "engine/io/model_io.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/elastic_beam_column.h"
#include "engine/structure/fiber_section.h"
#include "engine/structure/static_solver.h"

namespace pfem {
namespace {

std::string source(const std::string& relative) { return std::string(PFEM_SOURCE_DIR) + "/" + relative; }

// The paper's beam (theory.md section 7): L = 0.1 m, b = d = 0.012 m, E = 1 MPa, rho_s = 2500.
constexpr double kL = 0.1, kB = 0.012, kE = 1.0e6, kRho = 2500.0;
constexpr double kA = kB * kB;
constexpr double kI = kB * kB * kB * kB / 12.0;
constexpr double kTipMass = 0.01;  // nodal mass at the tip [kg], in x and y

// A vertical cantilever from "base" (0, 0), clamped, to "tip" (0, L), of n elements.
//   elastic: elastic beam-columns on a fiber_rectangle of the elastic material "soft"
//   fiber:   displacement-based, 2 Gauss points, 50 fibers of the bilinear material "steel"
std::string cantilever_json(bool fiber, int n) {
  const std::string section =
      fiber ? R"("fibers": 50, "material": "steel")" : R"("fibers": 10, "material": "soft")";
  const std::string beam =
      fiber ? R"("element_type": "displacement-based", "transformation": "linear", "integration_points": 2)"
            : R"("element_type": "elastic")";
  return R"({
  "structure": {
    "nodes": [
      {"name": "base", "x": 0.0, "y": 0.0, "support": {"ux": true, "uy": true, "rz": true}},
      {"name": "tip", "x": 0.0, "y": 0.1, "mass": {"x": 0.01, "y": 0.01}}
    ],
    "materials": [
      {"name": "soft", "elastic": {"e": 1.0e6}},
      {"name": "steel", "bilinear": {"fy": 5.0e4, "e0": 1.0e6, "hardening_ratio": 0.02}}
    ],
    "sections": [
      {"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.012, )" +
         section + R"(}}
    ],
    "beams": [
      {"name": "beam", "from_node": "base", "to_node": "tip", "elements": )" +
         std::to_string(n) + R"(,
       "section": "square", "rho": 2500.0, )" +
         beam + R"(}
    ]
  }
})";
}

pfem::v1::Model cantilever(bool fiber, int n = 10) { return parse_model_json(cantilever_json(fiber, n)); }

// Static tip deflection in x under a tip load P in x.
double tip_deflection(const pfem::v1::Model& model, double P) {
  auto build = build_structure(model);
  const int tip = build.node_index.at("tip");
  build.model.set_nodal_load(tip, P, 0.0);
  const auto summary = structure::solve_static(build.model);
  EXPECT_TRUE(summary.converged) << summary.message;
  return build.model.committed_displacement()(3 * tip);
}

std::string describe(const std::vector<FieldError>& errors) {
  std::string out;
  for (const auto& e : errors) out += "\n  " + e.to_string();
  return out.empty() ? " (none)" : out;
}

void expect_single_error(const std::vector<FieldError>& errors, const std::string& path,
                         const std::string& message) {
  ASSERT_EQ(errors.size(), 1u) << "errors:" << describe(errors);
  EXPECT_EQ(errors[0].path, path);
  EXPECT_EQ(errors[0].message, message);
}

// build_structure must throw ModelError with exactly this one error.
void expect_build_error(const pfem::v1::Model& model, const std::string& path, const std::string& message) {
  try {
    build_structure(model);
    ADD_FAILURE() << "no error; expected " << path << ": " << message;
  } catch (const ModelError& e) {
    expect_single_error(e.errors(), path, message);
  }
}

// ---------------------------------------------------------------------------------------------
// The cantilever reaches the library intact.

TEST(StructureBuilder, CantileverNodesNamesSupportsAndMasses) {
  const int n = 10;
  const auto build = build_structure(cantilever(false, n));
  const auto& m = build.model;
  ASSERT_EQ(m.num_nodes(), n + 1);
  ASSERT_EQ(m.num_elements(), n);
  EXPECT_EQ(build.node_index.at("base"), 0);
  EXPECT_EQ(build.node_index.at("tip"), 1);
  ASSERT_EQ(build.beam_nodes.size(), 1u);
  ASSERT_EQ(build.beam_nodes[0].size(), static_cast<std::size_t>(n + 1));
  EXPECT_EQ(build.beam_nodes[0].front(), 0);
  EXPECT_EQ(build.beam_nodes[0].back(), 1);
  for (int k = 1; k < n; ++k) {
    const std::string name = "beam/" + std::to_string(k);
    ASSERT_EQ(build.node_index.count(name), 1u) << name;
    const int node = build.node_index.at(name);
    EXPECT_EQ(build.beam_nodes[0][k], node);
    EXPECT_EQ(build.node_names[node], name);
    EXPECT_DOUBLE_EQ(m.node(node).x(0), 0.0);
    EXPECT_NEAR(m.node(node).x(1), kL * k / n, 1e-15);
  }
  EXPECT_EQ(build.node_index.count("beam/0"), 0u);
  EXPECT_EQ(build.node_index.count("beam/" + std::to_string(n)), 0u);
  for (int k = 1; k <= n; ++k) {
    const int e = build.element_index.at("beam/" + std::to_string(k));
    EXPECT_EQ(build.beam_elements[0][k - 1], e);
    EXPECT_EQ(m.element(e).nodes()[0], build.beam_nodes[0][k - 1]);
    EXPECT_EQ(m.element(e).nodes()[1], build.beam_nodes[0][k]);
    const auto* beam = dynamic_cast<const structure::ElasticBeamColumn2d*>(&m.element(e));
    ASSERT_NE(beam, nullptr);
    EXPECT_EQ(beam->transformation().kind(), structure::TransfKind::kCorotational);  // the default
    EXPECT_DOUBLE_EQ(beam->section().E, kE);
    EXPECT_DOUBLE_EQ(beam->section().A, kA);
    EXPECT_DOUBLE_EQ(beam->section().I, kI);
  }
  for (int dof = 0; dof < m.num_dofs(); ++dof) EXPECT_EQ(m.is_fixed(dof), dof < 3) << "dof " << dof;

  ASSERT_TRUE(m.mass_is_lumped());
  const Eigen::VectorXd mass = m.lumped_mass();
  double mx = 0.0, my = 0.0, mrz = 0.0;
  for (int node = 0; node < m.num_nodes(); ++node)
    mx += mass(3 * node), my += mass(3 * node + 1), mrz += mass(3 * node + 2);
  EXPECT_NEAR(mx, kRho * kA * kL + kTipMass, 1e-15);
  EXPECT_NEAR(my, kRho * kA * kL + kTipMass, 1e-15);
  EXPECT_EQ(mrz, 0.0);
}

TEST(StructureBuilder, ElasticCantileverTipDeflectionIsPL3Over3EI) {
  const double P = 1e-4 * 3.0 * kE * kI / (kL * kL * kL);  // delta / L = 1e-4
  const double closed_form = P * kL * kL * kL / (3.0 * kE * kI);
  const double delta = tip_deflection(cantilever(false), P);
  EXPECT_NEAR(delta / closed_form, 1.0, 0.005);
}

TEST(StructureBuilder, FiberCantileverTipDeflectionIsPL3Over3EI) {
  const auto model = cantilever(true);
  const auto build = build_structure(model);
  const auto* beam = dynamic_cast<const structure::DispBeamColumn2d*>(&build.model.element(0));
  ASSERT_NE(beam, nullptr);
  EXPECT_EQ(beam->num_integration_points(), 2);
  EXPECT_EQ(beam->transformation().kind(), structure::TransfKind::kLinear);
  const auto* section = dynamic_cast<const structure::FiberSection*>(&beam->section(0));
  ASSERT_NE(section, nullptr);
  EXPECT_EQ(section->num_fibers(), 50);

  const double P = 1e-4 * 3.0 * kE * kI / (kL * kL * kL);  // far below yield (sigma ~ 100 Pa)
  const double closed_form = P * kL * kL * kL / (3.0 * kE * kI);
  EXPECT_NEAR(tip_deflection(model, P) / closed_form, 1.0, 0.005);  // EI_50 = EI (1 - 1/2500)
}

TEST(StructureBuilder, NoStructureGivesAnEmptyBuild) {
  const auto build = build_structure(read_model_file(source("examples/hydrostatic.json")));
  EXPECT_EQ(build.model.num_nodes(), 0);
  EXPECT_TRUE(build.node_index.empty());
}

// ---------------------------------------------------------------------------------------------
// Bad input: one error each, at its field path.

TEST(StructureBuilderErrors, BeamWithZeroLength) {
  auto m = cantilever(false);
  m.mutable_structure()->mutable_nodes(1)->set_y(0.0);
  expect_build_error(m, "structure.beams[0]", "has zero length");
}

TEST(StructureBuilderErrors, FiberSectionWithZeroFibers) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_sections(0)->mutable_fiber_rectangle()->set_fibers(0);
  expect_build_error(m, "structure.sections[0].fiber_rectangle.fibers", "must be >= 1");
}

TEST(StructureBuilderErrors, HardeningRatioOutsideZeroOne) {
  for (double b : {1.0, -0.1, 1.5}) {
    auto m = cantilever(true);
    m.mutable_structure()->mutable_materials(1)->mutable_bilinear()->set_hardening_ratio(b);
    expect_build_error(m, "structure.materials[1].bilinear.hardening_ratio", "must be in [0, 1)");
  }
  auto m = cantilever(true);
  m.mutable_structure()->mutable_materials(1)->mutable_bilinear()->set_hardening_ratio(0.0);
  EXPECT_NO_THROW(build_structure(m));  // perfectly plastic is allowed
}

TEST(StructureBuilderErrors, NonPositiveValues) {
  struct Case {
    void (*edit)(pfem::v1::Structure&);
    const char* path;
  };
  const Case cases[] = {
      {[](auto& s) { s.mutable_materials(1)->mutable_bilinear()->set_fy(-3.0); },
       "structure.materials[1].bilinear.fy"},
      {[](auto& s) { s.mutable_materials(1)->mutable_bilinear()->set_e0(0.0); },
       "structure.materials[1].bilinear.e0"},
      {[](auto& s) { s.mutable_materials(0)->mutable_elastic()->set_e(0.0); },
       "structure.materials[0].elastic.e"},
      {[](auto& s) { s.mutable_sections(0)->mutable_fiber_rectangle()->set_width(0.0); },
       "structure.sections[0].fiber_rectangle.width"},
      {[](auto& s) { s.mutable_sections(0)->mutable_fiber_rectangle()->set_depth(-1.0); },
       "structure.sections[0].fiber_rectangle.depth"},
      {[](auto& s) { s.mutable_beams(0)->set_rho(0.0); }, "structure.beams[0].rho"},
      {[](auto& s) {
         auto* e = s.add_sections();
         e->set_name("props");
         e->mutable_elastic()->set_e(1e6);
         e->mutable_elastic()->set_area(-1e-4);
         e->mutable_elastic()->set_inertia(1e-9);
       },
       "structure.sections[1].elastic.area"},
  };
  for (const auto& c : cases) {
    auto m = cantilever(true);
    c.edit(*m.mutable_structure());
    expect_build_error(m, c.path, "must be > 0");
  }
}

TEST(StructureBuilderErrors, ElementCountAndIntegrationPoints) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_elements(0);
  expect_build_error(m, "structure.beams[0].elements", "must be >= 1");
  m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_integration_points(11);
  expect_build_error(m, "structure.beams[0].integration_points", "must be in 1..10");
}

TEST(StructureBuilderErrors, UnknownNames) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_to_node("top");
  const auto errors = validate_structure(m);  // "tip" is then left unconnected, and said so
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_EQ(errors[0].to_string(), "structure.nodes[1]: is not connected to any beam");
  EXPECT_EQ(errors[1].to_string(), "structure.beams[0].to_node: unknown node 'top'");
  m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_section("round");
  expect_build_error(m, "structure.beams[0].section", "unknown section 'round'");
  m = cantilever(true);
  m.mutable_structure()->mutable_sections(0)->mutable_fiber_rectangle()->set_material("wood");
  expect_build_error(m, "structure.sections[0].fiber_rectangle.material", "unknown material 'wood'");
  m = cantilever(true);  // a beam ends at named nodes, not at generated ones
  auto* second = m.mutable_structure()->add_beams();
  *second = m.structure().beams(0);
  second->set_name("brace");
  second->set_from_node("beam/3");
  expect_build_error(
      m, "structure.beams[1].from_node",
      "unknown node 'beam/3' (a beam must end at a named structure node, not at a generated one)");
}

TEST(StructureBuilderErrors, DuplicateAndMalformedNames) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_materials(0)->set_name("steel");  // the first "steel" is the one used
  expect_build_error(m, "structure.materials[1].name", "'steel' is used twice");
  m = cantilever(true);
  m.mutable_structure()->mutable_nodes(1)->set_name("tip/1");
  m.mutable_structure()->mutable_beams(0)->set_to_node("tip/1");
  const auto errors = validate_structure(m);
  ASSERT_GE(errors.size(), 1u);
  EXPECT_EQ(errors[0].to_string(),
            "structure.nodes[1].name: must use only letters, digits, '_' and '-' (got 'tip/1')");
  m = cantilever(true);
  m.mutable_structure()->mutable_sections(0)->clear_name();
  m.mutable_structure()->mutable_beams(0)->set_section("");
  const auto missing = validate_structure(m);
  ASSERT_EQ(missing.size(), 2u) << describe(missing);
  EXPECT_EQ(missing[0].to_string(), "structure.sections[0].name: is required");
  EXPECT_EQ(missing[1].to_string(), "structure.beams[0].section: is required");
}

TEST(StructureBuilderErrors, UnknownKinds) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_element_type("timoshenko");
  expect_build_error(m, "structure.beams[0].element_type",
                     "unknown element type 'timoshenko'; expected elastic or displacement-based");
  m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_transformation("pdelta");
  expect_build_error(m, "structure.beams[0].transformation",
                     "unknown transformation 'pdelta'; expected corotational or linear");
  m = cantilever(true);
  m.mutable_structure()->mutable_beams(0)->set_mass("diagonal");
  expect_build_error(m, "structure.beams[0].mass", "unknown mass 'diagonal'; expected lumped or consistent");
  m = cantilever(true);
  m.mutable_structure()->mutable_materials(0)->clear_elastic();
  expect_build_error(m, "structure.materials[0]", "needs a kind: elastic or bilinear");
  m = cantilever(true);  // an elastic beam on fibers of a plastic material
  m.mutable_structure()->mutable_beams(0)->set_element_type("elastic");
  m.mutable_structure()->mutable_beams(0)->clear_integration_points();
  expect_build_error(m, "structure.beams[0].section",
                     "an elastic beam needs an elastic section or a fiber_rectangle of an elastic material; "
                     "section 'square' uses material 'steel', which is not elastic");
}

TEST(StructureBuilderErrors, UnconnectedNode) {
  auto m = cantilever(true);
  auto* loose = m.mutable_structure()->add_nodes();
  loose->set_name("loose");
  expect_build_error(m, "structure.nodes[2]", "is not connected to any beam");
}

TEST(StructureBuilderErrors, EveryErrorIsReported) {
  auto m = cantilever(true);
  m.mutable_structure()->mutable_materials(1)->mutable_bilinear()->set_fy(-3.0);
  m.mutable_structure()->mutable_beams(0)->set_elements(0);
  try {
    build_structure(m);
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_EQ(std::string(e.what()),
              "structure.materials[1].bilinear.fy: must be > 0\nstructure.beams[0].elements: must be >= 1");
  }
}

// ---------------------------------------------------------------------------------------------
// Parameters: targets resolve to components and set the values the builder uses.

TEST(StructureParameters, TargetSetsTheBuiltValue) {
  auto m = cantilever(false);
  EXPECT_DOUBLE_EQ(model_target_value(m, "material.soft.e"), kE);
  const double P = 1e-4 * 3.0 * kE * kI / (kL * kL * kL);
  const double before = tip_deflection(m, P);
  set_model_target(m, "material.soft.e", 2.0 * kE);
  EXPECT_DOUBLE_EQ(m.structure().materials(0).elastic().e(), 2.0 * kE);
  const auto build = build_structure(m);
  EXPECT_DOUBLE_EQ(dynamic_cast<const structure::ElasticBeamColumn2d&>(build.model.element(0)).section().E,
                   2.0 * kE);
  EXPECT_NEAR(tip_deflection(m, P) / before, 0.5, 1e-6);

  set_model_target(m, "beam.beam.rho", 1000.0);
  const double mx = build_structure(m).model.lumped_mass()(3);  // the tip: half an element + nodal mass
  EXPECT_NEAR(mx, 1000.0 * kA * kL / 10 / 2 + kTipMass, 1e-15);

  auto f = cantilever(true);
  set_model_target(f, "material.steel.e", 3e6);
  set_model_target(f, "material.steel.fy", 6e4);
  set_model_target(f, "material.steel.hardening_ratio", 0.1);
  const auto& b = f.structure().materials(1).bilinear();
  EXPECT_EQ(b.e0(), 3e6);
  EXPECT_EQ(b.fy(), 6e4);
  EXPECT_EQ(b.hardening_ratio(), 0.1);
}

TEST(StructureParameters, OneParameterSetsSectionWidthAndThickness) {
  auto m = cantilever(false);
  EXPECT_EQ(model_target_value(m, "thickness"), 1.0);  // the default
  auto* p = m.add_parameters();
  p->set_name("b");
  p->add_targets("section.square.width");
  p->add_targets("thickness");
  p->set_value(0.02);
  EXPECT_TRUE(validate_structure(m).empty());
  apply_parameter_overrides(m);
  EXPECT_EQ(m.thickness(), 0.02);
  EXPECT_EQ(m.structure().sections(0).fiber_rectangle().width(), 0.02);
  const auto build = build_structure(m);
  EXPECT_DOUBLE_EQ(dynamic_cast<const structure::ElasticBeamColumn2d&>(build.model.element(0)).section().A,
                   0.02 * kB);
}

// ---------------------------------------------------------------------------------------------
// The sloshing-beam example: validates; recorders and parameters resolve against its names.

pfem::v1::Model sloshing() { return read_model_file(source("examples/sloshing-beam.json")); }

pfem::v1::Recorder& add_recorder(pfem::v1::Model& m, const std::string& quantity) {
  auto* r = m.add_recorders();
  r->set_name("extra");
  r->set_quantity(quantity);
  return *r;
}

std::string last_recorder(const pfem::v1::Model& m, const std::string& field = "") {
  return "recorders[" + std::to_string(m.recorders_size() - 1) + "]" + field;
}

TEST(SloshingBeam, ExampleValidates) {
  const auto m = sloshing();
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
  const auto build = build_structure(m);
  EXPECT_EQ(build.model.num_nodes(), 41);
  EXPECT_EQ(build.model.num_elements(), 40);
}

// Beam elements much longer than the particle spacing would let water through between their
// nodes: an error naming the count that would do (the example's 40 elements are one h each).
TEST(SloshingBeam, ElementsLongerThanOneAndAHalfSpacingsAreRefused) {
  auto m = sloshing();  // beam 0.1 m, mesh.h 0.0025 m
  m.mutable_structure()->mutable_beams(0)->set_elements(26);  // 1.54 h
  expect_single_error(validate_model(m), "structure.beams[0].elements",
                      "gives elements of 0.00384615 m, longer than 1.5 mesh.h: water would pass between the "
                      "beam's nodes; use at least 27");
  m.mutable_structure()->mutable_beams(0)->set_elements(27);  // 1.48 h
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
}

// A beam may stand on a wall (its base on the floor) but not cross a wall or another beam, nor
// lie along a wall; an elastic beam has no integration points; a recorder point must lie in the
// domain.
TEST(SloshingBeam, BeamsCrossingWallsOrBeamsAndStrayOptionsAreRefused) {
  const auto with_beam = [](double x0, double y0, double x1, double y1) {
    auto m = sloshing();  // tank walls x = 0 and y = 0 up to x = 0.1; beam x = 0.1 from y = 0 to 0.1
    auto* st = m.mutable_structure();
    for (const auto& [name, x, y] : {std::tuple{"a", x0, y0}, std::tuple{"b", x1, y1}}) {
      auto* n = st->add_nodes();
      n->set_name(name), n->set_x(x), n->set_y(y);
    }
    auto* b = st->add_beams();
    *b = st->beams(0);
    b->set_name("second"), b->set_from_node("a"), b->set_to_node("b");
    return m;
  };
  expect_single_error(validate_model(with_beam(0.05, 0.05, 0.15, 0.05)), "structure.beams[0]",
                      "crosses structure.beams[1]");
  expect_single_error(validate_model(with_beam(-0.02, 0.05, 0.05, 0.05)), "structure.beams[1]", "crosses walls[0]");
  expect_single_error(validate_model(with_beam(0.02, 0.0, 0.06, 0.0)), "structure.beams[1]", "lies along walls[0]");
  EXPECT_TRUE(validate_model(with_beam(0.05, 0.0, 0.05, 0.04)).empty());  // standing on the floor
  EXPECT_TRUE(validate_model(with_beam(0.1, 0.1, 0.14, 0.1)).empty());    // on the first beam's tip

  auto m = sloshing();
  m.mutable_structure()->mutable_beams(0)->set_integration_points(3);
  expect_single_error(validate_model(m), "structure.beams[0].integration_points",
                      "is for displacement-based beams (an elastic beam has none)");
  m = sloshing();
  auto* r = m.add_recorders();
  r->set_name("far"), r->set_quantity("p");
  r->mutable_point()->set_x(0.5), r->mutable_point()->set_y(0.0);
  expect_single_error(validate_model(m), "recorders[2].point", "lies outside the domain");
}

TEST(SloshingBeam, RecorderNodesResolveAgainstStructureNames) {
  auto m = sloshing();
  add_recorder(m, "uy").set_node("beam/39");
  add_recorder(m, "rz").set_node("tip");
  m.mutable_recorders(m.recorders_size() - 1)->set_name("tip_rz");
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));

  for (const char* missing : {"beam/40", "beam/0", "beam/01", "pole/3", "beam_tip"}) {
    auto bad = sloshing();
    add_recorder(bad, "ux").set_node(missing);
    expect_single_error(validate_model(bad), last_recorder(bad, ".node"),
                        "unknown node '" + std::string(missing) + "'");
  }
  auto bad = sloshing();
  auto& r = add_recorder(bad, "rz");
  r.mutable_point()->set_x(0.1);
  expect_single_error(validate_model(bad), last_recorder(bad, ".point"),
                      "quantity 'rz' needs a structure node (node), not a point");
  bad = sloshing();
  add_recorder(bad, "rz");
  expect_single_error(validate_model(bad), last_recorder(bad), "quantity 'rz' needs a target: node");
}

TEST(SloshingBeam, ElementRecorders) {
  auto m = sloshing();
  auto& force = add_recorder(m, "basic_force");
  force.set_element("beam/40");
  force.set_component(2);
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));

  force.set_element("beam/41");
  expect_single_error(validate_model(m), last_recorder(m, ".element"), "unknown element 'beam/41'");
  force.set_element("beam/1");
  force.set_component(3);
  expect_single_error(validate_model(m), last_recorder(m, ".component"),
                      "must be in 0..2 (0 = N, 1 = M_i, 2 = M_j) (got 3)");
  force.clear_element();
  expect_single_error(validate_model(m), last_recorder(m),
                      "quantity 'basic_force' needs a target: element (\"<beam>/<k>\")");

  auto elastic = sloshing();
  add_recorder(elastic, "fiber_stress").set_element("beam/1");
  expect_single_error(validate_model(elastic), last_recorder(elastic, ".element"),
                      "element 'beam/1' has no fibers: fiber_stress needs a displacement-based beam with a "
                      "fiber_rectangle section");

  auto fibers = sloshing();
  fibers.mutable_structure()->mutable_beams(0)->set_element_type("displacement-based");
  auto& strain = add_recorder(fibers, "fiber_strain");
  strain.set_element("beam/1");
  strain.set_section_point(1);
  strain.set_fiber(9);
  EXPECT_TRUE(validate_model(fibers).empty()) << describe(validate_model(fibers));
  strain.set_section_point(2);
  expect_single_error(validate_model(fibers), last_recorder(fibers, ".section_point"),
                      "must be in 0..1 (got 2)");
  strain.set_section_point(0);
  strain.set_fiber(10);
  expect_single_error(validate_model(fibers), last_recorder(fibers, ".fiber"), "must be in 0..9 (got 10)");
}

TEST(SloshingBeam, ParameterTargets) {
  auto m = sloshing();
  auto* p = m.add_parameters();
  p->set_name("linked");
  p->add_targets("section.square.width");
  p->add_targets("thickness");
  p->add_targets("beam.beam.rho");
  EXPECT_TRUE(validate_model(m).empty()) << describe(validate_model(m));
  const std::string path = "parameters[" + std::to_string(m.parameters_size() - 1) + "]";

  struct Case {
    const char* target;
    const char* message;
  };
  const Case cases[] = {
      {"material.steel.e", "unknown material 'steel' in target 'material.steel.e'"},
      {"material.soft.fy", "material 'soft' is elastic: it has no fy (only e)"},
      {"section.square.e",
       "section 'square' is a fiber_rectangle: it has no e (width or depth; E is its material's)"},
      {"beam.pole.rho", "unknown beam 'pole' in target 'beam.pole.rho'"},
      {"section.square.radius",
       "unknown target 'section.square.radius'; expected fluid.rho, fluid.mu, fluid.kappa, thickness, "
       "material.<name>.e|fy|hardening_ratio, section.<name>.width|depth|e|area|inertia, beam.<name>.rho "
       "or wavemaker.<wall>.stroke|period|height|scale"},
  };
  for (const auto& c : cases) {
    auto bad = m;
    bad.mutable_parameters(bad.parameters_size() - 1)->set_targets(0, c.target);
    expect_single_error(validate_model(bad), path + ".targets[0]", c.message);
  }
  auto twice = m;
  twice.mutable_parameters(twice.parameters_size() - 1)->add_targets("thickness");
  expect_single_error(validate_model(twice), path + ".targets[3]", "target 'thickness' is listed twice");
  auto negative = m;
  negative.mutable_parameters(negative.parameters_size() - 1)->set_value(-0.01);
  const auto errors = validate_model(negative);
  ASSERT_EQ(errors.size(), 3u) << describe(errors);
  EXPECT_EQ(errors[0].to_string(), path + ".value: must be > 0 for section.square.width");
  EXPECT_EQ(errors[1].to_string(), path + ".value: must be > 0 for thickness");
  EXPECT_EQ(errors[2].to_string(), path + ".value: must be > 0 for beam.beam.rho");
}

}  // namespace
}  // namespace pfem
