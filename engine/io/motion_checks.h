#pragma once
// Validation of a wall's prescribed motion (model.proto, WallMotion): paths "walls[i].motion...".
#include <vector>

#include "engine/base/field_error.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// The errors of walls[wall].motion, if it has one: its kind, its signal's fields, a hinge on
// the wall, and that the motion keeps the wall inside the domain up to analysis.t_end.
std::vector<FieldError> wall_motion_errors(const pfem::v1::Model& model, int wall);

}  // namespace pfem
