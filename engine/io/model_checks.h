#pragma once
// Always-on validation of a pfem.v1.Model: every problem with the field path it concerns.
#include <map>
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
  // Names of the structure's components -> their index in model.structure.
  struct StructureNames {
    std::map<std::string, int> nodes;      // explicit nodes only (generated ones are "<beam>/<k>")
    std::map<std::string, int> materials;
    std::map<std::string, int> sections;
    std::map<std::string, int> beams;
  };

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
  void check_direction(const pfem::v1::Parameter& p, const std::string& path);
  void check_domain();

  void collect_structure_names();
  void check_structure();
  void check_structure_nodes();
  void check_materials();
  void check_sections();
  void check_beams();
  // Beams may touch walls and each other (a beam standing on the floor) but not cross them or
  // lie along them: the triangulation takes both as constraints.
  void check_beam_crossings();
  // Names "<beam>/<k>" resolved against the beams: whether a node exists; the beam of an element (-1: none).
  bool is_structure_node(const std::string& name) const;
  int beam_of_element(const std::string& name) const;
  void check_element_recorder(const pfem::v1::Recorder& r, const std::string& path);
  void check_point(const pfem::v1::Recorder& r, const std::string& path);
  void check_boundary_recorder(const pfem::v1::Recorder& r, const std::string& path);
  void check_target(const std::string& target, const std::string& path);
  // The motion of the wall of that name (nullptr: none, or it does not move).
  const pfem::v1::WallMotion* wall_motion_named(const std::string& name) const;
  void check_target_value(const std::string& target, double value, const std::string& path);

  const pfem::v1::Model& model_;
  std::vector<FieldError> errors_;
  StructureNames names_;
};

}  // namespace pfem
