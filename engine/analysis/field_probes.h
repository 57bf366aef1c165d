#pragma once
// Recorders that read the fluid's fields at a fixed place in space rather than at a node, and
// their DDM sensitivities: the same formula evaluated on dual numbers whose derivative parts
// are the nodes' sensitivities (the element or edge found for the response is the one
// differentiated, so the response and its sensitivity take the same discrete decision).
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

// Where a probe reads: the two nodes of the free edge a wave gauge crosses, or the triangle that
// holds a pressure point; -1 where there is none. Found once for the value and every sensitivity.
struct ProbeSite {
  int a = -1, b = -1;     // wave gauge: the edge's ends
  int triangle = -1;      // pressure: index into mesh.triangles
};

// Free-surface elevation at x [m]: the highest crossing of the vertical line x with a free edge
// of the mesh (a boundary edge with a particle end that is not a wall or beam piece); 0 where no
// free surface crosses it (no water there). k < 0: the value; k >= 0: its sensitivity to
// parameter k.
ProbeSite wave_gauge_site(const mesh::FluidMesh& mesh, const NodeState& nodes, double x);
double wave_gauge(const ProbeSite& site, const NodeState& nodes, double x, int k = -1);

// Pressure at the point (x, y) [Pa], interpolated linearly in the triangle that holds it at the
// nodes' current positions; 0 where no triangle does (dry). k as for wave_gauge.
ProbeSite pressure_site(const mesh::FluidMesh& mesh, const NodeState& nodes, double x, double y);
double pressure_at(const ProbeSite& site, const mesh::FluidMesh& mesh, const NodeState& nodes, double x, double y,
                   int k = -1);

}  // namespace pfem
