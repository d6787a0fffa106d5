#include <gtest/gtest.h>

#include <sstream>

#include "wheel_rail_contact/scenario.hpp"

using namespace wheel_rail_contact;

namespace {
std::string errorOf(const std::string& text) {
  std::istringstream in(text);
  try {
    readScenario(in, "s.csv");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Scenario, ReadsAnyColumnOrderAndComments) {
  std::istringstream in(
      "# comment\nfz,t,V,xi,eta,phi,extra\n1e4,0,10,1e-3,0,0.5,x\n\n2e4,0.1,10,2e-3,0,0,y\n");
  const auto rows = readScenario(in, "s.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].fz, 2e4);
  EXPECT_EQ(rows[0].phi, 0.5);
  EXPECT_EQ(rows[1].t, 0.1);
}

TEST(Scenario, BadInputNamesLineAndField) {
  EXPECT_EQ(errorOf("t,V,xi,eta,phi\n0,1,0,0,0\n"), "s.csv:1: missing column 'fz'");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,abc,0,0,1\n"),
            "s.csv:2: field 'xi': not a number ('abc')");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,0,0,0\n"), "s.csv:2: field 'fz': missing value");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,nan,0,0,0,1\n"),
            "s.csv:2: field 'V': not finite ('nan')");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,0,0,0,1\n0,1,0,0,0,1\n"),
            "s.csv:3: field 't': time must increase strictly");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,0,,0,1\n"), "s.csv:2: field 'eta': not a number ('')");
  EXPECT_EQ(errorOf(""), "s.csv:0: no header line (expected t,V,xi,eta,phi,fz)");
}
