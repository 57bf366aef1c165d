#include "engine/solve/step_numbering.h"

namespace pfem {

StepNumbering number_unknowns(const mesh::FluidMesh &mesh,
                              const NodeState &nodes,
                              std::span<const std::uint8_t> slip,
                              const structure::StructureModel *model,
                              std::span<const int> structure_node,
                              std::span<const StepRider> riders) {
  StepNumbering u;
  const std::size_t n = nodes.size();
  u.vx.assign(n, -1);
  u.vy.assign(n, -1);
  // The sides of each node that have water (bit s: side s).
  std::vector<std::uint8_t> wet(n, 0);
  const std::size_t ne = mesh.triangles.size();
  for (std::size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a)
      wet[mesh.triangles[e][a]] |= static_cast<std::uint8_t>(1u << mesh.side(e, a));
  std::vector<int> side_unknown(n * mesh::kMaxPressureSides, -1);
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
    for (int side = 0; side < mesh::kMaxPressureSides; ++side) {
      if (!(wet[i] >> side & 1u))
        continue;
      // on the free surface too (see fluid_step.h)
      side_unknown[i * mesh::kMaxPressureSides + side] = u.pressures++;
      u.pressure_node.push_back(static_cast<int>(i));
      u.pressure_side.push_back(static_cast<std::uint8_t>(side));
    }
  }
  u.corner_p.resize(ne);
  for (std::size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 3; ++a)
      u.corner_p[e][a] =
          side_unknown[mesh.triangles[e][a] * mesh::kMaxPressureSides +
                       mesh.side(e, a)];
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
  if (!riders.empty()) {
    u.rider.assign(n, -1);
    u.riders.assign(riders.begin(), riders.end());
    for (std::size_t r = 0; r < riders.size(); ++r)
      u.rider[riders[r].node] = static_cast<int>(r);
  }
  return u;
}

bool StepNumbering::has_rider(const std::array<std::int32_t, 3> &tri) const {
  return is_rider(tri[0]) || is_rider(tri[1]) || is_rider(tri[2]);
}

std::array<VelocityTerms, 9>
StepNumbering::condensed_terms(const std::array<std::int32_t, 3> &tri,
                               int e) const {
  std::array<VelocityTerms, 9> t;
  for (int c = 0; c < 3; ++c) {
    t[2 * c] = velocity_terms(tri[c], 0);
    t[2 * c + 1] = velocity_terms(tri[c], 1);
    t[6 + c] = {{node_velocities + corner_p[e][c], -1}, {1.0, 0.0}};
  }
  return t;
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
    const std::array<std::int32_t, 3> &tri, int e) const {
  std::array<int, 9> u;
  for (int c = 0; c < 3; ++c) {
    u[2 * c] = vx[tri[c]], u[2 * c + 1] = vy[tri[c]];
    u[6 + c] = node_velocities + corner_p[e][c];
  }
  return u;
}

void gather_velocities(const StepNumbering &num, const NodeState &nodes,
                       Eigen::VectorXd &v) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (num.vx[i] >= 0)
      v[num.vx[i]] = nodes.vx[i];
    if (num.vy[i] >= 0)
      v[num.vy[i]] = nodes.vy[i];
  }
}

Eigen::VectorXd gather_pressures(const StepNumbering &num,
                                 const mesh::FluidMesh &mesh,
                                 const NodeState &nodes) {
  Eigen::VectorXd p(num.pressures);
  for (int q = 0; q < num.pressures; ++q) {
    const int i = num.pressure_node[q];
    p[q] = nodes.pressure(i, mesh.multi_sided(i), num.pressure_side[q]);
  }
  return p;
}

} // namespace pfem
