#pragma once
// ParaView output, one file per output step in two series, each with a .pvd collection of the
// times (rewritten after every file, so that a failed or cancelled run still loads):
//   <stem>_000000.vtu ...  every node but removed particles: the fluid mesh as triangles, the
//                          particles as vertices; point fields velocity, pressure,
//                          displacement, kind (0 fluid particle, 1 wall node, 2 structure
//                          node), free_surface (1 on the free surface), and with DDM per
//                          parameter P d_velocity/dP, d_pressure/dP, d_displacement/dP;
//   beams_000000.vtu ...   (with a structure) its nodes and the beam elements as lines;
//                          point fields displacement, rotation, velocity, pressure and their
//                          d.../dP; cell fields element (index), axial_force (N, tension > 0),
//                          moment_i, moment_j (the corotational basic forces) and d.../dP.
// The legend is written in each file as an XML comment.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"
#include "engine/state/state_archive.h"
#include "engine/structure/structure_model.h"

namespace pfem {

class VtkSeries {
 public:
  // params: the names of the DDM parameters (node sensitivity k is params[k]); structure_nodes:
  // the node index of each structure node (empty without a structure).
  VtkSeries(std::filesystem::path dir, std::vector<std::string> params, std::vector<int> structure_nodes,
            std::string stem = "pfem");
  void write(double time, const NodeState& nodes, const mesh::FluidMesh& mesh,
             const structure::StructureModel* structure);
  // Saves or restores the files written so far (a restarted run's .pvd lists them too, and
  // its files are numbered on from them).
  void archive(StateArchive& a);

 private:
  using Collection = std::vector<std::pair<double, std::string>>;
  void write_fluid(const std::filesystem::path& file, const NodeState& nodes, const mesh::FluidMesh& mesh) const;
  void write_beams(const std::filesystem::path& file, const NodeState& nodes,
                   const structure::StructureModel& structure) const;
  void add(Collection& files, const std::string& stem, double time, const std::string& name) const;

  std::filesystem::path dir_;
  std::vector<std::string> params_;
  std::vector<int> structure_nodes_;
  std::string stem_;
  Collection fluid_files_, beam_files_;
};

}  // namespace pfem
