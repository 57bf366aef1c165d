#include "server/limits.h"

#include <cmath>
#include <string>

#include "server/status.h"

namespace pfem::server {
namespace {

double region_area(const pfem::v1::FluidRegion& region) {
  if (region.has_rectangle()) {
    const auto& r = region.rectangle();
    return std::abs((r.max().x() - r.min().x()) * (r.max().y() - r.min().y()));
  }
  if (region.has_polygon()) {
    const auto& p = region.polygon().points();
    double twice = 0.0;
    for (int i = 0; i < p.size(); ++i) {
      const auto& a = p[i];
      const auto& b = p[(i + 1) % p.size()];
      twice += a.x() * b.y() - b.x() * a.y();
    }
    return std::abs(twice) / 2.0;
  }
  return 0.0;
}

}  // namespace

long estimate_particles(const pfem::v1::Model& model) {
  const double h = model.mesh().h();
  if (!(h > 0.0) || !std::isfinite(h)) return 0;
  double total = 0.0;
  for (const auto& region : model.fluid_regions()) total += region_area(region) / (h * h);
  if (!std::isfinite(total)) return 0;
  if (total > 1e15) return static_cast<long>(1e15);
  return std::lround(total);
}

long count_steps(const pfem::v1::Model& model, std::optional<double> t_end,
                 std::optional<double> dt) {
  const double t = t_end.value_or(model.analysis().t_end());
  const double d = dt.value_or(model.analysis().dt());
  if (!(t > 0.0) || !(d > 0.0) || !std::isfinite(t) || !std::isfinite(d)) return 0;
  const double n = t / d;
  if (!std::isfinite(n) || n > 1e15) return static_cast<long>(1e15);
  return static_cast<long>(std::ceil(n * (1.0 - 1e-9)));
}

void check_run_limits(const pfem::v1::Model& model, std::optional<double> t_end,
                      std::optional<double> dt, const Limits& limits) {
  const long particles = estimate_particles(model);
  if (particles > limits.max_particles) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-particles limit exceeded: the model has about " +
                           std::to_string(particles) +
                           " fluid particles (fluid_regions area / mesh.h^2), the limit is " +
                           std::to_string(limits.max_particles));
  }
  const long steps = count_steps(model, t_end, dt);
  if (steps > limits.max_steps) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-steps limit exceeded: the run has " + std::to_string(steps) +
                           " steps (t_end / dt), the limit is " +
                           std::to_string(limits.max_steps));
  }
}

}  // namespace pfem::server
