// pfem._engine: the engine in-process for Python (pybind11). The `pfem` package
// (clients/python/pfem/__init__.py) wraps it; this file only converts.
//
// run() releases the GIL while the engine runs; after every step the progress callback takes
// it back to check for signals (PyErr_CheckSignals: a Ctrl-C raises KeyboardInterrupt there)
// and to call the user's callback. Either stops the run at the end of that step through the
// engine's cancel flag; the partial result comes back with "interrupted" set, or the user's
// exception is raised.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/analysis/run_estimate.h"
#include "engine/io/model_builder.h"
#include "engine/io/model_io.h"
#include "engine/io/model_warnings.h"
#include "engine/io/results_io.h"
#include "engine/state/state_archive.h"

namespace py = pybind11;

namespace {

py::list error_list(const std::vector<pfem::FieldError>& errors) {
  py::list out;
  for (const auto& e : errors) out.append(py::make_tuple(e.path, e.message));
  return out;
}

// rows[i][j] as a (rows, columns) float64 array.
py::array_t<double> matrix(const pfem::Histories& h) {
  py::array_t<double> a({h.rows.size(), h.columns.size()});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < h.rows.size(); ++i)
    for (std::size_t j = 0; j < h.columns.size(); ++j) m(i, j) = h.rows[i][j];
  return a;
}

py::dict histories(const pfem::Histories& h) {
  py::dict d;
  d["columns"] = h.columns;
  d["time"] = py::array_t<double>(h.time.size(), h.time.data());
  d["values"] = matrix(h);
  return d;
}

pfem::SensitivityMethod method(const std::string& name) {
  if (name == "none") return pfem::SensitivityMethod::kNone;
  if (name == "ddm") return pfem::SensitivityMethod::kDdm;
  if (name == "fdm") return pfem::SensitivityMethod::kFdm;
  throw py::value_error("sensitivity: '" + name + "' is not none, ddm or fdm");
}

// {"errors": [(path, message)...], "warnings": [...], "estimate": {...}} for a model given as
// proto3 JSON; a syntax error is an error with its line and column, as in `pfem validate`.
py::dict validate(const std::string& json) {
  py::dict out;
  out["warnings"] = py::list();
  try {
    const pfem::v1::Model model = pfem::parse_model_json(json);
    const auto errors = pfem::model_errors(model);
    out["errors"] = error_list(errors);
    if (errors.empty()) out["warnings"] = error_list(pfem::model_warnings(model));
    const pfem::RunEstimate e = pfem::estimate_run(model);
    py::dict estimate;
    estimate["particles"] = e.particles, estimate["elements"] = e.elements, estimate["steps"] = e.steps;
    estimate["seconds"] = e.seconds, estimate["seconds_per_particle_step"] = e.seconds_per_particle_step;
    out["estimate"] = estimate;
  } catch (const pfem::ModelError& e) {
    out["errors"] = error_list(e.errors());
  }
  return out;
}

// {"errors"} for invalid input, else {"responses", "sensitivities", "summary_json", "interrupted"}.
py::dict run(const std::string& json, const std::string& sensitivity, const std::vector<std::string>& params,
             std::optional<double> t_end, std::optional<double> dt, int threads, std::optional<double> fdm_eps,
             const std::string& vtk_dir, py::object progress, int checkpoint_every,
             const std::string& checkpoint_file, const std::string& restart_from) {
  pfem::RunOptions options;
  options.checkpoint_every = checkpoint_every;
  options.checkpoint_file = checkpoint_file;
  options.restart_from = restart_from;
  options.sensitivity = method(sensitivity);
  options.params = params;
  options.t_end = t_end;
  options.dt = dt;
  options.threads = threads;
  if (fdm_eps) options.fdm_eps = *fdm_eps;
  options.vtk_dir = vtk_dir;
  std::atomic<bool> cancel{false};
  options.cancel = &cancel;
  bool interrupted = false;
  std::optional<py::error_already_set> raised;  // by the user's callback
  options.progress = [&](const pfem::Progress& p) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {  // the SIGINT handler raised KeyboardInterrupt
      PyErr_Clear();
      interrupted = true;
      cancel.store(true);
      return;
    }
    if (progress.is_none()) return;
    try {
      py::dict d;
      d["step"] = p.step, d["total_steps"] = p.total_steps, d["time"] = p.time, d["t_end"] = p.t_end;
      d["newton_iterations"] = p.newton_iterations, d["elapsed_seconds"] = p.elapsed_seconds;
      d["remaining_seconds"] = p.remaining_seconds;
      progress(d);
    } catch (py::error_already_set& e) {
      // A Ctrl-C arriving while the callback runs Python code surfaces here.
      interrupted = interrupted || e.matches(PyExc_KeyboardInterrupt);
      if (!interrupted) raised = std::move(e);
      cancel.store(true);
    }
  };
  py::dict out;
  std::optional<pfem::RunResult> result;
  try {
    const pfem::v1::Model model = pfem::parse_model_json(json);
    py::gil_scoped_release release;
    result = pfem::run(model, options);
  } catch (const pfem::ModelError& e) {
    out["errors"] = error_list(e.errors());
    return out;
  }
  if (raised) throw std::move(*raised);
  out["responses"] = histories(result->responses);
  out["sensitivities"] = histories(result->sensitivities);
  out["summary_json"] = pfem::summary_json(result->summary);  // the layout of summary.json
  out["interrupted"] = interrupted;
  return out;
}

}  // namespace

PYBIND11_MODULE(_engine, m) {
  m.doc() = "The PFEM-DDM engine in-process; use the pfem package, which wraps this module.";
  m.def("validate", &validate, py::arg("json"));
  m.def("run", &run, py::arg("json"), py::arg("sensitivity") = "none", py::arg("params") = std::vector<std::string>{},
        py::arg("t_end") = std::nullopt, py::arg("dt") = std::nullopt, py::arg("threads") = 1,
        py::arg("fdm_eps") = std::nullopt, py::arg("vtk_dir") = "", py::arg("progress") = py::none(),
        py::arg("checkpoint_every") = 0, py::arg("checkpoint_file") = "", py::arg("restart_from") = "");
  py::register_exception<pfem::CheckpointError>(m, "CheckpointError", PyExc_ValueError);
}
