#include "engine/solve/step_numbering.h"

namespace pfem {

StepNumbering number_unknowns(const mesh::FluidMesh &mesh,
                              const NodeState &nodes,
                              std::span<const std::uint8_t> slip,
                              const structure::StructureModel *model,
                              std::span<const int> structure_node) {
  StepNumbering u;
  const std::size_t n = nodes.size();
  u.vx.assign(n, -1);
  u.vy.assign(n, -1);
  u.p.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!mesh.in_mesh[i])
      continue;
    if (!nodes.is_fixed(i) && nodes.kind[i] != mesh::NodeKind::Structure)
      u.vx[i] = u.node_velocities++, u.vy[i] = u.node_velocities++;
    else if (nodes.kind[i] == mesh::NodeKind::Wall && i < slip.size() &&
             slip[i] == kSlipX)
      u.vx[i] = u.node_velocities++;
    else if (nodes.kind[i] == mesh::NodeKind::Wall && i < slip.size() &&
             slip[i] == kSlipY)
      u.vy[i] = u.node_velocities++;
    u.p[i] = u.pressures++; // on the free surface too (see fluid_step.h)
  }
  // Structure nodes move with the structure whether or not water touches them;
  // a supported dof has no unknown.
  u.structure.assign(model ? model->num_dofs() : 0, -1);
  for (std::size_t k = 0; model && k < structure_node.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const int dof = 3 * static_cast<int>(k) + c;
      if (model->is_fixed(dof))
        continue;
      u.structure[dof] = u.node_velocities++;
      if (c == 0)
        u.vx[structure_node[k]] = u.structure[dof];
      if (c == 1)
        u.vy[structure_node[k]] = u.structure[dof];
    }
  }
  u.velocities =
      u.node_velocities + 2 * static_cast<int>(mesh.triangles.size());
  return u;
}

std::array<int, 8>
StepNumbering::element_velocities(const std::array<std::int32_t, 3> &tri,
                                  int e) const {
  std::array<int, 8> dof;
  for (int a = 0; a < 3; ++a)
    dof[2 * a] = vx[tri[a]], dof[2 * a + 1] = vy[tri[a]];
  dof[6] = bubble(e), dof[7] = bubble(e) + 1;
  return dof;
}

std::array<int, 9> StepNumbering::condensed_unknowns(
    const std::array<std::int32_t, 3> &tri) const {
  std::array<int, 9> u;
  for (int c = 0; c < 3; ++c) {
    u[2 * c] = vx[tri[c]], u[2 * c + 1] = vy[tri[c]];
    u[6 + c] = p[tri[c]] >= 0 ? node_velocities + p[tri[c]] : -1;
  }
  return u;
}

} // namespace pfem
