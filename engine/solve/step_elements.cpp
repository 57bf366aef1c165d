#include "engine/solve/step_elements.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "engine/solve/fluid_step.h"

namespace pfem {

void StepElements::begin(const mesh::FluidMesh& mesh, const StepSettings& s, const StepNumbering& num,
                         const NodeState& nodes, Eigen::VectorXd bubbles_n) {
  mesh_ = &mesh, s_ = &s, num_ = &num;
  xn_ = nodes.x, yn_ = nodes.y, vxn_ = nodes.vx, vyn_ = nodes.vy;
  vbn_ = std::move(bubbles_n);
  pn_.resize(num.pressures);
  for (int q = 0; q < num.pressures; ++q) {
    const int i = num.pressure_node[q];
    pn_[q] = nodes.pressure(i, mesh.multi_sided(i), num.pressure_side[q]);
  }
  volume_ = pfem::volume_correction(mesh, nodes, s.target_area, s.volume_relaxation, s.thickness);  // at t_n
}

void StepElements::update(const Eigen::VectorXd& v, const Eigen::VectorXd& p) {
  const mesh::FluidMesh& mesh = *mesh_;
  const StepSettings& s = *s_;
  const int ne = static_cast<int>(mesh.triangles.size());
  geometries_.resize(ne);
  element_residuals_.resize(ne);
  matrices_current_ = false;
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) {
    std::array<double, 3> x, y, xn, yn;
    for (int a = 0; a < 3; ++a) {
      const int i = mesh.triangles[e][a];
      xn[a] = xn_[i], yn[a] = yn_[i];
      x[a] = xn_[i] + s.dt * velocity_x(i, v);
      y[a] = yn_[i] + s.dt * velocity_y(i, v);
    }
    geometries_[e] = fluid::triangle_geometry(x, y);
    fluid::continuity_at_midpoint(geometries_[e], xn, yn);
    element_residuals_[e] =
        fluid::element_residual(geometries_[e], s.fluid, s.thickness, s.gx, s.gy, s.dt, state(e, v, p));
  }
}

const std::vector<fluid::MiniMatrices>& StepElements::matrices() const {
  if (matrices_current_) return mats_;
  const StepSettings& s = *s_;
  const int ne = static_cast<int>(geometries_.size());
  mats_.resize(ne);
#pragma omp parallel for schedule(static) num_threads(s.threads)
  for (int e = 0; e < ne; ++e) fluid::mini_matrices(geometries_[e], s.fluid, s.thickness, s.gx, s.gy, mats_[e]);
  matrices_current_ = true;
  return mats_;
}

fluid::ElementState StepElements::state(int e, const Eigen::VectorXd& v, const Eigen::VectorXd& p) const {
  const StepNumbering& num = *num_;
  fluid::ElementState st;
  const auto& tri = mesh_->triangles[e];
  for (int a = 0; a < 3; ++a) {
    const int i = tri[a], q = num.corner_p[e][a];
    st.v(2 * a) = velocity_x(i, v);
    st.v(2 * a + 1) = velocity_y(i, v);
    st.vn(2 * a) = vxn_[i];
    st.vn(2 * a + 1) = vyn_[i];
    st.p(a) = p[q];
    st.pn(a) = pn_[q];
  }
  const int b = num.bubble(e);
  st.v(6) = v[b], st.v(7) = v[b + 1];
  st.vn.tail<2>() = vbn_.segment<2>(2 * e);
  return st;
}

double StepElements::wall_velocity(int i, int c) const {
  return s_->wall_velocity.empty() ? 0.0 : s_->wall_velocity[2 * static_cast<std::size_t>(i) + c];
}
double StepElements::velocity(int i, int c, const Eigen::VectorXd& v) const {
  const int own = c == 0 ? num_->vx[i] : num_->vy[i];
  if (own >= 0) return v[own];
  return num_->is_rider(i) ? num_->velocity_in(i, c, v) : wall_velocity(i, c);
}

void StepElements::assemble(StepResidual& r) const {
  const StepNumbering& num = *num_;
  r.rv.setZero(num.velocities);
  r.rp.setZero(num.pressures);
  r.rp_abs.setZero(num.pressures);
  r.mp.setZero(num.pressures);
  const int ne = static_cast<int>(mesh_->triangles.size());
  for (int e = 0; e < ne; ++e) {
    const auto& re = element_residuals_[e];
    const auto& tri = mesh_->triangles[e];
    for (int a = 0; a < 3; ++a) {
      const int i = tri[a], q = num.corner_p[e][a];
      for (int c = 0; c < 2; ++c) num.add_to_velocity(i, c, re.rv(2 * a + c), r.rv);
      r.rp[q] += re.rp(a), r.rp_abs[q] += re.rp_abs(a), r.mp[q] += re.mp;
      if (volume_.dilatation != 0.0) {
        const double source = volume_.corner_source(e);
        r.rp[q] += source, r.rp_abs[q] += std::abs(source);
      }
    }
    const int b = num.bubble(e);
    r.rv[b] += re.rv(6), r.rv[b + 1] += re.rv(7);
  }
}

bool StepElements::any_inverted() const {
  return std::any_of(geometries_.begin(), geometries_.end(), [](const fluid::TriangleGeometry& g) { return !(g.A > 0.0); });
}

}  // namespace pfem
