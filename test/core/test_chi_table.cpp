#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "wheel_rail_contact/chi_table.hpp"

using namespace wheel_rail_contact;

namespace {
std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}
std::string loadError(const std::string& text) {
  try {
    ChiTable::load(write("bad_chi.csv", text));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
const char* kHeader = "# test\na_over_b,kind,chi1,chi2,chi3\n";
}  // namespace

TEST(ChiTable, InterpolatesInLogAOverBAndClamps) {
  const std::string path = write("chi.csv", std::string(kHeader) +
                                                "0.5,11,0.1,1.0,0.2\n2,11,0.3,1.0,0.4\n"
                                                "1,22,0.2,0.9,0.3\n1,23,0.1,0.8,0.1\n");
  const ChiTable t = ChiTable::load(path);
  EXPECT_NEAR(t.at(CreepageKind::kXi, 1.0).chi1, 0.2,
              1e-12);  // ln 1 is halfway between ln 0.5, ln 2
  EXPECT_NEAR(t.at(CreepageKind::kXi, 0.1).chi3, 0.2, 1e-12);
  EXPECT_NEAR(t.at(CreepageKind::kXi, 10).chi3, 0.4, 1e-12);
  EXPECT_NEAR(t.at(CreepageKind::kPhi, 3.0).chi2, 0.8, 1e-12);
}

TEST(ChiTable, ShippedTableLoadsAndIsStable) {
  const ChiTable t = ChiTable::load(ChiTable::defaultPath());
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (CreepageKind k : {CreepageKind::kXi, CreepageKind::kEta, CreepageKind::kPhi})
      EXPECT_GT(t.at(k, ab).chi3, 0.0);
}

TEST(ChiTable, MalformedTablesNameFileAndLine) {
  EXPECT_NE(loadError("a,b\n").find(":1: expected header"), std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,x,1,1\n").find(":3: field 3"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,12,0,1,1\n").find("kind must be"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,0.1,1,-1\n").find("chi3 must be > 0"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,0.1,1,1\n").find("no rows for kind 22"),
            std::string::npos);
  EXPECT_THROW(ChiTable::load("/nonexistent/chi.csv"), std::runtime_error);
}
