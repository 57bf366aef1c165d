#pragma once
// How big a run is, estimated from the model without building it: shared by validation (the
// engine's own caps) and the server's resource limits.
#include <optional>
#include <string>

#include "pfem/v1/model.pb.h"

namespace pfem {

// Beyond these the engine refuses a model: a 2D run of more particles or steps would exhaust
// the memory or run for months; validation says so instead of starting it.
inline constexpr long kMaxParticles = 10'000'000;
inline constexpr long kMaxSteps = 1'000'000'000;
// Building finds every wall node's duplicates among the others (quadratic): 1e5 nodes take
// seconds to build.
inline constexpr long kMaxWallNodes = 100'000;

// Fluid particles the model starts with: the area of every fluid region (rectangle, or polygon
// by the shoelace formula) over h^2, rounded (capped at 1e15). 0 when h is not a positive
// finite number (validation reports that).
long estimate_particles(const pfem::v1::Model& model);

// The wall nodes building makes: ceil(length / h) pieces for every wall segment, one more node
// for every open wall (capped at 1e15; a segment with a NaN end is left to validation). 0
// when h is not a positive finite number. Two points 1e57 m apart are one wall of 1e59 nodes.
long count_wall_nodes(const pfem::v1::Model& model);

// The steps of a run, ceil(t_end / dt) with a relative tolerance of 1e-9 (the last step is
// shortened to end at t_end), the overrides taking precedence over model.analysis (capped at
// 1e15); 0 when either is not a positive finite number.
long count_steps(const pfem::v1::Model& model, std::optional<double> t_end = std::nullopt,
                 std::optional<double> dt = std::nullopt);
long count_steps(double t_end, double dt);
// "" when a run of t_end in steps of dt (named dt_field in the message) stays within kMaxSteps;
// otherwise why not.
std::string too_many_steps(double t_end, double dt, const std::string& dt_field);

}  // namespace pfem
