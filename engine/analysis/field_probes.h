#pragma once
// Recorders that read the fluid's fields at a fixed place in space rather than at a node, and
// their DDM sensitivities: the same formula evaluated on dual numbers whose derivative parts
// are the nodes' sensitivities (the element or edge found for the response is the one
// differentiated, so the response and its sensitivity take the same discrete decision).
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

// Free-surface elevation at x [m]: the highest crossing of the vertical line x with a free edge
// of the mesh (a boundary edge with a particle end that is not a wall or beam piece); 0 where no
// free surface crosses it (no water there). k < 0: the value; k >= 0: its sensitivity to
// parameter k.
double wave_gauge(const mesh::FluidMesh& mesh, const NodeState& nodes, double x, int k = -1);

// Pressure at the point (x, y) [Pa], interpolated linearly in the triangle that holds it at the
// nodes' current positions; 0 where no triangle does (dry). k as for wave_gauge.
double pressure_at(const mesh::FluidMesh& mesh, const NodeState& nodes, double x, double y, int k = -1);

}  // namespace pfem
