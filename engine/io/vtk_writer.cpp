#include "engine/io/vtk_writer.h"

#include <fstream>
#include <stdexcept>

namespace pfem {

VtkSeries::VtkSeries(std::filesystem::path dir, std::string stem) : dir_(std::move(dir)), stem_(std::move(stem)) {
  std::filesystem::create_directories(dir_);
}

void VtkSeries::write(double time, const NodeState& nodes, const mesh::FluidMesh& mesh) {
  const std::string name = stem_ + "_" + std::to_string(files_.size()) + ".vtu";
  std::ofstream out(dir_ / name);
  if (!out) throw std::runtime_error("cannot write " + (dir_ / name).string());
  out.precision(9);
  const std::size_t n = nodes.size(), nt = mesh.triangles.size();
  std::size_t n_particles = 0;
  for (std::size_t i = 0; i < n; ++i) n_particles += nodes.kind[i] == mesh::NodeKind::Fluid;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << nt + n_particles << "\">\n"
      << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << nodes.x[i] << ' ' << nodes.y[i] << " 0\n";
  out << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : mesh.triangles) out << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  for (std::size_t i = 0; i < n; ++i)
    if (nodes.kind[i] == mesh::NodeKind::Fluid) out << i << '\n';
  out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (std::size_t k = 0; k < nt; ++k) out << (offset += 3) << '\n';
  for (std::size_t k = 0; k < n_particles; ++k) out << (offset += 1) << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < nt; ++k) out << "5\n";            // VTK_TRIANGLE
  for (std::size_t k = 0; k < n_particles; ++k) out << "1\n";   // VTK_VERTEX
  out << "</DataArray>\n</Cells>\n<PointData Scalars=\"pressure\" Vectors=\"velocity\">\n"
      << "<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << nodes.vx[i] << ' ' << nodes.vy[i] << " 0\n";
  out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"pressure\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << nodes.p[i] << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"kind\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << static_cast<int>(nodes.kind[i]) << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"free_surface\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) out << static_cast<int>(mesh.free_surface[i]) << '\n';
  out << "</DataArray>\n</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("failed writing " + (dir_ / name).string());

  files_.emplace_back(time, name);
  std::ofstream pvd(dir_ / (stem_ + ".pvd"));
  pvd.precision(12);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, f] : files_)
    pvd << "  <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
  pvd << "</Collection>\n</VTKFile>\n";
}

}  // namespace pfem
