#pragma once
// Always-on validation of a pfem.v1.Model: every problem with the field path it concerns.
#include <string>
#include <vector>

#include "engine/io/model_io.h"

namespace pfem {

// Nodal quantities recorders can sample, and model-wide ones.
bool is_nodal_quantity(const std::string& q);
bool is_global_quantity(const std::string& q);
// Parameter targets the engine knows ("fluid.rho", ...).
bool is_parameter_target(const std::string& target);

class ModelChecker {
 public:
  explicit ModelChecker(const pfem::v1::Model& model) : model_(model) {}
  std::vector<FieldError> run();

 private:
  void finite(const std::string& path, double v);
  void positive(const std::string& path, double v);
  void non_negative(const std::string& path, double v);
  void error(const std::string& path, const std::string& message) { errors_.push_back({path, message}); }

  void check_fluid();
  void check_mesh();
  void check_regions();
  void check_walls();
  void check_analysis();
  void check_recorders();
  void check_parameters();
  void check_domain();

  const pfem::v1::Model& model_;
  std::vector<FieldError> errors_;
};

}  // namespace pfem
