#pragma once
// Always-on validation of a pfem.v1.Model: every problem with the field path it concerns.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/model_io.h"

namespace pfem {

// Nodal quantities recorders can sample (ux, uy, vx, vy, p, rz), element quantities
// (basic_force, fiber_stress, fiber_strain), and model-wide ones.
bool is_nodal_quantity(const std::string& q);
bool is_element_quantity(const std::string& q);
bool is_global_quantity(const std::string& q);
bool is_point_quantity(const std::string& q);

// A parameter target split into its parts:
//   "fluid.rho"              -> {"fluid", "", "rho"}        (also mu, kappa)
//   "thickness"              -> {"thickness", "", ""}
//   "material.steel.fy"      -> {"material", "steel", "fy"}  (e, fy, hardening_ratio)
//   "section.sq.width"       -> {"section", "sq", "width"}   (width, depth, e, area, inertia)
//   "beam.tower.rho"         -> {"beam", "tower", "rho"}
struct TargetRef {
  std::string kind;
  std::string name;      // component name (material, section, beam); empty otherwise
  std::string property;  // empty for thickness
};
// The parts of a target of a known form; nullopt otherwise. Names are not resolved here.
std::optional<TargetRef> parse_parameter_target(const std::string& target);
// Whether the target has a known form (its component name is not resolved).
bool is_parameter_target(const std::string& target);

// Whether analysis.formulation is "incompressible" (div v = 0, no bulk modulus; the default is
// "quasi-incompressible").
bool is_incompressible(const pfem::v1::Model& model);

// "<beam>/<k>" -> {"<beam>", k} for a k written as a plain positive integer; nullopt otherwise.
// Names generated for a beam's interior nodes and its elements (see model.proto, Beam).
std::optional<std::pair<std::string, int>> split_generated_name(const std::string& name);

// Only the checks of model.structure (paths "structure...."): what build_structure() needs
// for a model that may have no fluid yet.
std::vector<FieldError> validate_structure(const pfem::v1::Model& model);

class ModelChecker {
 public:
  explicit ModelChecker(const pfem::v1::Model& model) : model_(model) {}
  std::vector<FieldError> run();
  std::vector<FieldError> run_structure();

 private:
  const pfem::v1::Model& model_;
};

}  // namespace pfem
