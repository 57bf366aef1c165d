#pragma once
// What a model costs to validate and build, bounded before that work starts. Validation and
// building grow with the square of the wall points (wall nodes against each other) and with
// beam elements x integration points x fiber layers (a section state each); a 1 KB model can
// ask for minutes and gigabytes. And the particle estimate (shoelace area / h^2) is only an
// upper bound for a simple polygon: a self-crossing one (a bow-tie) cancels its own area.
#include <vector>

#include "engine/io/model_io.h"
#include "pfem/v1/model.pb.h"

namespace pfem::server {

// Points of every wall and fluid polygon.
long count_geometry_points(const pfem::v1::Model& model);
// Section states of the displacement-based beams: elements x integration points x fibers.
long count_fiber_points(const pfem::v1::Model& model);
// "fluid_regions[i].polygon: edges j and k cross (the polygon must be simple)" for every
// self-crossing fluid polygon. Quadratic in its points: call within the geometry-points limit.
std::vector<FieldError> polygon_errors(const pfem::v1::Model& model);

}  // namespace pfem::server
