#pragma once
// The names of model.structure's components as the checks resolve them (internal to
// engine/io/'s checks).
#include <map>
#include <string>

#include "pfem/v1/model.pb.h"

namespace pfem {

constexpr int kMaxBeamElements = 10000;

// Names of structure components: letters, digits, '_' and '-' (so that "<beam>/<k>" and the
// dotted parameter targets stay unambiguous).
bool valid_name(const std::string& name);

// Names of the structure's components -> their index in model.structure.
struct StructureNames {
  explicit StructureNames(const pfem::v1::Structure& st);
  // Names "<beam>/<k>" resolved against the beams: whether a node exists; the beam of an element (-1: none).
  bool is_structure_node(const std::string& name) const;
  int beam_of_element(const std::string& name) const;

  const pfem::v1::Structure& structure;
  std::map<std::string, int> nodes;  // explicit nodes only (generated ones are "<beam>/<k>")
  std::map<std::string, int> materials;
  std::map<std::string, int> sections;
  std::map<std::string, int> beams;
};

}  // namespace pfem
