#include "engine/solve/volume_correction.h"

namespace pfem {

VolumeCorrection volume_correction(const mesh::FluidMesh& mesh, const NodeState& nodes, double target_area,
                                   double relaxation, double thickness) {
  VolumeCorrection c;
  c.target = target_area, c.relaxation = relaxation, c.thickness = thickness;
  c.element_area.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) c.area += c.element_area.emplace_back(nodes.triangle_area(t));
  if (target_area > 0.0 && relaxation > 0.0 && c.area > 0.0) c.dilatation = (target_area / c.area - 1.0) / relaxation;
  return c;
}

Eigen::MatrixXd corner_source_sensitivity(const VolumeCorrection& c, const mesh::FluidMesh& mesh,
                                          const NodeState& nodes, std::span<const fluid::FluidSeed> seeds,
                                          std::span<const double> target_sensitivity) {
  const auto ne = static_cast<Eigen::Index>(mesh.triangles.size());
  const auto np = static_cast<Eigen::Index>(seeds.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(ne, np);
  if (c.dilatation == 0.0) return out;
  Eigen::MatrixXd darea(ne, np);  // dA_e / d theta_k
  for (Eigen::Index e = 0; e < ne; ++e)
    for (Eigen::Index k = 0; k < np; ++k)
      darea(e, k) = nodes.triangle_area_sensitivity(mesh.triangles[e], static_cast<int>(k));
  for (Eigen::Index k = 0; k < np; ++k) {
    // s = (target / A_n - 1) / relaxation, A_n = sum_e A_e.
    double ds = 0.0;
    for (Eigen::Index e = 0; e < ne; ++e) ds += darea(e, k);
    ds *= -c.target / (c.area * c.area * c.relaxation);
    if (!target_sensitivity.empty()) ds += target_sensitivity[k] / (c.area * c.relaxation);
    for (Eigen::Index e = 0; e < ne; ++e)
      out(e, k) = seeds[k].thickness * c.dilatation * c.element_area[e] / 3.0 +
                  c.thickness / 3.0 * (ds * c.element_area[e] + c.dilatation * darea(e, k));
  }
  return out;
}

}  // namespace pfem
