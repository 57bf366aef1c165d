#include "engine/io/vtk_writer.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "engine/structure/beam_column.h"

namespace pfem {

namespace {

using mesh::NodeKind;

constexpr const char* kFluidLegend =
    "<!-- pfem: points are the nodes except removed particles; cells are the fluid triangles "
    "(VTK_TRIANGLE) and the fluid particles (VTK_VERTEX). kind: 0 fluid particle, 1 wall node, "
    "2 structure node. free_surface: 1 on the free surface. d_<field>/d<P>: DDM sensitivity to "
    "parameter P. Units SI. -->\n";
constexpr const char* kBeamLegend =
    "<!-- pfem: points are the structure nodes, cells the beam elements (VTK_LINE). displacement "
    "and rotation from the initial configuration; axial_force (tension > 0), moment_i, moment_j: "
    "the element's corotational basic forces [N, N m per unit thickness as in the model]. "
    "d_<field>/d<P>: DDM sensitivity to parameter P. -->\n";

std::string padded(std::size_t index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06zu", index);
  return buf;
}

// <DataArray> of count items with `components` values each, value(item, component).
template <class F>
void data_array(std::ostream& out, const char* type, const std::string& name, int components, std::size_t count,
                F value) {
  out << "<DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
  out << " format=\"ascii\">\n";
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < components; ++c) out << (c ? " " : "") << value(i, c);
    out << '\n';
  }
  out << "</DataArray>\n";
}

// The fields of every node i = index[item]: velocity, pressure, displacement (all nodes) and
// rotation (beams), then their sensitivities.
void nodal_fields(std::ostream& out, const NodeState& n, const std::vector<int>& index,
                  const std::vector<std::string>& params, bool rotation) {
  const std::size_t count = index.size();
  data_array(out, "Float64", "velocity", 3, count, [&](std::size_t k, int c) {
    return c == 0 ? n.vx[index[k]] : c == 1 ? n.vy[index[k]] : 0.0;
  });
  data_array(out, "Float64", "pressure", 1, count, [&](std::size_t k, int) { return n.p[index[k]]; });
  data_array(out, "Float64", "displacement", 3, count, [&](std::size_t k, int c) {
    const int i = index[k];
    return c == 0 ? n.x[i] - n.x0[i] : c == 1 ? n.y[i] - n.y0[i] : 0.0;
  });
  if (rotation) data_array(out, "Float64", "rotation", 1, count, [&](std::size_t k, int) { return n.rz[index[k]]; });
  for (int p = 0; p < n.num_params; ++p) {
    const std::string d = "/d" + params.at(p);
    const auto field = [&](int f) { return [&, f](std::size_t k, int c) {
      return c < 2 ? n.sensitivity(index[k], p)[f + c] : 0.0;
    }; };
    data_array(out, "Float64", "d_velocity" + d, 3, count, field(NodeState::kDvx));
    data_array(out, "Float64", "d_pressure" + d, 1, count, field(NodeState::kDp));
    data_array(out, "Float64", "d_displacement" + d, 3, count, field(NodeState::kDx));
    if (rotation) data_array(out, "Float64", "d_rotation" + d, 1, count, field(NodeState::kDrz));
  }
}

void header(std::ostream& out, const char* legend, std::size_t points, std::size_t cells) {
  out << "<?xml version=\"1.0\"?>\n" << legend
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid><Piece NumberOfPoints=\"" << points << "\" NumberOfCells=\"" << cells << "\">\n";
}

void points(std::ostream& out, const NodeState& n, const std::vector<int>& index) {
  out << "<Points>\n";
  data_array(out, "Float64", "position", 3, index.size(), [&](std::size_t k, int c) {
    return c == 0 ? n.x[index[k]] : c == 1 ? n.y[index[k]] : 0.0;
  });
  out << "</Points>\n";
}

// connectivity (in point numbers), offsets and types of cells of sizes[c] points of VTK type types[c].
void cells(std::ostream& out, const std::vector<int>& connectivity, const std::vector<int>& sizes,
           const std::vector<int>& types) {
  out << "<Cells>\n";
  data_array(out, "Int32", "connectivity", 1, connectivity.size(), [&](std::size_t k, int) { return connectivity[k]; });
  int offset = 0;
  data_array(out, "Int32", "offsets", 1, sizes.size(), [&](std::size_t k, int) { return offset += sizes[k]; });
  data_array(out, "UInt8", "types", 1, types.size(), [&](std::size_t k, int) { return types[k]; });
  out << "</Cells>\n";
}

void close(std::ofstream& out, const std::filesystem::path& file) {
  out << "</Piece></UnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("failed writing " + file.string());
}

std::ofstream open(const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out.precision(15);
  return out;
}

}  // namespace

