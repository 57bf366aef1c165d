#pragma once
// What `pfem validate` and the service say about a valid model's run before it starts: its size,
// and its time on this machine (measured by running a small reference model).
#include "pfem/v1/model.pb.h"

namespace pfem {

struct RunEstimate {
  long particles = 0;                 // at t = 0 (estimate_particles)
  long elements = 0;                  // fluid triangles, about 2 per particle
  long steps = 0;                     // to t_end
  double seconds = 0.0;               // response only, one thread
  double seconds_per_particle_step = 0.0;  // measured on this machine
};

// The run's size, and its time from this machine's speed, measured on a small reference dam
// break (about 0.1 s the first time; the figure is kept for later calls in the process).
RunEstimate estimate_run(const pfem::v1::Model& model);

}  // namespace pfem
