#pragma once
// pfem.v1.Model.structure -> structure::StructureModel, with the names recorders and
// parameters use to address its nodes and elements.
//
// Numbering: the explicit nodes come first, in model order (node i = structure.nodes[i]);
// then, beam by beam in model order, each beam's interior nodes "<beam>/1" ... "<beam>/<n-1>"
// from its from_node. Elements beam by beam, "<beam>/1" ... "<beam>/<n>" from its from_node;
// element k joins the beam's nodes k-1 and k.
//
// Parameters: a target ("material.steel.fy", "section.sq.width", "thickness", ...; see
// model.proto, Parameter) is applied to the proto model, and the model is built afterwards,
// so that the built objects never need setters: set_model_target() sets one target,
// apply_parameter_overrides() sets every parameter that carries a value.
#include <map>
#include <string>
#include <vector>

#include "engine/io/model_io.h"
#include "engine/structure/structure_model.h"

namespace pfem {

// A DDM seed on one parameter target (same forms as Parameter.targets): d target / d theta =
// weight, 1 for a parameter's own targets, w_k for those of the parameters a directional one
// weighs (model.proto, Parameter.direction).
struct SeedTarget {
  std::string target;
  double weight = 1.0;
};

struct StructureBuild {
  structure::StructureModel model;
  std::map<std::string, int> node_index;     // every node by name, generated ones included
  std::map<std::string, int> element_index;  // "<beam>/<k>" -> element index
  std::vector<std::string> node_names;       // by node index
  std::vector<std::string> element_names;    // by element index
  // Per beam (model order): its node indices from from_node to to_node (elements + 1 of
  // them), and its element indices in the same order.
  std::vector<std::vector<int>> beam_nodes;
  std::vector<std::vector<int>> beam_elements;
};

// Validates model.structure (validate_structure(): the fluid is not required) and builds it;
// an absent structure gives an empty build. Throws ModelError listing every problem, with
// field paths ("structure.materials[1].bilinear.fy: must be > 0"); a std::invalid_argument
// from engine/structure is reported at the path of the field it names.
//
// DDM: sensitivity_targets[k] lists the seeded targets of parameter theta_k. Each structural
// target seeds its constant with its weight (several seeds of one parameter on one constant add
// up; derived constants follow, e.g. A = b d and I = b d^3/12 of an elastic beam built from a
// rectangle); "fluid.*" and "thickness" are ignored. The model is then sized for
// P = sensitivity_targets.size() parameters. Errors at "sensitivity_targets[k][j]".
// validated: validate_model (or validate_structure) has passed the model already.
StructureBuild build_structure(const pfem::v1::Model& model,
                               const std::vector<std::vector<SeedTarget>>& sensitivity_targets = {},
                               bool validated = false);

// The current value of a parameter target (thickness: 1 when absent; material e: E of an
// elastic material, E0 of a bilinear one). Throws ModelError at `path` for a target of an
// unknown form or that names a missing component or a property its kind does not have.
double model_target_value(const pfem::v1::Model& model, const std::string& target,
                          const std::string& path = "target");

// Sets a parameter target to value in the model (same targets and errors as above). The value
// itself is not checked: validate or build the model afterwards.
void set_model_target(pfem::v1::Model& model, const std::string& target, double value,
                      const std::string& path = "target");

// For every parameter that has a value, sets each of its targets to it (errors at
// "parameters[i].targets[k]").
void apply_parameter_overrides(pfem::v1::Model& model);

}  // namespace pfem
