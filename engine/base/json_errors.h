#pragma once
// Why protobuf's JSON parser refused an input file (a model, a reliability or optimisation
// problem), as errors with field paths: protobuf stops at the first problem and names it in its
// own terms ("invalid value \"abc\" for type TYPE_DOUBLE", "Proto field is not repeating, cannot
// start list"); this reads the JSON again against the message's schema.
#include <google/protobuf/descriptor.h>

#include <string>
#include <string_view>
#include <vector>

#include "engine/base/field_error.h"

namespace pfem {

// The line and column of a syntax error (at path `name`, e.g. "model"); else every unknown field
// with the nearest name or the place a field of that name belongs, and every value of the wrong
// kind with what its field takes ("fluid.rho: expected a number, found the string \"heavy\"");
// else protobuf_message (its parser's own).
std::vector<FieldError> json_errors(std::string_view json, const google::protobuf::Descriptor& root,
                                    const std::string& name, std::string protobuf_message);

}  // namespace pfem
