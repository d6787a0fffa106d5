#include <gtest/gtest.h>

#include <cmath>

#include "core/exact/halfspace_normal.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

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

TEST(HalfspaceNormal, PatchFollowsTheLoadOnAFixedGrid) {
  // The reference patch scaled as (fz/fz0)^(1/3) has fixed curvatures (the undeformed distance
  // does not change with the load), and on one grid the loaded area grows as fz^(2/3) (within
  // 8 %, whole elements on a 24 x 24 grid).
  const ReferencePatch ref{6e-3, 4e-3, 8e4};
  double A0, B0;
  hertzCurvatures(ref.a0, ref.b0, ref.fz0, 8.2e10, 0.28, &A0, &B0);
  const HertzEllipse big = ref.at(1.5 * ref.fz0);
  const HalfspaceGrid g = HalfspaceGrid::covering(big.a, big.b, 24, 24);
  for (double f : {0.4, 1.0, 1.5}) {
    const HertzEllipse h = ref.at(f * ref.fz0);
    double A, B;
    hertzCurvatures(h.a, h.b, f * ref.fz0, 8.2e10, 0.28, &A, &B);
    EXPECT_NEAR(A, A0, 1e-9 * A0);
    EXPECT_NEAR(B, B0, 1e-9 * B0);
    const Eigen::VectorXd p = hertzianGridPressure(g, h.a, h.b, f * ref.fz0, 8.2e10, 0.28);
    const double area = (p.array() > 0.0).count() * g.dx * g.dy;
    EXPECT_NEAR(area, M_PI * h.a * h.b, 0.08 * M_PI * h.a * h.b) << f;
  }
}
