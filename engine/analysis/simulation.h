#pragma once
// The PFEM time loop of one problem (theory §6): remesh -> Newton solve -> commit -> record.
#include "engine/analysis/problem.h"
#include "engine/analysis/run.h"

namespace pfem {

struct SimulationOutput {
  Histories responses;
  Histories sensitivities;  // DDM: "d<recorder>/d<param>" columns when problem.sensitivity_params
  RunSummary summary;  // status, counts and timings of this one simulation
};

// Runs problem from t = 0 to problem.t_end. Uses options' progress, cancel, vtk_dir and
// vtk_every. Never throws for a simulation failure: the summary says where and why.
SimulationOutput simulate(const Problem& problem, const RunOptions& options);

}  // namespace pfem
