#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

using namespace wheel_rail_contact;

TEST(KalkerCoefficients, ReproducesTablePoints) {
  const double nus[3] = {0.0, 0.25, 0.5};
  for (int row = 0; row < 19; ++row)
    for (int k = 0; k < 3; ++k) {
      const CreepCoefficients t = kalkerTableEntry(row, k);
      const CreepCoefficients c = kalkerCoefficients(kalkerTableAOverB(row), nus[k]);
      EXPECT_NEAR(c.c11, t.c11, 1e-12) << "row " << row;
      EXPECT_NEAR(c.c22, t.c22, 1e-12) << "row " << row;
      EXPECT_NEAR(c.c23, t.c23, 1e-12) << "row " << row;
    }
}

TEST(KalkerCoefficients, CircleAtNu028) {
  const CreepCoefficients c = kalkerCoefficients(1.0, 0.28);
  EXPECT_NEAR(c.c11, 4.226, 0.0005);
  EXPECT_NEAR(c.c22, 3.705, 0.0005);
  EXPECT_NEAR(c.c23, 1.488, 0.0005);
}

TEST(KalkerCoefficients, ContactReferenceTableColumn) {
  // test/data/contact_reference/contact_steady_coefficients.csv: coef_kalker_table is CONTACT's
  // own interpolation of the same table at nu = 0.28.
  std::ifstream in(std::string(WRC_SOURCE_DIR) +
                   "/test/data/contact_reference/contact_steady_coefficients.csv");
  ASSERT_TRUE(in) << "test/data/contact_reference/contact_steady_coefficients.csv missing";
  std::string line;
  std::getline(in, line);
  int n = 0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string f[10];
    for (auto& s : f) std::getline(ss, s, ',');
    const CreepCoefficients c = kalkerCoefficients(std::stod(f[0]), std::stod(f[6]));
    const double mine = f[7] == "C11" ? c.c11 : f[7] == "C22" ? c.c22 : c.c23;
    EXPECT_NEAR(mine, std::stod(f[9]), 1e-6 * mine) << line;
    ++n;
  }
  EXPECT_EQ(n, 15);
}

TEST(KalkerCoefficients, LinearBetweenRowsAndMonotoneInNu) {
  const CreepCoefficients lo = kalkerCoefficients(0.5, 0.28), hi = kalkerCoefficients(0.6, 0.28);
  const CreepCoefficients mid = kalkerCoefficients(0.55, 0.25);  // at a tabulated nu: plain linear
  EXPECT_NEAR(mid.c11, 0.5 * (kalkerTableEntry(4, 1).c11 + kalkerTableEntry(5, 1).c11), 1e-12);
  EXPECT_GT(kalkerCoefficients(0.55, 0.28).c11, lo.c11);
  EXPECT_LT(kalkerCoefficients(0.55, 0.28).c11, hi.c11);
  // b/a axis: a/b = 1/0.55 lies halfway between rows b/a = 0.5 and 0.6.
  const CreepCoefficients r1 = kalkerCoefficients(2.0, 0.25),
                          r2 = kalkerCoefficients(1 / 0.6, 0.25);
  EXPECT_NEAR(kalkerCoefficients(1 / 0.55, 0.25).c22, 0.5 * (r1.c22 + r2.c22), 1e-12);
  EXPECT_LT(kalkerCoefficients(1.0, 0.1).c11, kalkerCoefficients(1.0, 0.3).c11);
}

TEST(KalkerCoefficients, OutsideTableIsAClearError) {
  EXPECT_THROW(kalkerCoefficients(0.05, 0.28), std::domain_error);
  EXPECT_THROW(kalkerCoefficients(11.0, 0.28), std::domain_error);
  EXPECT_THROW(kalkerCoefficients(1.0, 0.6), std::domain_error);
  EXPECT_THROW(kalkerCoefficients(NAN, 0.28), std::domain_error);
  try {
    kalkerCoefficients(20.0, 0.28);
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("a/b = 20"), std::string::npos);
  }
}
