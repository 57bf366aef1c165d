#pragma once
// What one run gives back (pfem::run, engine/analysis/run.h): response and sensitivity histories
// and a summary. Plain data: written to files by engine/io/results_io.h, carried on the wire by
// wire/convert.h.
#include <algorithm>
#include <string>
#include <vector>

namespace pfem {

enum class RunStatus { kCompleted, kFailed, kCancelled };

// Histories sampled every analysis.record_every steps (and at t = 0).
struct Histories {
  std::vector<std::string> columns;        // without the leading "time"
  std::vector<double> time;                // one entry per row
  std::vector<std::vector<double>> rows;   // rows[i][j]: column j at time[i]

  // The index of the column named `name`, -1 if there is none.
  int column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
  }
};

struct RunSummary {
  RunStatus status = RunStatus::kCompleted;
  std::string message;      // why a run failed or was cancelled (empty when completed)
  int failed_step = -1;     // step at which it failed, -1 otherwise
  double failed_time = 0.0;
  int steps = 0;
  double t_end = 0.0;
  double dt = 0.0;
  double wall_seconds = 0.0;
  double response_seconds = 0.0;
  double sensitivity_seconds = 0.0;
  double remesh_seconds = 0.0;     // split of response_seconds
  double assemble_seconds = 0.0;
  double factorize_seconds = 0.0;
  double solve_seconds = 0.0;
  long newton_iterations = 0;  // of every attempt, failed ones before a halving included
  long factorizations = 0;
  int substeps = 0;         // steps split in halves after a failed Newton solve
  // Steps (or substeps) split in halves before an attempt, a triangle collapsing within them at
  // their start's velocities (engine/mesh/deformation_cfl.h).
  int deformation_substeps = 0;
  int removed_particles = 0;   // taken out for coming too close to another node, or for crossing a wall
  int inserted_particles = 0;  // added in the middle of stretched edges
  int left_domain = 0;         // removed for leaving the domain (domain.on_exit "remove")
  // Largest |A(t) / (A(0) - A_flight(t) - A_left(t)) - 1| over the steps: the drift of the water
  // that should be in the mesh (engine/analysis/water_account.h).
  double fluid_area_max_drift = 0.0;
  std::vector<std::string> warnings;  // e.g. the fluid area drifted by more than kAreaDriftWarning
  int particles = 0;
  int max_elements = 0;
  double fluid_area_initial = 0.0;
  double fluid_area_final = 0.0;
  double fluid_area_left = 0.0;  // A_left: the mesh area the particles that left the domain held
  // "none", "ddm", "fdm", or "ddm-approximate" (the DDM of analysis.formulation "incompressible":
  // H and T from the previous step, one pass of the fractional step, docs/theory.md §8).
  std::string sensitivity_method;
  std::vector<std::string> parameters;  // names differentiated
  std::vector<double> parameter_values;
};

struct RunResult {
  Histories responses;      // columns: recorder names
  Histories sensitivities;  // columns: "d<recorder>/d<param>", empty without sensitivity
  RunSummary summary;
  // Central finite differences only (in memory; not written or sent): per sensitivity column,
  // the largest |r+ - 2 r0 + r-| over time against the largest |r+ - r-|, how far the central
  // difference is from a slope (0 for a one-sided difference, a column of zeros or a negligible
  // one; engine/analysis/run.h).
  std::vector<double> fdm_spread;
};

}  // namespace pfem
