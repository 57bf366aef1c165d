#pragma once
// pfem.v1.Model.structure -> structure::StructureModel, with the names recorders and
// parameters use to address its nodes and elements.
//
// Numbering: the explicit nodes come first, in model order (node i = structure.nodes[i]);
// then, beam by beam in model order, each beam's interior nodes "<beam>/1" ... "<beam>/<n-1>"
// from its from_node. Elements beam by beam, "<beam>/1" ... "<beam>/<n>" from its from_node;
// element k joins the beam's nodes k-1 and k.
//
// Parameters: their values are set on the proto model's targets (engine/io/parameter_targets.h),
// and the model is built afterwards, so that the built objects never need setters.
#include <map>
#include <string>
#include <vector>

#include "engine/io/model_io.h"
#include "engine/io/parameter_targets.h"
#include "engine/structure/structure_model.h"

namespace pfem {

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
// DDM: seeds[k] is parameter theta_k's seed on the model's constants (parameter_seeds of this
// model): the materials, sections and beam densities take theirs, and derived constants follow
// (A = b d and I = b d^3/12 of an elastic beam built from a rectangle). The model is then sized
// for P = seeds.size() parameters.
// validated: validate_model (or validate_structure) has passed the model already.
StructureBuild build_structure(const pfem::v1::Model& model, const std::vector<ParameterSeed>& seeds = {},
                               bool validated = false);

}  // namespace pfem
