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

// Whether analysis.formulation is "incompressible" (div v = 0, no bulk modulus; the default is
// "quasi-incompressible").
bool is_incompressible(const pfem::v1::Model& model);

// "<beam>/<k>" -> {"<beam>", k} for a k written as a plain positive integer; nullopt otherwise.
// Names generated for a beam's interior nodes and its elements (see model.proto, Beam).
std::optional<std::pair<std::string, int>> split_generated_name(const std::string& name);

// Only the checks of model.structure (paths "structure...."): what build_structure() needs
// for a model that may have no fluid yet.
std::vector<FieldError> validate_structure(const pfem::v1::Model& model);

// The checks of the parameters' values alone (finite, within each target's range): all that
// validate_model can find wrong in a valid model whose parameter values were changed, since no
// other check reads them (the FDM's perturbed models).
std::vector<FieldError> validate_parameter_values(const pfem::v1::Model& model);

class ModelChecker {
 public:
  explicit ModelChecker(const pfem::v1::Model& model) : model_(model) {}
  std::vector<FieldError> run();
  std::vector<FieldError> run_structure();

 private:
  const pfem::v1::Model& model_;
};

}  // namespace pfem
