#include "server/limits.h"

#include <cmath>
#include <string>

#include "engine/io/model_size.h"
#include "server/model_cost.h"
#include "server/status.h"

namespace pfem::server {
namespace {

// RESOURCE_EXHAUSTED "<flag> limit exceeded: <subject> <value> <unit>, the limit is <limit>".
void require_within(long value, long limit, const char* flag, const char* subject,
                    const char* unit) {
  if (value <= limit) return;
  throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                     std::string(flag) + " limit exceeded: " + subject + " " +
                         std::to_string(value) + " " + unit + ", the limit is " +
                         std::to_string(limit));
}

}  // namespace

void check_model_cost(const pfem::v1::Model& model, const Limits& limits) {
  require_within(count_geometry_points(model), limits.max_geometry_points, "max-geometry-points",
                 "the walls and fluid polygons have", "points");
  require_within(count_wall_nodes(model), limits.max_wall_nodes, "max-wall-nodes",
                 "the walls make", "wall nodes (their length / mesh.h)");
  require_within(count_fiber_points(model), limits.max_fiber_points, "max-fiber-points",
                 "the fiber beams have",
                 "section states (elements x integration points x fibers)");
}

void check_run_limits(const pfem::v1::Model& model, std::optional<double> t_end,
                      std::optional<double> dt, const Limits& limits) {
  check_model_cost(model, limits);
  require_within(estimate_particles(model), limits.max_particles, "max-particles",
                 "the model has about", "fluid particles (fluid_regions area / mesh.h^2)");
  require_within(count_steps(model, t_end, dt), limits.max_steps, "max-steps", "the run has",
                 "steps (t_end / dt)");
}

}  // namespace pfem::server
