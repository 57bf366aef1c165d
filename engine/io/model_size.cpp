#include "engine/io/model_size.h"

#include <algorithm>
#include <cmath>

#include "engine/io/geometry_bounds.h"

namespace pfem {

long estimate_particles(const pfem::v1::Model& model) {
  const double h = model.mesh().h();
  if (!(h > 0.0) || !std::isfinite(h)) return 0;
  double total = 0.0;
  for (const auto& region : model.fluid_regions()) {
    double area = 0.0;
    if (region.has_rectangle()) {
      const auto& r = region.rectangle();
      area = std::abs((r.max().x() - r.min().x()) * (r.max().y() - r.min().y()));
    } else if (region.has_polygon()) {
      area = std::abs(polygon_area(region.polygon()));
    }
    total += area / (h * h);
  }
  if (!std::isfinite(total)) return 0;
  if (total > 1e15) return static_cast<long>(1e15);
  return std::lround(total);
}

long count_wall_nodes(const pfem::v1::Model& model) {
  const double h = model.mesh().h();
  if (!(h > 0.0) || !std::isfinite(h)) return 0;
  constexpr double kCap = 1e15;
  double total = 0.0;
  for (const auto& w : model.walls()) {
    const int n = w.points_size();
    if (n < 2) continue;
    const int segments = w.closed() ? n : n - 1;
    total += w.closed() ? 0.0 : 1.0;
    for (int k = 0; k < segments; ++k) {
      const auto& a = w.points(k);
      const auto& b = w.points((k + 1) % n);
      const double pieces = std::ceil(std::hypot(b.x() - a.x(), b.y() - a.y()) / h - 1e-9);
      if (!std::isnan(pieces)) total += std::max(1.0, pieces);
    }
    if (total > kCap) return static_cast<long>(kCap);
  }
  return static_cast<long>(total);
}

long count_steps(double t_end, double dt) {
  if (!(t_end > 0.0) || !(dt > 0.0) || !std::isfinite(t_end) || !std::isfinite(dt)) return 0;
  const double n = t_end / dt;
  if (!std::isfinite(n) || n > 1e15) return static_cast<long>(1e15);
  return static_cast<long>(std::ceil(n * (1.0 - 1e-9)));
}

std::string too_many_steps(double t_end, double dt, const std::string& dt_field) {
  const long steps = count_steps(t_end, dt);
  if (steps <= kMaxSteps) return "";
  return "is " + std::to_string(steps) + " steps of " + dt_field + ", more than the " + std::to_string(kMaxSteps) +
         " a run may take";
}

long count_steps(const pfem::v1::Model& model, std::optional<double> t_end, std::optional<double> dt) {
  return count_steps(t_end.value_or(model.analysis().t_end()), dt.value_or(model.analysis().dt()));
}

}  // namespace pfem
