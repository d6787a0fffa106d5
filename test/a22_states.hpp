// The Manchester benchmark's case wheelset states (test/data/profiles/a22_cases.csv), read
// once by validation/manchester_a22's reader for every test that uses them (tests only).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "validation/manchester_a22.hpp"

/// Both wheels of the 21 states, in the file's order; the reader throws on a bad file.
inline std::vector<wheel_rail_contact::A22State> a22States() {
  const std::vector<wheel_rail_contact::A22State> states = wheel_rail_contact::readA22States(
      std::string(WRC_SOURCE_DIR) + "/test/data/profiles/a22_cases.csv");
  EXPECT_EQ(states.size(), 42u);
  return states;
}
