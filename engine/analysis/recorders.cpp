#include "engine/analysis/recorders.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/analysis/boundary_force.h"
#include "engine/analysis/field_probes.h"
#include "engine/fluid/mini_element.h"
#include "engine/structure/disp_beam_column.h"
#include "engine/structure/fiber_section.h"

namespace pfem {

double fluid_area(const mesh::FluidMesh& mesh, const NodeState& nodes) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += nodes.triangle_area(t);
  return area;
}

namespace {
// The fluid particle in the mesh farthest along x (or y), -1 when there is none.
int fluid_extreme(const NodeState& nodes, const mesh::FluidMesh& mesh, bool use_x) {
  int best = -1;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.kind[i] == mesh::NodeKind::Fluid && mesh.in_mesh[i] &&
        (best < 0 || (use_x ? nodes.x[i] > nodes.x[best] : nodes.y[i] > nodes.y[best])))
      best = static_cast<int>(i);
  return best;
}
// The fastest fluid particle, -1 when every one is at rest.
int fastest(const NodeState& nodes) {
  int best = -1;
  double best_speed = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (const double speed = std::hypot(nodes.vx[k], nodes.vy[k]);
        nodes.kind[k] == mesh::NodeKind::Fluid && speed > best_speed)
      best = static_cast<int>(k), best_speed = speed;
  return best;
}

// force_x, force_y or moment of a boundary recorder, or its sensitivity to parameter k (k >= 0).
double boundary_value(const RecorderSpec& r, const Problem& problem, const NodeState& nodes,
                      const mesh::FluidMesh& mesh, int k = -1) {
  const BoundaryLoad load = boundary_load(r.pieces, mesh, nodes, problem.fluid, problem.thickness, r.x, r.y,
                                          k < 0 ? nullptr : &problem.fluid_seeds[k], k);
  return r.quantity == "force_x" ? load.fx : r.quantity == "force_y" ? load.fy : load.moment;
}

// The fiber material a fiber_* recorder reads.
const structure::UniaxialMaterial& fiber(const RecorderSpec& r, const structure::BeamColumn2d& beam) {
  const auto& disp = dynamic_cast<const structure::DispBeamColumn2d&>(beam);
  const auto& fibers = dynamic_cast<const structure::FiberSection&>(disp.section(r.section_point));
  return fibers.fiber_material(r.fiber);
}
// basic_force, fiber_stress or fiber_strain of a beam element (validated by the model checks),
// or its sensitivity to parameter k (k >= 0).
double element_value(const RecorderSpec& r, const structure::StructureModel& model, int k = -1) {
  const auto& beam = dynamic_cast<const structure::BeamColumn2d&>(model.element(r.element));
  if (r.quantity == "basic_force")
    return k < 0 ? beam.basic_force()(r.component) : beam.basic_force_sensitivity(k)(r.component);
  const auto& material = fiber(r, beam);
  if (r.quantity == "fiber_stress") return k < 0 ? material.stress() : material.stress_sensitivity(k);
  return k < 0 ? material.strain() : material.strain_sensitivity(k);
}

// The fluid area's sensitivity to each parameter, sum of d(A/2) over the triangles with
// dA/dx_a = c_a, dA/dy_a = d_a (each triangle's geometry once for all parameters).
std::vector<double> fluid_area_sensitivities(const NodeState& nodes, const mesh::FluidMesh& mesh) {
  std::vector<double> out(nodes.num_params, 0.0);
  for (const auto& t : mesh.triangles) {
    std::array<double, 3> x, y;
    for (int a = 0; a < 3; ++a) x[a] = nodes.x[t[a]], y[a] = nodes.y[t[a]];
    const fluid::TriangleGeometry g = fluid::triangle_geometry(x, y);
    for (int k = 0; k < nodes.num_params; ++k)
      for (int a = 0; a < 3; ++a) {
        const double* d = nodes.sensitivity(t[a], k);
        out[k] += 0.5 * (g.c[a] * d[NodeState::kDx] + g.d[a] * d[NodeState::kDy]);
      }
  }
  return out;
}

}  // namespace

