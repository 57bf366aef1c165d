#include <cmath>
#include <string>

#include "engine/analysis/run.h"

namespace pfem {

std::vector<FieldError> RunOptions::validate() const {
  std::vector<FieldError> errors;
  if (t_end && !(std::isfinite(*t_end) && *t_end > 0)) errors.push_back({"t_end", "must be > 0"});
  if (dt && !(std::isfinite(*dt) && *dt > 0)) errors.push_back({"dt", "must be > 0"});
  if (vtk_every && *vtk_every < 1) errors.push_back({"vtk_every", "must be >= 1"});
  if (threads < 1 || threads > kMaxThreads)
    errors.push_back({"threads", "must be in [1, " + std::to_string(kMaxThreads) + "]"});
  if (!(std::isfinite(fdm_eps) && fdm_eps > 0 && fdm_eps < 0.1)) errors.push_back({"fdm_eps", "must be in (0, 0.1)"});
  if (checkpoint_every < 0) errors.push_back({"checkpoint_every", "must be >= 0"});
  if (checkpoint_every > 0 && checkpoint_file.empty())
    errors.push_back({"checkpoint_file", "is needed with checkpoint_every"});
  if (sensitivity == SensitivityMethod::kFdm && (checkpoint_every > 0 || !restart_from.empty()))
    errors.push_back({checkpoint_every > 0 ? "checkpoint_every" : "restart_from",
                      "checkpoints are for runs without sensitivities or with the DDM (an FDM run is 2P + 1 runs)"});
  return errors;
}

}  // namespace pfem
