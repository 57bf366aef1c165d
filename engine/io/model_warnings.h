#pragma once
// What `pfem validate` says about a valid model beyond its errors: warnings for values that
// are allowed but implausible (they validate and then fail, or lose water, later). The estimate
// of the run's size and time is engine/analysis/run_estimate.h.
#include <optional>
#include <vector>

#include "engine/io/model_io.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// Plausibility limits of the warnings.
inline constexpr double kMinPlausibleDensity = 100.0;     // [kg/m^3]
inline constexpr double kMaxPlausibleDensity = 30'000.0;  // [kg/m^3]
inline constexpr double kMinSoundToFlowSpeed = 10.0;      // sqrt(kappa/rho) against sqrt(2 g H)

// Warnings, each naming the field, for a model without errors (fields it cannot read are
// skipped): a fluid density outside [100, 30000] kg/m^3; a speed of sound sqrt(kappa/rho)
// below 10 times the expected flow speed U = sqrt(2 g H) (H the height of the water), or with
// the incompressible formulation a fluid.kappa at all (it is ignored there); a dt
// above h / U (a particle at speed U crossing more than one spacing per step); a beam whose
// deflection as a cantilever under the hydrostatic load of min(H, L) of water exceeds its
// length L; a recorder point farther than h from every fluid region and from the structure.
std::vector<FieldError> model_warnings(const pfem::v1::Model& model);

// The warning for a fluid.kappa the incompressible formulation ignores (also in a run's
// summary), or nullopt.
std::optional<FieldError> ignored_bulk_modulus(const pfem::v1::Model& model);

// Central differences at a relative step fdm_eps carry each run's Newton error divided by the
// step: the warning for a Newton tolerance above kFdmToleranceToStep times it (in the summary of
// a run with FDM), or nullopt. On the yielding obstacle to 0.3 s (E, step 1e-7) DDM against FDM
// was 1.2e-7 to 5.7e-5 at a tolerance of 1e-10, about the same at 1e-8 and 1e-7, and up to
// 9.8e-5 at 1e-6, the FDM's own error grown tenfold; the DDM needs no such margin.
inline constexpr double kFdmToleranceToStep = 0.1;
std::optional<FieldError> fdm_tolerance_warning(double newton_tolerance, double fdm_eps);

}  // namespace pfem
