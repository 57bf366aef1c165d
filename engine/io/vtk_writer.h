#pragma once
// ParaView output: one .vtu per output step (all nodes as points; the fluid mesh as
// triangles and the particles as vertices; fields velocity, pressure, kind, free_surface)
// and a .pvd collection rewritten after every file, so a failed run still loads.
#include <filesystem>
#include <string>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

class VtkSeries {
 public:
  explicit VtkSeries(std::filesystem::path dir, std::string stem = "pfem");
  void write(double time, const NodeState& nodes, const mesh::FluidMesh& mesh);

 private:
  std::filesystem::path dir_;
  std::string stem_;
  std::vector<std::pair<double, std::string>> files_;
};

}  // namespace pfem
