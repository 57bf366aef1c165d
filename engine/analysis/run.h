#pragma once
// The engine's one entry point: run a model, get response (and sensitivity) histories and a
// summary back. Used by the `pfem` command, the gRPC server and the reliability drivers.
//
// Thread-safety: run() keeps no shared mutable state; several runs may go side by side on
// different threads. The progress callback is called on the running thread after every step.
#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/field_error.h"
#include "engine/io/run_result.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

struct PreparedRun;  // a model validated and built for one run (prepare_run)

enum class SensitivityMethod { kNone, kDdm, kFdm };
const char* method_name(SensitivityMethod m);  // "none", "ddm", "fdm"

struct Progress {
  int step = 0;                 // steps completed
  int total_steps = 0;          // steps to t_end
  double time = 0.0;            // simulated time reached [s]
  double t_end = 0.0;           // [s]
  int newton_iterations = 0;    // Newton iterations of the last step
  double elapsed_seconds = 0.0;
  double remaining_seconds = 0.0;  // estimate from the mean step cost so far
};

inline constexpr int kMaxThreads = 256;
// A run whose fluid area drifts further than this from its initial value gets a warning.
inline constexpr double kAreaDriftWarning = 0.02;

// A sensitivity below this times its natural scale max |r| / |theta| is negligible: its finite
// difference is round-off (gradient_check.h leaves such a column out of its verdict).
inline constexpr double kNegligibleSensitivity = 1e-4;
// Whether a sensitivity of largest size `sensitivity` is negligible for a response of largest
// size max_response and a parameter of size theta_scale (|theta|, 1 where theta is 0).
inline bool negligible_sensitivity(double sensitivity, double max_response, double theta_scale) {
  return sensitivity * theta_scale < kNegligibleSensitivity * max_response;
}
// A central difference whose two one-sided differences differ by more than this of it is noise
// more than slope (the run warns; error about half of that).
inline constexpr double kFdmNoise = 2e-3;
// ... and by more than this, no slope at all: the perturbed runs parted (a remeshing decision
// taken differently) or the response is round-off (gradient_check.h leaves such a column out
// of its verdict).
inline constexpr double kFdmParted = 0.5;

struct RunOptions {
  std::optional<double> t_end;  // overrides analysis.t_end
  std::optional<double> dt;     // overrides analysis.dt
  SensitivityMethod sensitivity = SensitivityMethod::kNone;
  std::vector<std::string> params;  // parameter names to differentiate; empty = all of the model's
  double fdm_eps = 1e-7;            // relative perturbation of the FDM
  // DDM without the geometric matrices H and T (the approximation of the paper's baseline),
  // only to show what dropping them costs; never for results.
  bool drop_geometric_terms = false;
  std::string vtk_dir;              // when set, write .vtu files and a .pvd there
  std::optional<int> vtk_every;     // overrides analysis.vtk_every
  int threads = 1;                  // threads for element loops, 1..kMaxThreads
  std::function<void(const Progress&)> progress;  // may be empty
  const std::atomic<bool>* cancel = nullptr;      // checked between steps (and Newton iterations)
  // Checkpoints (engine/analysis/checkpoint.h; not with the FDM, whose runs are 2P + 1): the
  // state after every checkpoint_every-th step (0: none), and after the last step done when
  // cancelled, written to checkpoint_file (each replacing the last, atomically).
  int checkpoint_every = 0;
  std::filesystem::path checkpoint_file;
  // Continue from this checkpoint instead of t = 0, bit-identically to a run that was never
  // stopped; the model and the options above the progress callback must be the checkpointed
  // run's (else CheckpointError, as for a checkpoint of another engine build).
  std::filesystem::path restart_from;
  // The model already built for a run with these options (prepare_run of the same model and
  // options, e.g. by a service that builds it to check it); empty: run() builds it.
  std::shared_ptr<const PreparedRun> prepared;

  // Every problem of these options by themselves, the flag's name as the path ("t_end: must
  // be > 0"); the parameter names are checked against the model by run().
  std::vector<FieldError> validate() const;
};

// Runs the model. Throws ModelError (engine/io/model_io.h) when the model or the options are
// invalid, CheckpointError (engine/state/state_archive.h) for a restart_from it cannot continue; a simulation failure (Newton divergence, a particle leaving the domain) does not
// throw: it returns status kFailed with the step, time and reason and the partial histories.
RunResult run(const pfem::v1::Model& model, const RunOptions& options);

// What run() does before simulating, once: validates the model (unless validated: validate_model
// passed it already), builds it with the DDM's seeds for the parameters the options name, and
// checks the options against it. Throws ModelError as run() does.
std::shared_ptr<const PreparedRun> prepare_run(const pfem::v1::Model& model, const RunOptions& options,
                                               bool validated = false);

}  // namespace pfem