std::vector<double> sample_recorders(const Problem& problem, const NodeState& nodes,
                                     const mesh::FluidMesh& mesh, const structure::StructureModel* structure) {
  std::vector<double> row;
  row.reserve(problem.recorders.size());
  for (const auto& r : problem.recorders) {
    const int i = r.node;
    double value = 0.0;
    if (r.quantity == "ux") value = nodes.x[i] - nodes.x0[i];
    else if (r.quantity == "uy") value = nodes.y[i] - nodes.y0[i];
    else if (r.quantity == "vx") value = nodes.vx[i];
    else if (r.quantity == "vy") value = nodes.vy[i];
    else if (r.quantity == "p") value = nodes.p[i];
    else if (r.quantity == "rz") value = nodes.rz[i];
    else if (r.element >= 0 && structure) value = element_value(r, *structure);
    else if (!r.pieces.empty()) value = boundary_value(r, problem, nodes, mesh);
    else if (r.quantity == "fluid_area") value = fluid_area(mesh, nodes);
    else if (r.quantity == "wave_gauge") value = wave_gauge(wave_gauge_site(mesh, nodes, r.x), nodes, r.x);
    else if (r.quantity == "pressure") value = pressure_at(pressure_site(mesh, nodes, r.x, r.y), mesh, nodes, r.x, r.y);
    else if (r.quantity == "front_x" || r.quantity == "front_y") {
      const bool use_x = r.quantity == "front_x";
      const int front = fluid_extreme(nodes, mesh, use_x);
      value = front < 0 ? -std::numeric_limits<double>::infinity() : use_x ? nodes.x[front] : nodes.y[front];
    } else if (r.quantity == "max_speed") {
      if (const int f = fastest(nodes); f >= 0) value = std::hypot(nodes.vx[f], nodes.vy[f]);
    }
    row.push_back(value);
  }
  return row;
}

std::vector<double> sample_recorder_sensitivities(const Problem& problem, const NodeState& nodes,
                                                  const mesh::FluidMesh& mesh,
                                                  const structure::StructureModel* structure) {
  const int np = nodes.num_params;
  std::vector<double> row;
  row.reserve(problem.recorders.size() * np);
  for (const auto& r : problem.recorders) {
    // Nodal quantities read the node's own sensitivity field; extremes that of the extreme node.
    int node = r.node, field = -1;
    if (r.quantity == "ux") field = NodeState::kDx;
    else if (r.quantity == "uy") field = NodeState::kDy;
    else if (r.quantity == "vx") field = NodeState::kDvx;
    else if (r.quantity == "vy") field = NodeState::kDvy;
    else if (r.quantity == "p") field = NodeState::kDp;
    else if (r.quantity == "rz") field = NodeState::kDrz;
    else if (r.quantity == "front_x") node = fluid_extreme(nodes, mesh, true), field = NodeState::kDx;
    else if (r.quantity == "front_y") node = fluid_extreme(nodes, mesh, false), field = NodeState::kDy;
    const int fast = r.quantity == "max_speed" ? fastest(nodes) : -1;
    const std::vector<double> area = r.quantity == "fluid_area" ? fluid_area_sensitivities(nodes, mesh)
                                                                : std::vector<double>();
    const ProbeSite site = r.quantity == "wave_gauge" ? wave_gauge_site(mesh, nodes, r.x)
                           : r.quantity == "pressure" ? pressure_site(mesh, nodes, r.x, r.y)
                                                      : ProbeSite{};
    for (int k = 0; k < np; ++k) {
      double value = 0.0;
      if (field >= 0 && node >= 0) {
        value = nodes.sensitivity(node, k)[field];
      } else if (r.element >= 0 && structure) {
        value = element_value(r, *structure, k);
      } else if (!r.pieces.empty()) {
        value = boundary_value(r, problem, nodes, mesh, k);
      } else if (r.quantity == "fluid_area") {
        value = area[k];
      } else if (r.quantity == "wave_gauge") {
        value = wave_gauge(site, nodes, r.x, k);
      } else if (r.quantity == "pressure") {
        value = pressure_at(site, mesh, nodes, r.x, r.y, k);
      } else if (fast >= 0) {
        const double* d = nodes.sensitivity(fast, k);
        value = (nodes.vx[fast] * d[NodeState::kDvx] + nodes.vy[fast] * d[NodeState::kDvy]) /
                std::hypot(nodes.vx[fast], nodes.vy[fast]);
      }
      row.push_back(value);
    }
  }
  return row;
}

}  // namespace pfem
