#pragma once
// DDM against central finite differences on one model: the check users and tests run before
// trusting a gradient (`pfem check-gradients`).
//
// For every recorder r and parameter k: the largest |DDM - FDM| over the recorded times,
// relative to the largest |FDM| over the same times. Optionally the same figure for the DDM
// without the geometric matrices H and T (the paper's baseline approximation), to show that
// dropping them fails the check. A sensitivity that stays below kNegligibleSensitivity (run.h)
// times its natural scale max |r| / |theta| in both (a pressure w.r.t. the thickness, a fluid
// area w.r.t. a beam's density) is marked negligible: there the FDM is round-off and a ratio
// says nothing.
#include <string>
#include <vector>

#include "engine/analysis/run.h"

namespace pfem {

struct GradientCheckRow {
  std::string recorder, parameter;
  double max_fdm = 0.0;           // largest |FDM| over time
  double max_ddm = 0.0;           // largest |DDM| over time
  double ddm = 0.0;               // largest |DDM - FDM| / max_fdm
  double without_geometric = -1;  // same without H, T; -1 when not computed
  bool negligible = false;        // max_fdm and max_ddm < kNegligibleSensitivity max |r| / |theta|
};

struct GradientCheck {
  std::vector<GradientCheckRow> rows;
  RunSummary ddm, fdm;  // the two runs' summaries (failed runs leave rows empty)
};

// options: params, t_end, dt, fdm_eps, threads, cancel; sensitivity is set here. Throws
// ModelError for an invalid model or options.
GradientCheck check_gradients(const pfem::v1::Model& model, RunOptions options, bool without_geometric);

}  // namespace pfem