VtkSeries::VtkSeries(std::filesystem::path dir, std::vector<std::string> params, std::vector<int> structure_nodes,
                     std::string stem)
    : dir_(std::move(dir)), params_(std::move(params)), structure_nodes_(std::move(structure_nodes)),
      stem_(std::move(stem)) {
  std::filesystem::create_directories(dir_);
}

void VtkSeries::write(double time, const NodeState& nodes, const mesh::FluidMesh& mesh,
                      const structure::StructureModel* structure) {
  const std::string index = padded(fluid_files_.size());
  const std::string fluid = stem_ + "_" + index + ".vtu";
  write_fluid(dir_ / fluid, nodes, mesh);
  add(fluid_files_, stem_, time, fluid);
  if (!structure) return;
  const std::string beams = "beams_" + index + ".vtu";
  write_beams(dir_ / beams, nodes, *structure);
  add(beam_files_, "beams", time, beams);
}

void VtkSeries::archive(StateArchive& a) { a(fluid_files_), a(beam_files_); }

void VtkSeries::write_fluid(const std::filesystem::path& file, const NodeState& nodes,
                            const mesh::FluidMesh& mesh) const {
  std::vector<int> index, point(nodes.size(), -1);  // point number of each node written
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.kind[i] != NodeKind::Removed) point[i] = static_cast<int>(index.size()), index.push_back(static_cast<int>(i));
  std::vector<int> connectivity, sizes, types;
  for (const auto& t : mesh.triangles) {
    for (int a = 0; a < 3; ++a) connectivity.push_back(point.at(t[a]));
    sizes.push_back(3), types.push_back(5);  // VTK_TRIANGLE
  }
  for (std::size_t k = 0; k < index.size(); ++k)
    if (nodes.kind[index[k]] == NodeKind::Fluid) connectivity.push_back(static_cast<int>(k)), sizes.push_back(1), types.push_back(1);
  std::ofstream out = open(file);
  header(out, kFluidLegend, index.size(), sizes.size());
  points(out, nodes, index);
  cells(out, connectivity, sizes, types);
  out << "<PointData Scalars=\"pressure\" Vectors=\"velocity\">\n";
  nodal_fields(out, nodes, index, params_, false);
  data_array(out, "UInt8", "kind", 1, index.size(), [&](std::size_t k, int) { return static_cast<int>(nodes.kind[index[k]]); });
  data_array(out, "UInt8", "free_surface", 1, index.size(),
             [&](std::size_t k, int) { return static_cast<int>(mesh.free_surface[index[k]]); });
  out << "</PointData>\n";
  close(out, file);
}

void VtkSeries::write_beams(const std::filesystem::path& file, const NodeState& nodes,
                            const structure::StructureModel& structure) const {
  std::vector<const structure::BeamColumn2d*> beams;
  std::vector<int> element, connectivity;
  for (int e = 0; e < structure.num_elements(); ++e) {
    const auto* beam = dynamic_cast<const structure::BeamColumn2d*>(&structure.element(e));
    if (!beam) continue;
    beams.push_back(beam), element.push_back(e);
    for (int n : beam->nodes()) connectivity.push_back(n);  // structure node n is point n
  }
  std::ofstream out = open(file);
  header(out, kBeamLegend, structure_nodes_.size(), beams.size());
  points(out, nodes, structure_nodes_);
  cells(out, connectivity, std::vector<int>(beams.size(), 2), std::vector<int>(beams.size(), 3));  // VTK_LINE
  out << "<PointData Vectors=\"displacement\">\n";
  nodal_fields(out, nodes, structure_nodes_, params_, true);
  out << "</PointData>\n<CellData>\n";
  data_array(out, "Int32", "element", 1, beams.size(), [&](std::size_t k, int) { return element[k]; });
  const char* names[] = {"axial_force", "moment_i", "moment_j"};
  for (int c = 0; c < 3; ++c)
    data_array(out, "Float64", names[c], 1, beams.size(), [&](std::size_t k, int) { return beams[k]->basic_force()(c); });
  for (int p = 0; p < nodes.num_params; ++p)
    for (int c = 0; c < 3; ++c)
      data_array(out, "Float64", std::string("d_") + names[c] + "/d" + params_.at(p), 1, beams.size(),
                 [&](std::size_t k, int) { return beams[k]->basic_force_sensitivity(p)(c); });
  out << "</CellData>\n";
  close(out, file);
}

void VtkSeries::add(Collection& files, const std::string& stem, double time, const std::string& name) const {
  files.emplace_back(time, name);
  std::ofstream pvd(dir_ / (stem + ".pvd"));
  pvd.precision(15);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, f] : files)
    pvd << "  <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
  pvd << "</Collection>\n</VTKFile>\n";
  if (!pvd) throw std::runtime_error("failed writing " + (dir_ / (stem + ".pvd")).string());
}

}  // namespace pfem
