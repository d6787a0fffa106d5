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
      "# comment\nfz,t,V,xi,eta,phi\n1e4,0,10,1e-3,0,0.5\n\n2e4,0.1,10,2e-3,0,0\n");
  const auto rows = readScenario(in, "s.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].fz, 2e4);
  EXPECT_EQ(rows[0].phi, 0.5);
  EXPECT_EQ(rows[1].t, 0.1);
}

TEST(Scenario, ReadsOptionalGeometryAndFrictionColumns) {
  std::istringstream in(
      "t,V,xi,eta,phi,fz,mu,b,a\n0,10,0,0,0,1e4,0.2,4e-3,6e-3\n0.1,10,0,0,0,1e4,0,0,0\n");
  const auto rows = readScenario(in, "s.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].a, 6e-3);
  EXPECT_EQ(rows[0].b, 4e-3);
  EXPECT_EQ(rows[0].mu, 0.2);
  const StepInput step = stepInputAt(rows, 0);
  EXPECT_EQ(step.a, 6e-3);
  EXPECT_EQ(step.b, 4e-3);
  EXPECT_EQ(step.mu, 0.2);
  EXPECT_EQ(rows[1].a, 0.0);  // 0: not given, the parameters apply
  std::istringstream plain("t,V,xi,eta,phi,fz\n0,10,0,0,0,1e4\n");
  const auto none = readScenario(plain, "s.csv");
  EXPECT_EQ(none[0].a, 0.0);
  EXPECT_EQ(none[0].mu, 0.0);
}

TEST(Scenario, UnknownRepeatedOrUnpairedColumnsAndEmptyCellsAreErrors) {
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz,extra\n0,1,0,0,0,1,x\n"),
            "s.csv:1: unknown column 'extra' (known: t,V,xi,eta,phi,fz and optional a,b,mu)");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz,a\n0,1,0,0,0,1,1e-3\n"),
            "s.csv:1: columns 'a' and 'b' must be given together");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz,mu,mu\n0,1,0,0,0,1,1,1\n"),
            "s.csv:1: column 'mu' given twice");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz,a,b\n0,1,0,0,0,1,,4e-3\n"),
            "s.csv:2: field 'a': not a number ('')");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz,mu\n0,1,0,0,0,1,inf\n"),
            "s.csv:2: field 'mu': not finite ('inf')");
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
  // A field beyond the header's columns, a trailing comma's empty one too, is not data to drop.
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,0,0,0,1,7\n"),
            "s.csv:2: 7 fields, more than the header's 6 columns");
  EXPECT_EQ(errorOf("t,V,xi,eta,phi,fz\n0,1,0,0,0,1,\n"),
            "s.csv:2: 7 fields, more than the header's 6 columns");
  EXPECT_EQ(errorOf(""), "s.csv:0: no header line (expected t,V,xi,eta,phi,fz)");
}
