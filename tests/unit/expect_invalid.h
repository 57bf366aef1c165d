#pragma once
// Test helper: make() must throw std::invalid_argument whose message starts with "field:" and
// contains rule (the engine/structure validation convention "field: rule (got X)").
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

inline void expect_invalid(auto make, const std::string& field, const std::string& rule) {
  try {
    make();
    FAIL() << "expected std::invalid_argument for " << field;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(field + ":", 0), 0u) << what;
    EXPECT_NE(what.find(rule), std::string::npos) << what;
  }
}
