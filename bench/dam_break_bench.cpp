// Dam-break throughput at several particle spacings: particles, elements, steps per second and
// the per-step split (remesh / assemble / factorise / solve / other), one core.
//   pfem-bench-dam-break [--steps N] [h ...]     (default: 100 steps at h = 0.01 0.005 0.0025)
#include <cstdio>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

int main(int argc, char** argv) {
  int steps = 100;
  std::vector<double> spacings;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--steps" && i + 1 < argc) steps = std::stoi(argv[++i]);
    else spacings.push_back(std::stod(a));
  }
  if (spacings.empty()) spacings = {0.01, 0.005, 0.0025};

  auto model = pfem::read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/dam-break.json");
  std::printf("dam break, %d steps of dt = %g s from rest, 1 thread\n", steps, model.analysis().dt());
  std::printf("%8s %9s %9s %10s %9s | %8s %8s %8s %8s %8s  (ms per step)\n", "h [m]", "particles",
              "elements", "steps/s", "newton/st", "remesh", "assemble", "factor", "solve", "other");
  for (double h : spacings) {
    model.mutable_mesh()->set_h(h);
    pfem::RunOptions options;
    options.t_end = steps * model.analysis().dt();
    const auto result = pfem::run(model, options);
    const auto& s = result.summary;
    const double per = 1e3 / std::max(s.steps, 1);
    const double other = s.response_seconds - s.remesh_seconds - s.assemble_seconds -
                         s.factorize_seconds - s.solve_seconds;
    std::printf("%8.4f %9d %9d %10.1f %9.1f | %8.2f %8.2f %8.2f %8.2f %8.2f%s\n", h, s.particles,
                s.max_elements, s.steps / s.response_seconds,
                static_cast<double>(s.newton_iterations) / std::max(s.steps, 1), s.remesh_seconds * per,
                s.assemble_seconds * per, s.factorize_seconds * per, s.solve_seconds * per, other * per,
                s.status == pfem::RunStatus::kCompleted ? "" : ("  " + s.message).c_str());
  }
  return 0;
}
