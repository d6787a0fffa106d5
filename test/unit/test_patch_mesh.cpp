#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/fastsim/patch_mesh.hpp"

using namespace wheel_rail_contact;

TEST(PatchMesh, StripLayoutCoversTheEllipse) {
  const PatchMesh m(10, 8, 6e-3, 4e-3);
  EXPECT_EQ(m.size(), 80);
  EXPECT_NEAR(m.stripWidth(0), 1e-3, 1e-15);
  EXPECT_NEAR(m.stripY(0), -3.5e-3, 1e-15);
  for (int j = 0; j < m.ny(); ++j) {
    const double aj = m.stripHalfLength(j), y = m.stripY(j);
    EXPECT_NEAR(aj * aj / 36e-6 + y * y / 16e-6, 1.0, 1e-12);
    EXPECT_NEAR(m.nodeX(0, j), aj - 0.5 * m.stripStep(j), 1e-15);  // leading element centre
    EXPECT_NEAR(m.nodeX(m.nx() - 1, j), -aj + 0.5 * m.stripStep(j),
                1e-15);  // trailing element centre
  }
}

TEST(PatchMesh, AreaSumsToTheMidpointRuleOfTheEllipse) {
  for (int n : {10, 40, 160}) {
    const PatchMesh m(n, n, 6e-3, 4e-3);
    double area = 0.0;
    for (int j = 0; j < m.ny(); ++j) area += m.nx() * m.nodeArea(j);
    EXPECT_NEAR(area, M_PI * 24e-6, 2.0 / (n * std::sqrt(n)) * M_PI * 24e-6) << n;
  }
}

TEST(PatchMesh, ScaleKeepsTheNormalisedLayout) {
  PatchMesh m(6, 5, 1.0, 2.0);
  const double xn = m.xNorm(2, 3);
  m.scale(3.0, 5.0);
  EXPECT_DOUBLE_EQ(m.xNorm(2, 3), xn);
  EXPECT_NEAR(m.nodeX(2, 3), 3.0 * xn, 1e-15);
  EXPECT_NEAR(m.stripY(3), 5.0 * m.yNorm(3), 1e-15);
}

TEST(PatchMesh, RejectsDegenerateMeshes) {
  EXPECT_THROW(PatchMesh(1, 5, 1, 1), std::invalid_argument);
  EXPECT_THROW(PatchMesh(5, 0, 1, 1), std::invalid_argument);
  EXPECT_THROW(PatchMesh(5, 5, 0, 1), std::invalid_argument);
  EXPECT_THROW(PatchMesh(5, 5, 1, -1), std::invalid_argument);
}
