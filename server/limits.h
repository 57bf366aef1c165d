#pragma once
// Resource limits checked before a model is queued or run (RESOURCE_EXHAUSTED naming the
// limit), against the estimates of engine/io/model_size.h.
#include <optional>

#include "engine/io/model_size.h"
#include "pfem/v1/model.pb.h"

namespace pfem::server {

struct Limits {
  long max_queued = 1000;      // jobs waiting for a worker (--max-queued)
  long max_particles = 200000; // fluid particles estimated from the model (--max-particles)
  long max_steps = 1000000;    // ceil(t_end / dt) (--max-steps)
  int max_message_mb = 64;     // largest request or response message (--max-message-mb)
  // Bounds on what validating and building a model costs (server/model_cost.h): 300 wall
  // points took 3.4 CPU-s to validate, growing with their square.
  long max_geometry_points = 200;   // points of all walls and fluid polygons (--max-geometry-points)
  long max_fiber_points = 100000;   // beam elements x integration points x fibers (--max-fiber-points)
  long max_wall_nodes = 20000;      // wall length / mesh.h, all walls (--max-wall-nodes)
  // WatchJob and GetResult streams open at once (server/stream_slots.h).
  long max_streams = 256;            // in total (--max-streams)
  long max_streams_per_client = 64;  // of one client address (--max-streams-per-client)
};

// Throws ServiceError(RESOURCE_EXHAUSTED) naming the limit when validating or building the
// model would exceed max_geometry_points, max_wall_nodes or max_fiber_points. Cheap: call it
// first.
void check_model_cost(const pfem::v1::Model& model, const Limits& limits);

// Throws ServiceError(RESOURCE_EXHAUSTED) naming the limit when the run exceeds
// max_particles or max_steps, or check_model_cost does.
void check_run_limits(const pfem::v1::Model& model, std::optional<double> t_end,
                      std::optional<double> dt, const Limits& limits);

}  // namespace pfem::server
