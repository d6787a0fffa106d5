#include <gtest/gtest.h>

#include <cmath>

#include "wheel_rail_contact/halfspace_normal.hpp"
#include "wheel_rail_contact/hertz.hpp"

using namespace wheel_rail_contact;

TEST(HalfspaceNormal, CurvaturesInvertHertz) {
  for (double ab : {0.2, 1.0, 3.0}) {
    const double a = 6e-3, b = a / ab, fz = 8e4;
    double A, B;
    hertzCurvatures(a, b, fz, 8.2e10, 0.28, &A, &B);
    const HertzEllipse h = hertzFromCurvatures(fz, A, B, 8.2e10, 0.28);
    EXPECT_NEAR(h.a, a, 1e-9 * a) << ab;
    EXPECT_NEAR(h.b, b, 1e-9 * b) << ab;
  }
}

TEST(HalfspaceNormal, DiscreteHertzCarriesTheLoadOnTheEllipse) {
  // 30 x 30 elements: the load is met exactly, the loaded elements lie within one element of the
  // ellipse, and the peak pressure is within 3 % of Hertz's p0 (piecewise-constant pressure).
  const double a = 6e-3, b = 4e-3, fz = 8e4;
  const HalfspaceGrid g = HalfspaceGrid::covering(a, b, 30, 30);
  const Eigen::VectorXd p = hertzianGridPressure(g, a, b, fz, 8.2e10, 0.28);
  EXPECT_NEAR(p.sum() * g.dx * g.dy, fz, 1e-9 * fz);
  EXPECT_NEAR(p.maxCoeff(), 3.0 * fz / (2.0 * M_PI * a * b), 0.03 * p.maxCoeff());
  int loaded = 0;
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy) {
      if (!(p[g.index(ix, iy)] > 0.0)) continue;
      ++loaded;
      const double x = std::abs(g.xc(ix)) - g.dx, y = std::abs(g.yc(iy)) - g.dy;
      EXPECT_LT(std::max(x, 0.0) * std::max(x, 0.0) / (a * a) +
                    std::max(y, 0.0) * std::max(y, 0.0) / (b * b),
                1.0);
      EXPECT_DOUBLE_EQ(p[g.index(ix, iy)], p[g.index(ix, g.my - 1 - iy)]);
    }
  EXPECT_NEAR(loaded * g.dx * g.dy, M_PI * a * b, 0.05 * M_PI * a * b);
}
