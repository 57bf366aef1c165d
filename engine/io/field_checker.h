#pragma once
// The errors of a model's validation as they are found, with the numeric rules every section's
// checks share (internal to engine/io/'s checks).
#include <string>
#include <utility>
#include <vector>

#include "engine/base/field_error.h"

namespace pfem {

class FieldChecker {
 public:
  void finite(const std::string& path, double v);
  void positive(const std::string& path, double v);
  void non_negative(const std::string& path, double v);
  // 0 (a setting's "off" or "default") or finite within [lo, hi]; else the message.
  void zero_or_within(const std::string& path, double v, double lo, double hi, const std::string& message);
  void error(const std::string& path, const std::string& message) { errors_.push_back({path, message}); }
  void add(FieldError e) { errors_.push_back(std::move(e)); }

  bool empty() const { return errors_.empty(); }
  const std::vector<FieldError>& errors() const { return errors_; }

 private:
  std::vector<FieldError> errors_;
};

// "walls", 2 -> "walls[2]"; "steel" -> "'steel'".
std::string at(const std::string& path, int i);
std::string quoted(const std::string& s);

}  // namespace pfem
