#pragma once
// The PFEM time loop of one problem (theory §6): remesh -> Newton solve -> commit -> record.
#include <filesystem>
#include <string>

#include "engine/analysis/checkpoint.h"
#include "engine/io/problem.h"
#include "engine/analysis/run.h"

namespace pfem {

struct SimulationOutput {
  Histories responses;
  Histories sensitivities;  // DDM: "d<recorder>/d<param>" columns when problem.sensitivity_params
  RunSummary summary;  // status, counts and timings of this one simulation
};

// A simulation's checkpoints: the state after every `every`-th step (0: none) and, when
// cancelled, after the last step done, written to file for run (see checkpoint.h); and the
// state of a checkpoint to continue from (null: from t = 0).
struct Checkpointing {
  std::filesystem::path file;
  int every = 0;
  CheckpointedRun run;
  const std::string* restore = nullptr;
};

// Runs problem from t = 0 (or the checkpoint's step) to problem.t_end. Uses options'
// progress, cancel, vtk_dir and vtk_every. Never throws for a simulation failure: the summary
// says where and why. A checkpoint that does not fit the problem throws CheckpointError.
SimulationOutput simulate(const Problem& problem, const RunOptions& options,
                          const Checkpointing* checkpoints = nullptr);

}  // namespace pfem
