#pragma once
// DDM against central finite differences on one model: the check users and tests run before
// trusting a gradient (`pfem check-gradients`).
//
// For every recorder r and parameter k: the largest |DDM - FDM| over the recorded times,
// relative to the largest |FDM| over the same times. Optionally the same figure for the DDM
// without the geometric matrices H and T (the paper's baseline approximation), to show that
// dropping them fails the check. Three kinds of column have nothing to compare, and are marked
// and left out of a verdict: a sensitivity that stays below kNegligibleSensitivity (run.h) times
// its natural scale max |r| / |theta| in both (a pressure w.r.t. the thickness, a fluid area
// w.r.t. a beam's density), where the FDM is round-off; a finite difference that is no slope,
// its one-sided differences apart by more than kFdmParted of it (the perturbed runs parted at a
// remeshing decision, or the response itself is round-off: the run warns of both); and a
// response that stays 0 with its finite difference (an obstacle's sway before the water reaches
// it), where the DDM can only be round-off.
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
  bool not_a_slope = false;       // the FDM's one-sided differences apart by > kFdmParted of it
  bool unmoved = false;           // the response and its FDM 0 throughout
  bool compared() const { return !negligible && !not_a_slope && !unmoved; }
};

struct GradientCheck {
  std::vector<GradientCheckRow> rows;
  RunSummary ddm, fdm;  // the two runs' summaries (failed runs leave rows empty)
};

// options: params, t_end, dt, fdm_eps, threads, cancel; sensitivity is set here. Throws
// ModelError for an invalid model or options.
GradientCheck check_gradients(const pfem::v1::Model& model, RunOptions options, bool without_geometric);

}  // namespace pfem
