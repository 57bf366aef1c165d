#pragma once
// Resource limits checked before a model is queued or run (RESOURCE_EXHAUSTED naming the
// limit), and the estimates they are checked against.
#include <optional>

#include "pfem/v1/model.pb.h"

namespace pfem::server {

struct Limits {
  long max_queued = 1000;      // jobs waiting for a worker (--max-queued)
  long max_particles = 200000; // fluid particles estimated from the model (--max-particles)
  long max_steps = 1000000;    // ceil(t_end / dt) (--max-steps)
  int max_message_mb = 64;     // largest request or response message (--max-message-mb)
};

// Fluid particles the model starts with, estimated without building it: the area of every
// fluid region (rectangle, or polygon by the shoelace formula) over h^2, rounded. 0 when h is
// not a positive finite number (validation reports that).
long estimate_particles(const pfem::v1::Model& model);

// ceil(t_end / dt) (with a relative tolerance of 1e-9), the overrides taking precedence over
// model.analysis; 0 when either is not a positive finite number.
long count_steps(const pfem::v1::Model& model, std::optional<double> t_end,
                 std::optional<double> dt);

// Throws ServiceError(RESOURCE_EXHAUSTED) naming the limit when the run exceeds
// max_particles or max_steps.
void check_run_limits(const pfem::v1::Model& model, std::optional<double> t_end,
                      std::optional<double> dt, const Limits& limits);

}  // namespace pfem::server
