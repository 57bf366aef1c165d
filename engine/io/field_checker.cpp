#include "engine/io/field_checker.h"

#include <cmath>

namespace pfem {

void FieldChecker::finite(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
}
void FieldChecker::positive(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
  else if (!(v > 0.0)) error(path, "must be > 0");
}
void FieldChecker::non_negative(const std::string& path, double v) {
  if (!std::isfinite(v)) error(path, "must be a finite number");
  else if (v < 0.0) error(path, "must be >= 0");
}

void FieldChecker::zero_or_within(const std::string& path, double v, double lo, double hi,
                                  const std::string& message) {
  if (!std::isfinite(v) || (v != 0.0 && (v < lo || v > hi))) error(path, message);
}

std::string at(const std::string& path, int i) { return path + "[" + std::to_string(i) + "]"; }
std::string quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace pfem
