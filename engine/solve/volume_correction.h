#pragma once
// The volume correction of a step (theory §2), as a step's solver takes it: the mass balance of
// every element gains the uniform dilatation s = (A_target / A_n - 1) / relaxation [1/s], A_n the
// mesh's area at t_n, so that area a remeshing made or lost goes back to the water over about
// `relaxation`; each corner of element e gets s t A_e / 3 (A_e its area at t_n, t the
// thickness). s is fixed within the step. Its DDM derivative goes through A_n, A_e and the
// target's own sensitivity (engine/analysis/water_account.h).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "engine/fluid/mini_sensitivity.h"
#include "engine/mesh/remesher.h"
#include "engine/solve/node_state.h"

namespace pfem {

struct VolumeCorrection {
  double dilatation = 0.0;           // s; 0 without a correction
  double area = 0.0;                 // A_n
  std::vector<double> element_area;  // A_e at t_n
  double target = 0.0, relaxation = 0.0, thickness = 0.0;

  // What each corner of element e adds to its mass balance.
  double corner_source(std::size_t e) const { return dilatation * thickness / 3.0 * element_area[e]; }
};

// nodes at t_n; target_area or relaxation 0: no correction.
VolumeCorrection volume_correction(const mesh::FluidMesh& mesh, const NodeState& nodes, double target_area,
                                   double relaxation, double thickness);

// d corner_source(e) / d theta_k: rows per element, a column per parameter (nodes at t_n with
// their position sensitivities; target_sensitivity per parameter, empty when none moves it).
Eigen::MatrixXd corner_source_sensitivity(const VolumeCorrection& c, const mesh::FluidMesh& mesh,
                                          const NodeState& nodes, std::span<const fluid::FluidSeed> seeds,
                                          std::span<const double> target_sensitivity);

}  // namespace pfem
