#include "server/limits.h"

#include <cmath>
#include <string>

#include "engine/io/model_size.h"
#include "server/model_cost.h"
#include "server/status.h"

namespace pfem::server {

void check_model_cost(const pfem::v1::Model& model, const Limits& limits) {
  const long points = count_geometry_points(model);
  if (points > limits.max_geometry_points) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-geometry-points limit exceeded: the walls and fluid polygons have " +
                           std::to_string(points) + " points, the limit is " +
                           std::to_string(limits.max_geometry_points));
  }
  const long wall_nodes = count_wall_nodes(model);
  if (wall_nodes > limits.max_wall_nodes) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-wall-nodes limit exceeded: the walls make " +
                           std::to_string(wall_nodes) +
                           " wall nodes (their length / mesh.h), the limit is " +
                           std::to_string(limits.max_wall_nodes));
  }
  const long fibers = count_fiber_points(model);
  if (fibers > limits.max_fiber_points) {
    throw ServiceError(grpc::StatusCode::RESOURCE_EXHAUSTED,
                       "max-fiber-points limit exceeded: the fiber beams have " +
                           std::to_string(fibers) +
                           " section states (elements x integration points x fibers), the "
                           "limit is " +
                           std::to_string(limits.max_fiber_points));
  }
}

void check_run_limits(const pfem::v1::Model& model, std::optional<double> t_end,
                      std::optional<double> dt, const Limits& limits) {
  check_model_cost(model, limits);
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
