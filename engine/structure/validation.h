#pragma once
// Always-on checks of user input. Each throws std::invalid_argument with a message of the
// form "<field>: <rule> (got <value>)", so that callers can prefix the field path
// ("structure.materials[1].fy: must be > 0 (got -3)").
#include <string>

namespace pfem::structure {

void require_positive(double value, const char* field);               // value > 0 and finite
void require_non_negative(double value, const char* field);           // value >= 0 and finite
void require_in_range(int value, int lo, int hi, const char* field);  // lo <= value <= hi
[[noreturn]] void throw_invalid(const char* field, const std::string& rule);

}  // namespace pfem::structure
