#include "engine/structure/validation.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pfem::structure {

namespace {
template <typename T>
std::string describe(const char* field, const char* rule, T value) {
  std::ostringstream out;
  out << field << ": " << rule << " (got " << value << ")";
  return out.str();
}
}  // namespace

void require_positive(double value, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(describe(field, "must be > 0", value));
}

void require_non_negative(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw std::invalid_argument(describe(field, "must be >= 0", value));
}

void require_in_range(int value, int lo, int hi, const char* field) {
  if (value < lo || value > hi) {
    const std::string rule = "must be in " + std::to_string(lo) + ".." + std::to_string(hi);
    throw std::invalid_argument(describe(field, rule.c_str(), value));
  }
}

void throw_invalid(const char* field, const std::string& rule) {
  throw std::invalid_argument(std::string(field) + ": " + rule);
}

}  // namespace pfem::structure
