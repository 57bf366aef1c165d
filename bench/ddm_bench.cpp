// The cost of exact gradients (issues 4 and 16): the yielding obstacle (mu = 1, the paper's) and
// the elastic obstacle (water, mu = 1e-3) to t = 0.3 s with P = 1, 2, 4 and 8 parameters by DDM,
// against central finite differences of the same parameters.
//   pfem-bench-ddm [--model obstacle|elastic|both] [--t-end T] [--fdm all|1]
// Prints per model and P: response seconds, sensitivity seconds (their ratio), and the
// central-FDM seconds: measured for every P with --fdm all, otherwise measured at P = 1 (3 runs)
// and scaled to 2P + 1 runs for the others (every FDM run costs one plain response run). Then
// the split of the sensitivity cost of each solver path into a fixed part per step and a part
// per parameter, both as fractions of the response.
#include <array>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/cli/arguments.h"
#include "engine/io/model_io.h"

namespace {

// An example with its parameters and those of its obstacle's material, section and beam (the
// first of each) given as (name, kind, field) added, eight in all.
pfem::v1::Model example_with(const std::string& file, const std::vector<std::array<std::string, 3>>& extra) {
  auto model = pfem::read_model_file(std::string(PFEM_SOURCE_DIR) + "/examples/" + file);
  const auto& structure = model.structure();
  const std::map<std::string, std::string> names{{"material", structure.materials(0).name()},
                                                 {"section", structure.sections(0).name()},
                                                 {"beam", structure.beams(0).name()}};
  for (const auto& [name, kind, field] : extra) {
    auto* p = model.add_parameters();
    p->set_name(name);
    p->add_targets(kind.empty() ? field : kind + "." + names.at(kind) + "." + field);
  }
  if (model.parameters_size() != 8) throw std::logic_error(file + ": the bench expects eight parameters");
  return model;
}

// The example's E, Fy, rho_f, mu, kappa, then the hardening ratio, the section depth and the
// obstacle's density.
pfem::v1::Model yielding_obstacle() {
  return example_with("dam-break-obstacle.json", {{{"b", "material", "hardening_ratio"},
                                                   {"depth", "section", "depth"},
                                                   {"rho_s", "beam", "rho"}}});
}

// The example's E, rho_f, mu, kappa, then the section's width and depth, the obstacle's density
// and the model's thickness.
pfem::v1::Model elastic_obstacle() {
  return example_with("dam-break-elastic-obstacle.json", {{{"width", "section", "width"},
                                                           {"depth", "section", "depth"},
                                                           {"rho_s", "beam", "rho"},
                                                           {"thickness", "", "thickness"}}});
}

void bench(const char* title, const pfem::v1::Model& model, double t_end, bool fdm_all) {
  std::vector<std::string> names;
  for (const auto& p : model.parameters()) names.push_back(p.name());
  std::printf("%s to t = %g s, 1 thread; DDM vs central FDM (2P + 1 runs)\n", title, t_end);
  std::printf("%3s %-46s %10s %12s %9s %11s %8s\n", "P", "parameters", "response s", "sensitivity s", "sens/resp",
              "FDM s", "FDM/DDM");
  double fdm_run_seconds = 0.0;  // one response run, from the measured P = 1 FDM
  std::vector<double> ps, ratios;
  for (const int count : {1, 2, 4, 8}) {
    pfem::RunOptions options;
    options.t_end = t_end;
    options.params.assign(names.begin(), names.begin() + count);
    options.sensitivity = pfem::SensitivityMethod::kDdm;
    const auto ddm = pfem::run(model, options).summary;
    double fdm = 0.0;
    const char* how = "";
    if (count == 1 || fdm_all) {
      options.sensitivity = pfem::SensitivityMethod::kFdm;
      fdm = pfem::run(model, options).summary.wall_seconds;
      if (count == 1) fdm_run_seconds = fdm / 3.0;
    } else {
      fdm = (2 * count + 1) * fdm_run_seconds;
      how = " (scaled)";
    }
    std::string list;
    for (int k = 0; k < count; ++k) list += (k ? "," : "") + names[k];
    const double ratio = ddm.sensitivity_seconds / ddm.response_seconds;
    std::printf("%3d %-46s %10.1f %12.1f %9.2f %11.1f %8.1f%s%s\n", count, list.c_str(), ddm.response_seconds,
                ddm.sensitivity_seconds, ratio, fdm, fdm / ddm.wall_seconds, how,
                ddm.status == pfem::RunStatus::kCompleted ? "" : ("  " + ddm.message).c_str());
    ps.push_back(count);
    ratios.push_back(ratio);
  }
  // sens/resp = fixed + per_param * P on each of the two paths (step_sensitivity.cpp): GMRES
  // preconditioned by the Newton factorisation (P = 1, 2), one LU of the Jacobian (P = 4, 8).
  const auto split = [&](std::size_t i, std::size_t j, const char* path) {
    const double per_param = (ratios[j] - ratios[i]) / (ps[j] - ps[i]), fixed = ratios[i] - per_param * ps[i];
    std::printf("%s: %.2f x response + %.1f %% of the response per parameter\n", path, fixed, 100 * per_param);
  };
  std::printf("sensitivity cost (aim: <= 0.15 and <= 8 %%; P = 8 at least 9x faster than central FDM)\n");
  split(0, 1, "  P <= 2, GMRES");
  split(2, 3, "  P > 2, LU   ");
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "usage: pfem-bench-ddm [--model obstacle|elastic|both] [--t-end T] [--fdm all|1]\n";
  double t_end = 0.3;
  bool fdm_all = false;
  std::string which = "both";
  try {
    pfem::cli::Arguments a(std::vector<std::string>(argv + 1, argv + argc));
    if (a.take_flag("--help") || a.take_flag("-h")) {
      std::printf("%s", usage);
      return 0;
    }
    t_end = a.take_double("--t-end").value_or(t_end);
    if (!(t_end > 0)) throw std::invalid_argument("--t-end must be > 0");
    const std::string fdm = a.take_string("--fdm").value_or("1");
    if (fdm != "all" && fdm != "1") throw std::invalid_argument("--fdm must be all or 1");
    fdm_all = fdm == "all";
    which = a.take_string("--model").value_or(which);
    if (which != "obstacle" && which != "elastic" && which != "both")
      throw std::invalid_argument("--model must be obstacle, elastic or both");
    a.expect_done(0);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "pfem-bench-ddm: %s\n%s", e.what(), usage);
    return 2;
  }
  try {
    if (which != "elastic") bench("yielding obstacle (dam-break-obstacle.json)", yielding_obstacle(), t_end, fdm_all);
    if (which == "both") std::printf("\n");
    if (which != "obstacle")
      bench("elastic obstacle (dam-break-elastic-obstacle.json, water)", elastic_obstacle(), t_end, fdm_all);
  } catch (const std::exception& e) {  // a model error or an example that no longer fits the bench
    std::fprintf(stderr, "pfem-bench-ddm: %s\n", e.what());
    return 1;
  }
  return 0;
}
