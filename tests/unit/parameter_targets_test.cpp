// The table of parameter targets (engine/io/parameter_targets.h): every target parses, reads
// and sets its own field of the model and nothing else, seeds its own constant, and gives the
// messages validation gives (unknown targets, a property the component's form lacks, ranges).
#include "engine/io/parameter_targets.h"

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <functional>

#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"

namespace pfem {
namespace {

using pfem::v1::Model;

// One component of every form, every value distinct (a row that reads another's field shows).
const char* kModel = R"({
  "thickness": 0.5,
  "fluid": {"rho": 1000.0, "mu": 0.001, "kappa": 2.15e9},
  "walls": [
    {"name": "floor", "points": [{"x": 0.0, "y": 0.0}, {"x": 1.0, "y": 0.0}]},
    {"name": "paddle", "points": [{"x": 0.0, "y": 0.0}, {"x": 0.0, "y": 0.3}],
     "motion": {"kind": "piston", "sinusoid": {"stroke": 0.02, "period": 1.5, "ramp": 1.0}}},
    {"name": "soliton", "points": [{"x": 1.0, "y": 0.0}, {"x": 1.0, "y": 0.3}],
     "motion": {"kind": "piston", "solitary": {"height": 0.03, "depth": 0.1}}},
    {"name": "tabled", "points": [{"x": 0.5, "y": 0.0}, {"x": 0.5, "y": 0.3}],
     "motion": {"kind": "piston", "table": {"t": [0.0, 1.0], "s": [0.0, 0.01], "scale": 2.5}}}
  ],
  "structure": {
    "materials": [{"name": "soft", "elastic": {"e": 1.0e6}},
                  {"name": "steel", "bilinear": {"fy": 5.0e4, "e0": 2.0e6, "hardening_ratio": 0.05}}],
    "sections": [{"name": "square", "fiber_rectangle": {"width": 0.012, "depth": 0.011, "fibers": 10,
                                                        "material": "soft"}},
                 {"name": "plate", "elastic": {"e": 3.0e6, "area": 0.004, "inertia": 2.0e-8}}],
    "beams": [{"name": "beam", "section": "square", "rho": 2500.0}]
  }
})";

Model model() { return parse_model_json(kModel); }

