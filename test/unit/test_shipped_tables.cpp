// Tables compiled into the library (shipped_tables.hpp): the same bytes as the source tree's
// config/*.csv, so an installed package behaves exactly as the build tree.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "process.hpp"
#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/shipped_tables.hpp"

using namespace wheel_rail_contact;

using wrc_test::fileText;

TEST(ShippedTables, EveryTableIsItsConfigFileByteForByte) {
  ASSERT_FALSE(shippedTableNames().empty());
  for (const std::string& name : shippedTableNames()) {
    const bool csv = name.find('.') == std::string::npos;
    const std::string file =
        fileText(std::string(WRC_SOURCE_DIR) + "/config/" + name + (csv ? ".csv" : ""));
    ASSERT_FALSE(file.empty()) << name;
    EXPECT_EQ(shippedTable(name), file) << name;
  }
}

TEST(ShippedTables, ChiTableIsShipped) {
  const ChiTable shipped = ChiTable::shipped();
  const ChiTable file = ChiTable::load(std::string(WRC_SOURCE_DIR) + "/config/chi_table.csv");
  EXPECT_EQ(shipped.meshes(), file.meshes());
  for (int nx : file.meshes())
    for (double ab : {0.2, 0.7, 1.0, 3.0, 5.0}) {
      const SecondOrderChi a = shipped.forMesh(nx).secondOrderAt(CreepageKind::kPhi, ab);
      const SecondOrderChi b = file.forMesh(nx).secondOrderAt(CreepageKind::kPhi, ab);
      EXPECT_EQ(a.chi1, b.chi1) << nx << " " << ab;
      EXPECT_EQ(a.chi5, b.chi5) << nx << " " << ab;
    }
}

TEST(ShippedTables, AnUnknownNameIsAnErrorNamingTheShippedOnes) {
  try {
    shippedTable("no_such_table");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_table"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chi_table"), std::string::npos) << e.what();
  }
}
