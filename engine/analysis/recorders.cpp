#include "engine/analysis/recorders.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/structure/disp_beam_column.h"
#include "engine/structure/fiber_section.h"

namespace pfem {

double fluid_area(const mesh::FluidMesh& mesh, const NodeState& nodes) {
  double twice = 0.0;
  for (const auto& t : mesh.triangles) {
    const double x1 = nodes.x[t[0]], y1 = nodes.y[t[0]];
    twice += (nodes.x[t[1]] - x1) * (nodes.y[t[2]] - y1) - (nodes.x[t[2]] - x1) * (nodes.y[t[1]] - y1);
  }
  return 0.5 * twice;
}

namespace {
double fluid_extreme(const NodeState& nodes, const mesh::FluidMesh& mesh, bool use_x) {
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.kind[i] == mesh::NodeKind::Fluid && mesh.in_mesh[i])
      best = std::max(best, use_x ? nodes.x[i] : nodes.y[i]);
  return best;
}
}  // namespace

namespace {
// basic_force, fiber_stress or fiber_strain of a beam element (validated by the model checks).
double element_value(const RecorderSpec& r, const structure::StructureModel& model) {
  const auto& beam = dynamic_cast<const structure::BeamColumn2d&>(model.element(r.element));
  if (r.quantity == "basic_force") return beam.basic_force()(r.component);
  const auto& disp = dynamic_cast<const structure::DispBeamColumn2d&>(beam);
  const auto& fibers = dynamic_cast<const structure::FiberSection&>(disp.section(r.section_point));
  const auto& material = fibers.fiber_material(r.fiber);
  return r.quantity == "fiber_stress" ? material.stress() : material.strain();
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
    else if (r.quantity == "fluid_area") value = fluid_area(mesh, nodes);
    else if (r.quantity == "front_x") value = fluid_extreme(nodes, mesh, true);
    else if (r.quantity == "front_y") value = fluid_extreme(nodes, mesh, false);
    else if (r.quantity == "max_speed") {
      for (std::size_t k = 0; k < nodes.size(); ++k)
        if (nodes.kind[k] == mesh::NodeKind::Fluid) value = std::max(value, std::hypot(nodes.vx[k], nodes.vy[k]));
    }
    row.push_back(value);
  }
  return row;
}

}  // namespace pfem