struct Case {
  std::string target;
  TargetRef parts;
  std::function<double(const Model&)> field;         // the field the target addresses
  std::function<double(const ParameterSeed&)> seed;  // the seed it sets
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all{
      {"fluid.rho",
       {"fluid", "", "rho"},
       [](const Model& m) { return m.fluid().rho(); },
       [](const ParameterSeed& s) { return s.fluid.rho; }},
      {"fluid.mu",
       {"fluid", "", "mu"},
       [](const Model& m) { return m.fluid().mu(); },
       [](const ParameterSeed& s) { return s.fluid.mu; }},
      {"fluid.kappa",
       {"fluid", "", "kappa"},
       [](const Model& m) { return m.fluid().kappa(); },
       [](const ParameterSeed& s) { return s.fluid.kappa; }},
      {"thickness",
       {"thickness", "", ""},
       [](const Model& m) { return m.thickness(); },
       [](const ParameterSeed& s) { return s.fluid.thickness; }},
      {"material.soft.e",
       {"material", "soft", "e"},
       [](const Model& m) { return m.structure().materials(0).elastic().e(); },
       [](const ParameterSeed& s) { return s.materials[0].e0; }},
      {"material.steel.e",
       {"material", "steel", "e"},
       [](const Model& m) { return m.structure().materials(1).bilinear().e0(); },
       [](const ParameterSeed& s) { return s.materials[1].e0; }},
      {"material.steel.fy",
       {"material", "steel", "fy"},
       [](const Model& m) { return m.structure().materials(1).bilinear().fy(); },
       [](const ParameterSeed& s) { return s.materials[1].fy; }},
      {"material.steel.hardening_ratio",
       {"material", "steel", "hardening_ratio"},
       [](const Model& m) { return m.structure().materials(1).bilinear().hardening_ratio(); },
       [](const ParameterSeed& s) { return s.materials[1].b; }},
      {"section.square.width",
       {"section", "square", "width"},
       [](const Model& m) { return m.structure().sections(0).fiber_rectangle().width(); },
       [](const ParameterSeed& s) { return s.sections[0].rectangle.width; }},
      {"section.square.depth",
       {"section", "square", "depth"},
       [](const Model& m) { return m.structure().sections(0).fiber_rectangle().depth(); },
       [](const ParameterSeed& s) { return s.sections[0].rectangle.depth; }},
      {"section.plate.e",
       {"section", "plate", "e"},
       [](const Model& m) { return m.structure().sections(1).elastic().e(); },
       [](const ParameterSeed& s) { return s.sections[1].elastic.E; }},
      {"section.plate.area",
       {"section", "plate", "area"},
       [](const Model& m) { return m.structure().sections(1).elastic().area(); },
       [](const ParameterSeed& s) { return s.sections[1].elastic.A; }},
      {"section.plate.inertia",
       {"section", "plate", "inertia"},
       [](const Model& m) { return m.structure().sections(1).elastic().inertia(); },
       [](const ParameterSeed& s) { return s.sections[1].elastic.I; }},
      {"beam.beam.rho",
       {"beam", "beam", "rho"},
       [](const Model& m) { return m.structure().beams(0).rho(); },
       [](const ParameterSeed& s) { return s.beam_rho[0]; }},
      {"wavemaker.paddle.stroke",
       {"wavemaker", "paddle", "stroke"},
       [](const Model& m) { return m.walls(1).motion().sinusoid().stroke(); },
       [](const ParameterSeed& s) { return s.walls[1].stroke; }},
      {"wavemaker.paddle.period",
       {"wavemaker", "paddle", "period"},
       [](const Model& m) { return m.walls(1).motion().sinusoid().period(); },
       [](const ParameterSeed& s) { return s.walls[1].period; }},
      {"wavemaker.soliton.height",
       {"wavemaker", "soliton", "height"},
       [](const Model& m) { return m.walls(2).motion().solitary().height(); },
       [](const ParameterSeed& s) { return s.walls[2].height; }},
      {"wavemaker.tabled.scale",
       {"wavemaker", "tabled", "scale"},
       [](const Model& m) { return m.walls(3).motion().table().scale(); },
       [](const ParameterSeed& s) { return s.walls[3].scale; }},
  };
  return all;
}

// Every seed slot of one parameter, added up.
double seed_total(const ParameterSeed& s) {
  double total = s.fluid.rho + s.fluid.mu + s.fluid.kappa + s.fluid.thickness;
  for (const auto& m : s.materials) total += m.e0 + m.fy + m.b;
  for (const auto& c : s.sections)
    total += c.rectangle.width + c.rectangle.depth + c.elastic.E + c.elastic.A + c.elastic.I;
  for (const double r : s.beam_rho) total += r;
  for (const auto& w : s.walls) total += w.stroke + w.period + w.height + w.scale;
  return total;
}

TEST(ParameterTargets, EachTargetParsesIntoItsParts) {
  for (const auto& c : cases()) {
    const auto parts = parse_parameter_target(c.target);
    ASSERT_TRUE(parts) << c.target;
    EXPECT_EQ(parts->kind, c.parts.kind) << c.target;
    EXPECT_EQ(parts->name, c.parts.name) << c.target;
    EXPECT_EQ(parts->property, c.parts.property) << c.target;
  }
  for (const char* bad : {"", "fluid", "fluid.colour", "fluid.x.rho", "thickness.x.y", "material.steel", "material..e",
                          "material.st eel.e", "section.square.radius", "beam.beam.mass", "wall.paddle.stroke",
                          "structure.materials[0].E"})
    EXPECT_FALSE(parse_parameter_target(bad)) << bad;
}

TEST(ParameterTargets, EachTargetReadsAndSetsItsOwnFieldOnly) {
  const Model original = model();
  for (const auto& c : cases()) {
    EXPECT_EQ(model_target_value(original, c.target), c.field(original)) << c.target;
    Model changed = original;
    set_model_target(changed, c.target, 4321.0);
    EXPECT_EQ(c.field(changed), 4321.0) << c.target;
    EXPECT_EQ(model_target_value(changed, c.target), 4321.0) << c.target;
    set_model_target(changed, c.target, c.field(original));
    EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(changed, original)) << c.target;
  }
}

