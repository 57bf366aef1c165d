#pragma once
// Checkpoint files (pfem run --checkpoint-every N, --restart): the state after a step
// (run_state.h) with what identifies the run, from which run() continues bit-identically to an
// uninterrupted run. The file holds, in a StateArchive after the line "PFEM checkpoint <format>":
// the engine build (kEngineBuild), the model, the run options that shape the results, the
// step and time of the state, the state's bytes, and a 64-bit FNV-1a checksum of everything
// before it. A checkpoint is only continued by the engine build that wrote it, for the same
// model and options; anything else is refused with a CheckpointError saying what differs.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/analysis/run.h"
#include "engine/state/state_archive.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// The SHA-256 of the engine's sources (generated at build time, cmake/EngineBuildId.cmake).
extern const char* const kEngineBuild;

// What a restart must share with the checkpointed run.
struct CheckpointedRun {
  pfem::v1::Model model;
  std::optional<double> t_end, dt;  // RunOptions' overrides
  SensitivityMethod sensitivity = SensitivityMethod::kNone;
  std::vector<std::string> params;
  bool drop_geometric_terms = false;
  bool vtk = false;                 // VTK files written (RunOptions::vtk_dir set)
  std::optional<int> vtk_every;
};

struct Checkpoint {
  CheckpointedRun run;
  int step = 0;       // steps done
  double time = 0.0;  // [s]
  std::string state;  // the RunState's bytes
};

CheckpointedRun checkpointed_run(const pfem::v1::Model& model, const RunOptions& options);

// Writes file atomically (to file + ".tmp", then renamed over it): a crash while writing leaves
// the previous checkpoint whole. Throws std::runtime_error when it cannot write.
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

// Throws CheckpointError (naming the file) when it is no checkpoint, is truncated or corrupted,
// or was written by another engine build.
Checkpoint read_checkpoint(const std::filesystem::path& file);

// Throws CheckpointError naming the first difference (a model field, an option) unless now is
// the run saved.
void check_same_run(const CheckpointedRun& saved, const CheckpointedRun& now);

}  // namespace pfem
