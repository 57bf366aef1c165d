#pragma once
// The index of a recorder's column in a run's histories (-1: none), for the integration tests.
#include <algorithm>
#include <string>

#include "engine/io/run_result.h"

namespace pfem {

inline int column(const Histories& h, const std::string& name) {
  const auto it = std::find(h.columns.begin(), h.columns.end(), name);
  return it == h.columns.end() ? -1 : static_cast<int>(it - h.columns.begin());
}

}  // namespace pfem
