// Engine throughput: particles, elements, steps per second and the per-step split
// (remesh / assemble / factorise / solve / other)
//  1. the dam break at several particle spacings, N steps from rest;
//  2. every example in examples/ as shipped, to its own t_end, with its fluid-area drift;
//  3. the yielding obstacle to t = 1.0 s with 2 threads (element loops), its wall time;
//  4. the paper's two examples with each fluid formulation (analysis.formulation), side by side.
//   pfem-bench-engine [--steps N] [h ...]     (default: 100 steps at h = 0.01 0.005 0.0025)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/io/model_io.h"

namespace {
void print_header(const char* first) {
  std::printf("%18s %9s %9s %8s %9s %9s %7s %8s | %8s %8s %8s %8s %8s  (ms per step)\n", first, "particles",
              "elements", "steps/s", "newton/st", "factor/st", "halved", "area %", "remesh", "assemble", "factor",
              "solve", "other");
}

void print_row(const char* label, const pfem::RunSummary& s) {
  const double per = 1e3 / std::max(s.steps, 1);
  const double other = s.response_seconds - s.remesh_seconds - s.assemble_seconds - s.factorize_seconds -
                       s.solve_seconds;
  // area %: the fluid area's largest drift from its start, |A(t)/A(0) - 1|.
  std::printf("%18s %9d %9d %8.1f %9.1f %9.1f %7d %8.2f | %8.2f %8.2f %8.2f %8.2f %8.2f%s\n", label, s.particles,
              s.max_elements, s.steps / s.response_seconds,
              static_cast<double>(s.newton_iterations) / std::max(s.steps, 1),
              static_cast<double>(s.factorizations) / std::max(s.steps, 1), s.substeps,
              100.0 * s.fluid_area_max_drift, s.remesh_seconds * per,
              s.assemble_seconds * per, s.factorize_seconds * per, s.solve_seconds * per, other * per,
              s.status == pfem::RunStatus::kCompleted ? "" : ("  " + s.message).c_str());
}

const char* kUsage = "usage: pfem-bench-engine [--steps N] [h ...]   (default: 100 steps at h = 0.01 0.005 0.0025)\n";

// A whole-string number > 0, or invalid_argument naming what was given.
double positive(const std::string& what, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size() || !(v > 0)) throw std::invalid_argument(what + ": '" + text + "' is not a number > 0");
  return v;
}
}  // namespace

int main(int argc, char** argv) {
  int steps = 100;
  std::vector<double> spacings;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::printf("%s", kUsage);
        return 0;
      }
      if (a == "--steps") {
        if (i + 1 >= argc) throw std::invalid_argument("--steps needs a value");
        steps = static_cast<int>(positive("--steps", argv[++i]));
      } else if (!a.empty() && a[0] == '-') {
        throw std::invalid_argument("unknown option " + a);
      } else {
        spacings.push_back(positive("h", a));
      }
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "pfem-bench-engine: %s\n%s", e.what(), kUsage);
    return 2;
  }
  if (spacings.empty()) spacings = {0.01, 0.005, 0.0025};

  const std::string examples = std::string(PFEM_SOURCE_DIR) + "/examples/";
  auto model = pfem::read_model_file(examples + "dam-break.json");
  std::printf("dam break, %d steps of dt = %g s from rest, 1 thread\n", steps, model.analysis().dt());
  print_header("h [m]");
  for (double h : spacings) {
    model.mutable_mesh()->set_h(h);
    pfem::RunOptions options;
    options.t_end = steps * model.analysis().dt();
    char label[32];
    std::snprintf(label, sizeof label, "%.4f", h);
    print_row(label, pfem::run(model, options).summary);
  }
  // Every example to its own end: its speed and its fluid-area drift side by side.
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(examples))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::printf("\nevery example in examples/ to its t_end, 1 thread (label: wall time)\n");
  print_header("example");
  for (const auto& file : files) {
    const auto summary = pfem::run(pfem::read_model_file(file.string()), pfem::RunOptions{}).summary;
    char label[64];
    std::snprintf(label, sizeof label, "%s %.0f s", file.stem().string().c_str(), summary.wall_seconds);
    print_row(label, summary);
  }
  // The aim of the FSI issue: the obstacle at the paper's resolution, 1.0 s in under 20 s.
  std::printf("\ndam-break-obstacle to t = 1.0 s with 2 threads (element loops; aim: under 20 s)\n");
  print_header("threads");
  pfem::RunOptions options;
  options.t_end = 1.0;
  options.threads = 2;
  const auto summary = pfem::run(pfem::read_model_file(examples + "dam-break-obstacle.json"), options).summary;
  char label[48];
  std::snprintf(label, sizeof label, "2: %.1f s", summary.wall_seconds);
  print_row(label, summary);
  // The paper's comparison: the quasi-incompressible Newton step against the incompressible
  // fractional step (engine/solve/fractional_step.h) on the same examples, to their t_end.
  std::printf(
      "\nthe paper's examples with each formulation, to t_end, 1 thread (newton/st: the fractional step's "
      "iterations)\n");
  print_header("example");
  for (const char* name : {"sloshing-beam", "dam-break-obstacle"}) {
    for (const char* formulation : {"quasi-incompressible", "incompressible"}) {
      auto m = pfem::read_model_file(examples + name + ".json");
      m.mutable_analysis()->set_formulation(formulation);
      std::snprintf(label, sizeof label, "%s %s", name == std::string("sloshing-beam") ? "sloshing" : "obstacle",
                    formulation == std::string("incompressible") ? "incompr." : "quasi-inc.");
      print_row(label, pfem::run(m, pfem::RunOptions{}).summary);
    }
  }
  return 0;
}
