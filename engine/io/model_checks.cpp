#include "engine/io/model_checks.h"

#include "engine/io/section_checks.h"

namespace pfem {

std::vector<FieldError> validate_structure(const pfem::v1::Model& model) {
  ModelChecker checker(model);
  return checker.run_structure();
}

std::vector<FieldError> ModelChecker::run_structure() {
  FieldChecker out;
  const StructureNames names(model_.structure());
  check_structure(model_, names, out);
  return out.errors();
}

std::vector<FieldError> ModelChecker::run() {
  FieldChecker out;
  const StructureNames names(model_.structure());
  if (model_.fluid_regions_size() == 0 && model_.walls_size() == 0) {
    out.error("model", "is empty: it needs at least one fluid region and one wall");
  }
  if (model_.has_thickness()) out.positive("thickness", model_.thickness());
  if (model_.has_gravity()) {
    out.finite("gravity.x", model_.gravity().x());
    out.finite("gravity.y", model_.gravity().y());
  }
  check_fluid(model_, out);
  check_mesh(model_, out);
  check_walls(model_, out);
  check_domain(model_, out);
  check_regions(model_, out);
  check_analysis(model_, out);
  check_recorders(model_, names, out);
  check_parameters(model_, out);
  check_structure(model_, names, out);
  return out.errors();
}

}  // namespace pfem
