// Wheelset scenario files (contact_cli wheelset's input): columns by name, refusals with the line.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "wheel_rail_contact/wheelset/wheelset_scenario.hpp"

using namespace wheel_rail_contact;

namespace {

std::vector<WheelsetScenarioRow> read(const std::string& text) {
  std::istringstream in(text);
  return readWheelsetScenario(in, "s.csv");
}

std::string errorOf(const std::string& text) {
  try {
    read(text);
  } catch (const WheelsetScenarioError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(WheelsetScenario, ColumnsByNameInAnyOrder) {
  const auto rows = read(
      "# a comment\n"
      "fz,omega,V,roll,yaw,y,t\n"
      "1e4,4.3,2,-2e-5,1e-3,-5e-4,0\n"
      "\n"
      " 2e4 , 4.4, 2.1, 0, 0, 0 , 0.5\n");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].t, 0.0);
  EXPECT_EQ(rows[0].y, -5e-4);
  EXPECT_EQ(rows[0].yaw, 1e-3);
  EXPECT_EQ(rows[0].roll, -2e-5);
  EXPECT_EQ(rows[0].V, 2.0);
  EXPECT_EQ(rows[0].omega, 4.3);
  EXPECT_EQ(rows[0].fz_left, 1e4);  // fz: both wheels
  EXPECT_EQ(rows[0].fz_right, 1e4);
  EXPECT_EQ(rows[0].vy, 0.0);  // optional columns not given
  EXPECT_EQ(rows[0].yaw_rate, 0.0);
  EXPECT_EQ(rows[0].curvature, 0.0);
  EXPECT_FALSE(rows[0].cant.has_value());  // the caller's default
  EXPECT_EQ(rows[1].t, 0.5);
  EXPECT_EQ(rows[1].fz_right, 2e4);
}

TEST(WheelsetScenario, SeparateLoadsAndTheOptionalMotionColumns) {
  const auto rows = read(
      "t,y,yaw,roll,V,omega,fz_left,fz_right,vy,yaw_rate,curvature,cant,vz,roll_rate\n"
      "0,0,0,0,20,43.5,9e3,1.1e4,0.1,0.02,0.002,-0.1,-0.003,0.004\n"
      "1,0,0,0,20,43.5,9e3,1.1e4,0.1,0.02,0.002,0,-0.003,0.004\n");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].cant, -0.1);
  EXPECT_EQ(rows[1].cant, 0.0);  // given as 0: not the default
  EXPECT_EQ(rows[0].fz_left, 9e3);
  EXPECT_EQ(rows[0].fz_right, 1.1e4);
  EXPECT_EQ(rows[0].vy, 0.1);
  EXPECT_EQ(rows[0].yaw_rate, 0.02);
  EXPECT_EQ(rows[0].curvature, 0.002);
  EXPECT_EQ(rows[0].vz, -0.003);
  EXPECT_EQ(rows[0].roll_rate, 0.004);
}

TEST(WheelsetScenario, BadFilesAreRefusedWithTheLineAndTheReason) {
  const std::string h = "t,y,yaw,roll,V,omega,fz\n";
  EXPECT_EQ(errorOf(""), "s.csv:0: no header line (expected t,y,yaw,roll,V,omega,fz)");
  EXPECT_EQ(errorOf("t,y,yaw,roll,V,fz\n"), "s.csv:1: missing column 'omega'");
  EXPECT_EQ(errorOf("t,y,yaw,roll,V,omega\n"),
            "s.csv:1: missing column 'fz' (or fz_left,fz_right)");
  EXPECT_EQ(errorOf("t,y,yaw,roll,V,omega,fz_left\n"),
            "s.csv:1: columns 'fz_left' and 'fz_right' must be given together");
  EXPECT_EQ(errorOf("t,y,yaw,roll,V,omega,fz,fz_left,fz_right\n"),
            "s.csv:1: columns 'fz' and 'fz_left','fz_right' given together: one or the other");
  EXPECT_EQ(errorOf("#\nt,y,yaw,roll,V,omega,fz,z\n").rfind("s.csv:2: unknown column 'z'", 0), 0u);
  EXPECT_EQ(errorOf("t,y,y,roll,V,omega,fz\n"), "s.csv:1: column 'y' given twice");
  EXPECT_EQ(errorOf(h + "0,0,0,0,2,4,1e4\n1,0,0,0,2,4,x\n"),
            "s.csv:3: field 'fz': not a number ('x')");
  EXPECT_EQ(errorOf(h + "0,0,0,0,2,4,\n"), "s.csv:2: field 'fz': not a number ('')");
  EXPECT_EQ(errorOf(h + "0,nan,0,0,2,4,1e4\n"), "s.csv:2: field 'y': not finite ('nan')");
  EXPECT_EQ(errorOf(h + "0,0,0,0,2,4\n"), "s.csv:2: 6 fields, the header has 7 columns");
  EXPECT_EQ(errorOf(h + "0,0,0,0,2,4,1e4,5\n"), "s.csv:2: 8 fields, the header has 7 columns");
  EXPECT_EQ(errorOf(h + "1,0,0,0,2,4,1e4\n1,0,0,0,2,4,1e4\n"),
            "s.csv:3: field 't': time must increase strictly");
}
