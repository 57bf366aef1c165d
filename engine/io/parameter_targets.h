#pragma once
// The parameter targets (model.proto, Parameter.targets) in one table: for each kind of target
// and property, the component it names, the field of pfem.v1.Model that holds its value (read
// and set here), the range of its values and the DDM seed it sets. Validation
// (check_parameters.cpp), the builders (model_builder, structure_builder, motion_builder) and
// whatever sets parameter values on a model (through Parameter.value and
// apply_parameter_overrides: the FDM, the service, the reliability drivers) use it.
#include <optional>
#include <string>
#include <vector>

#include "engine/base/field_error.h"
#include "engine/fluid/mini_sensitivity.h"
#include "engine/motion/wall_motion.h"
#include "engine/structure/bilinear_material.h"
#include "engine/structure/elastic_section.h"
#include "engine/structure/fiber_section.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// A parameter target split into its parts:
//   "fluid.rho"              -> {"fluid", "", "rho"}        (also mu, kappa)
//   "thickness"              -> {"thickness", "", ""}
//   "material.steel.fy"      -> {"material", "steel", "fy"}  (e, fy, hardening_ratio)
//   "section.sq.width"       -> {"section", "sq", "width"}   (width, depth, e, area, inertia)
//   "beam.tower.rho"         -> {"beam", "tower", "rho"}
//   "wavemaker.paddle.stroke" -> {"wavemaker", "paddle", "stroke"} (period, height, scale)
struct TargetRef {
  std::string kind;
  std::string name;      // the component's (material, section, beam, wall); empty otherwise
  std::string property;  // empty for thickness
};
// The parts of a target of a known form; nullopt otherwise. Names are not resolved here.
std::optional<TargetRef> parse_parameter_target(const std::string& target);

// Why the target names no value in the model, as validation says it at the target's path
// ("unknown material 'steel' in target 'material.steel.e'", "material 'soft' is elastic: it has
// no fy (only e)"); "" when it names one, or a component of none of its kind's forms (a section
// neither elastic nor a fiber_rectangle: its own checks say so).
std::string target_error(const pfem::v1::Model& model, const std::string& target);

// Why value is outside the target's range ("must be > 0 for thickness"; a solitary wave's height
// at most 0.6 of its depth), or "". A target of an unknown form has no range.
std::string target_value_error(const pfem::v1::Model& model, const std::string& target, double value);

// The current value of a target (thickness: 1 when absent; material e: E of an elastic
// material, E0 of a bilinear one; a motion table's scale: 1 when absent). Throws ModelError at
// `path` with target_error's message for a target that names no value.
double model_target_value(const pfem::v1::Model& model, const std::string& target, const std::string& path = "target");

// Sets a target to value in the model (errors as above). The value itself is not checked:
// validate or build the model afterwards.
void set_model_target(pfem::v1::Model& model, const std::string& target, double value,
                      const std::string& path = "target");

// For every parameter that has a value, sets each of its targets to it, in model order (errors
// at "parameters[i].targets[k]").
void apply_parameter_overrides(pfem::v1::Model& model);

// Each parameter's value at the model's point, in model order: its `value`, or else its first
// target's value in with_values (the model after apply_parameter_overrides, so that it never
// undoes another parameter that sets the same target); 0 for a directional parameter.
std::vector<double> parameter_values(const pfem::v1::Model& with_values);

// A DDM seed on one target: d target / d theta = weight, 1 for a parameter's own targets, w_k
// for those of the parameters a directional one weighs (model.proto, Parameter.direction).
struct SeedTarget {
  std::string target;
  double weight = 1.0;
};

// The seed of one parameter theta on every constant a target can set, d constant / d theta
// (several targets of one parameter on one constant add up), by component index of the model.
struct SectionSeed {
  structure::RectangleSeed rectangle;             // fiber_rectangle: width, depth
  structure::ElasticSectionProperties elastic{};  // elastic: e, area, inertia
};
struct ParameterSeed {
  fluid::FluidSeed fluid;                                // fluid.*, thickness
  std::vector<structure::BilinearParameters> materials;  // e0 holds E of an elastic material
  std::vector<SectionSeed> sections;
  std::vector<double> beam_rho;
  std::vector<motion::SignalSeed> walls;  // wavemaker.*, by wall index
};

// The seeds of the parameters whose seeded targets are targets[k]. Throws ModelError with every
// target that names no value, at "sensitivity_targets[k][j]".
std::vector<ParameterSeed> parameter_seeds(const pfem::v1::Model& model,
                                           const std::vector<std::vector<SeedTarget>>& targets);

}  // namespace pfem
