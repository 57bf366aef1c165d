#include "engine/analysis/run_estimate.h"

#include <algorithm>
#include <utility>

#include "engine/analysis/run.h"
#include "engine/io/model_size.h"

namespace pfem {

using pfem::v1::Model;

namespace {
// Seconds per particle and step of the response on this machine: a dam break of about 400
// particles over 20 steps.
double measured_seconds_per_particle_step() {
  static const double measured = [] {
    Model ref;
    ref.mutable_fluid()->set_rho(1000), ref.mutable_fluid()->set_mu(1e-3), ref.mutable_fluid()->set_kappa(2.15e9);
    ref.mutable_mesh()->set_h(0.01);
    auto* rect = ref.add_fluid_regions()->mutable_rectangle();
    rect->mutable_min()->set_x(0), rect->mutable_min()->set_y(0);
    rect->mutable_max()->set_x(0.146), rect->mutable_max()->set_y(0.292);
    auto* wall = ref.add_walls();
    for (auto [x, y] : {std::pair{0.0, 0.6}, {0.0, 0.0}, {0.584, 0.0}, {0.584, 0.6}}) {
      auto* p = wall->add_points();
      p->set_x(x), p->set_y(y);
    }
    ref.mutable_analysis()->set_dt(0.001), ref.mutable_analysis()->set_t_end(0.02);
    const RunResult r = run(ref, {});
    return r.summary.response_seconds / std::max(1, r.summary.particles * r.summary.steps);
  }();
  return measured;
}
}  // namespace

RunEstimate estimate_run(const Model& model) {
  RunEstimate e;
  e.particles = estimate_particles(model);
  e.elements = 2 * e.particles;
  e.steps = count_steps(model);
  e.seconds_per_particle_step = measured_seconds_per_particle_step();
  e.seconds = e.seconds_per_particle_step * static_cast<double>(e.particles) * static_cast<double>(e.steps);
  return e;
}

}  // namespace pfem