TEST(ParameterTargets, AbsentThicknessAndScaleReadAsOne) {
  Model m = model();
  m.clear_thickness();
  m.mutable_walls(3)->mutable_motion()->mutable_table()->clear_scale();
  EXPECT_EQ(model_target_value(m, "thickness"), 1.0);
  EXPECT_EQ(model_target_value(m, "wavemaker.tabled.scale"), 1.0);
}

TEST(ParameterTargets, EachTargetSeedsItsOwnConstant) {
  const Model m = model();
  for (const auto& c : cases()) {
    const auto seeds = parameter_seeds(m, {{{c.target, 0.25}, {c.target, 0.5}}});  // weights add up
    ASSERT_EQ(seeds.size(), 1u);
    EXPECT_EQ(c.seed(seeds[0]), 0.75) << c.target;
    EXPECT_EQ(seed_total(seeds[0]), 0.75) << c.target;
  }
}

TEST(ParameterTargets, RangeRules) {
  const Model m = model();
  for (const auto& c : cases()) {
    const std::string& p = c.parts.property;
    const double inside = p == "hardening_ratio" ? 0.5 : 0.01;
    EXPECT_EQ(target_value_error(m, c.target, inside), "") << c.target;
    if (p == "mu") {
      EXPECT_EQ(target_value_error(m, c.target, 0.0), "");
      EXPECT_EQ(target_value_error(m, c.target, -1e-9), "must be >= 0 for fluid.mu");
    } else if (p == "hardening_ratio") {
      EXPECT_EQ(target_value_error(m, c.target, 0.0), "");
      for (const double v : {-1e-9, 1.0})
        EXPECT_EQ(target_value_error(m, c.target, v), "must be in [0, 1) for material.steel.hardening_ratio") << v;
    } else {
      for (const double v : {0.0, -1.0})
        EXPECT_EQ(target_value_error(m, c.target, v), "must be > 0 for " + c.target) << v;
    }
  }
  // A solitary wave's height: at most 0.6 of its depth (0.1 m); a range needs no component.
  EXPECT_EQ(target_value_error(m, "wavemaker.soliton.height", 0.06), "");
  EXPECT_EQ(target_value_error(m, "wavemaker.soliton.height", 0.0601),
            "must be at most 0.6 of the solitary wave's depth for wavemaker.soliton.height");
  EXPECT_EQ(target_value_error(m, "material.wood.fy", 0.0), "must be > 0 for material.wood.fy");
  EXPECT_EQ(target_value_error(m, "fluid.colour", -1.0), "");
}

TEST(ParameterTargets, TargetsThatNameNoValue) {
  const Model m = model();
  for (const auto& c : cases()) EXPECT_EQ(target_error(m, c.target), "") << c.target;
  const std::pair<const char*, const char*> errors[] = {
      {"fluid.colour",
       "unknown target 'fluid.colour'; expected fluid.rho, fluid.mu, fluid.kappa, thickness, "
       "material.<name>.e|fy|hardening_ratio, section.<name>.width|depth|e|area|inertia, beam.<name>.rho "
       "or wavemaker.<wall>.stroke|period|height|scale"},
      {"material.wood.e", "unknown material 'wood' in target 'material.wood.e'"},
      {"material.soft.fy", "material 'soft' is elastic: it has no fy (only e)"},
      {"section.tube.e", "unknown section 'tube' in target 'section.tube.e'"},
      {"section.plate.width", "section 'plate' is elastic: it has no width (e, area or inertia)"},
      {"section.square.area",
       "section 'square' is a fiber_rectangle: it has no area (width or depth; E is its material's)"},
      {"beam.pole.rho", "unknown beam 'pole' in target 'beam.pole.rho'"},
      {"wavemaker.floor.stroke", "no wall 'floor' with a motion in target 'wavemaker.floor.stroke'"},
      {"wavemaker.paddle.height", "the motion of wall 'paddle' has no height (a sinusoid: stroke or period)"},
      {"wavemaker.soliton.stroke", "the motion of wall 'soliton' has no stroke (a solitary wave: height)"},
      {"wavemaker.tabled.period", "the motion of wall 'tabled' has no period (a table: scale)"},
  };
  for (const auto& [target, message] : errors) {
    EXPECT_EQ(target_error(m, target), message);
    try {
      model_target_value(m, target, "parameters[2].targets[1]");
      ADD_FAILURE() << target << ": no error";
    } catch (const ModelError& e) {
      ASSERT_EQ(e.errors().size(), 1u);
      EXPECT_EQ(e.errors()[0].to_string(), std::string("parameters[2].targets[1]: ") + message);
    }
  }
}

