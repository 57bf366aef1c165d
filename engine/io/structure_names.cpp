#include "engine/io/structure_names.h"

#include <algorithm>
#include <cctype>

#include "engine/io/model_checks.h"

namespace pfem {

namespace {
bool beam_elements_valid(const pfem::v1::Beam& b) {
  return b.elements() >= 1 && b.elements() <= kMaxBeamElements;
}
}  // namespace

bool valid_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

std::optional<std::pair<std::string, int>> split_generated_name(const std::string& name) {
  const auto slash = name.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= name.size()) return std::nullopt;
  const std::string digits = name.substr(slash + 1);
  if (digits.size() > 9 || digits[0] == '0' ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::pair{name.substr(0, slash), std::stoi(digits)};
}

StructureNames::StructureNames(const pfem::v1::Structure& st) : structure(st) {
  const auto collect = [](std::map<std::string, int>& names, const auto& items) {
    for (int i = 0; i < items.size(); ++i)
      if (valid_name(items[i].name())) names.emplace(items[i].name(), i);  // first one wins
  };
  collect(nodes, st.nodes());
  collect(materials, st.materials());
  collect(sections, st.sections());
  collect(beams, st.beams());
}

bool StructureNames::is_structure_node(const std::string& name) const {
  if (nodes.count(name) > 0) return true;
  const auto generated = split_generated_name(name);
  if (!generated) return false;
  const auto b = beams.find(generated->first);
  if (b == beams.end()) return false;
  const auto& beam = structure.beams(b->second);
  return beam_elements_valid(beam) && generated->second < beam.elements();
}

int StructureNames::beam_of_element(const std::string& name) const {
  const auto generated = split_generated_name(name);
  if (!generated) return -1;
  const auto b = beams.find(generated->first);
  if (b == beams.end()) return -1;
  const auto& beam = structure.beams(b->second);
  return beam_elements_valid(beam) && generated->second <= beam.elements() ? b->second : -1;
}

}  // namespace pfem