TEST(ParameterTargets, AComponentOfNoFormIsLeftToItsOwnChecks) {
  Model m = model();
  m.mutable_structure()->mutable_sections(1)->clear_elastic();  // neither elastic nor a rectangle
  EXPECT_EQ(target_error(m, "section.plate.e"), "");
  EXPECT_THROW(model_target_value(m, "section.plate.e"), ModelError);
}

TEST(ParameterTargets, AWavemakerTargetNamesTheWallThatMoves) {
  Model m = model();
  m.mutable_walls(0)->set_name("paddle");  // a fixed wall of the same name, before the paddle
  set_model_target(m, "wavemaker.paddle.stroke", 0.04);
  EXPECT_EQ(m.walls(1).motion().sinusoid().stroke(), 0.04);
  EXPECT_FALSE(m.walls(0).has_motion());
}

TEST(ParameterTargets, SeedErrorsAtTheirPaths) {
  try {
    parameter_seeds(model(), {{{"fluid.rho"}}, {{"thickness"}, {"material.none.fy"}}});
    FAIL() << "no error";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.errors().size(), 1u);
    EXPECT_EQ(e.errors()[0].to_string(),
              "sensitivity_targets[1][1]: unknown material 'none' in target 'material.none.fy'");
  }
}

TEST(ParameterTargets, ParameterValuesAtTheModelsPoint) {
  Model m = model();
  const auto add = [&](const std::string& name, std::vector<std::string> targets) {
    auto* p = m.add_parameters();
    p->set_name(name);
    for (const auto& t : targets) p->add_targets(t);
    return p;
  };
  add("E", {"material.soft.e"});
  add("rho_f", {"fluid.rho", "fluid.mu"})->set_value(1010.0);
  add("mu", {"fluid.mu"});  // no value: the one rho_f sets
  auto* along = m.add_parameters();
  along->set_name("along");
  auto* w = along->add_direction();
  w->set_parameter("E");
  w->set_weight(2.0);
  apply_parameter_overrides(m);
  EXPECT_EQ(m.fluid().rho(), 1010.0);
  EXPECT_EQ(parameter_values(m), (std::vector<double>{1.0e6, 1010.0, 1010.0, 0.0}));
}

// The built problem's fluid constants and thickness are those of the model with the parameters'
// values set: a parameter without a value leaves its targets as the model has them (it used to set
// its first target's value on its other fluid and thickness targets: here mu = rho = 1000).
TEST(ParameterTargets, TheBuiltProblemHasTheModelsValueWhereNoParameterSetsOne) {
  Model m = read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/sloshing-beam.json");
  m.clear_parameters();
  auto* p = m.add_parameters();
  p->set_name("linked");
  for (const char* t : {"fluid.rho", "fluid.mu", "thickness"}) p->add_targets(t);
  Problem pb = build_problem(m);
  EXPECT_EQ(pb.fluid.rho, 1000.0);
  EXPECT_EQ(pb.fluid.mu, 0.1);
  EXPECT_EQ(pb.thickness, 0.012);
  EXPECT_EQ(pb.parameters[0].value, 1000.0);  // its first target's
  p->set_value(0.5);
  pb = build_problem(m);
  EXPECT_EQ(pb.fluid.rho, 0.5);
  EXPECT_EQ(pb.fluid.mu, 0.5);
  EXPECT_EQ(pb.thickness, 0.5);
}

TEST(ParameterTargets, OverridesReportEveryBadTarget) {
  Model m = model();
  auto* p = m.add_parameters();
  p->set_name("b");
  p->add_targets("thickness");
  p->add_targets("section.tube.width");
  p->add_targets("material.soft.fy");
  p->set_value(0.02);
  try {
    apply_parameter_overrides(m);
    FAIL() << "no error";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.errors().size(), 2u);
    EXPECT_EQ(e.errors()[0].path, "parameters[0].targets[1]");
    EXPECT_EQ(e.errors()[1].to_string(), "parameters[0].targets[2]: material 'soft' is elastic: it has no fy (only e)");
  }
}

}  // namespace
}  // namespace pfem
