#include <gtest/gtest.h>

#include <cmath>

#include "core/exact/halfspace_influence.hpp"

using namespace wheel_rail_contact;

namespace {

const double kG = 8.2e10, kNu = 0.28;

// Relative displacement of two bodies under a point force Q_x (Cerruti, twice one body's).
double pointXX(double x, double y) {
  const double r = std::hypot(x, y);
  return 2.0 / (2.0 * M_PI * kG) * ((1.0 - kNu) / r + kNu * x * x / (r * r * r));
}
double pointXY(double x, double y) {
  const double r = std::hypot(x, y);
  return 2.0 / (2.0 * M_PI * kG) * kNu * x * y / (r * r * r);
}

}  // namespace

TEST(HalfspaceInfluence, SymmetriesOfTheKernel) {
  const InfluenceKernel k(HalfspaceGrid{10, 8, 1e-3, 2e-3}, kG, kNu);
  for (int di = -9; di <= 9; ++di)
    for (int dj = -7; dj <= 7; ++dj) {
      EXPECT_DOUBLE_EQ(k.xx(di, dj), k.xx(-di, dj));
      EXPECT_DOUBLE_EQ(k.yy(di, dj), k.yy(di, -dj));
      EXPECT_NEAR(k.xy(di, dj), -k.xy(-di, dj), 1e-12 * k.xx(0, 0));
      EXPECT_GT(k.xx(di, dj), 0.0);
    }
  EXPECT_EQ(k.xy(0, 0), 0.0);
  EXPECT_EQ(k.xy(3, 0), 0.0);
  EXPECT_GT(k.xx(0, 0), k.xx(1, 0));
}

TEST(HalfspaceInfluence, FarFieldIsThePointForceTimesTheArea) {
  // 20 cells away the closed form must agree with the point force to O((h/r)^2) ~ 1e-3.
  const HalfspaceGrid g{41, 41, 1e-3, 1.5e-3};
  const InfluenceKernel k(g, kG, kNu);
  const double A = g.dx * g.dy;
  EXPECT_NEAR(k.xx(20, 13), A * pointXX(20 * g.dx, 13 * g.dy), 1e-3 * k.xx(20, 13));
  EXPECT_NEAR(k.xy(20, 13), A * pointXY(20 * g.dx, 13 * g.dy), 1e-3 * std::abs(k.xy(20, 13)));
}

TEST(HalfspaceInfluence, NeighbourMatchesNumericalQuadrature) {
  // Midpoint rule with 400 x 400 points over the source element, field point one cell away
  // diagonally (no singularity): agreement to 1e-5 relative checks the primitives.
  const HalfspaceGrid g{5, 5, 1e-3, 2e-3};
  const InfluenceKernel k(g, kG, kNu);
  const int n = 400;
  double xx = 0.0, xy = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double sx = (i + 0.5) / n * g.dx - 0.5 * g.dx, sy = (j + 0.5) / n * g.dy - 0.5 * g.dy;
      xx += pointXX(g.dx - sx, g.dy - sy);
      xy += pointXY(g.dx - sx, g.dy - sy);
    }
  const double w = g.dx * g.dy / (n * n);
  EXPECT_NEAR(k.xx(1, 1), xx * w, 1e-5 * k.xx(1, 1));
  EXPECT_NEAR(k.xy(1, 1), xy * w, 1e-5 * std::abs(k.xy(1, 1)));
}

TEST(HalfspaceInfluence, GridConvergenceOnJohnsonsTraction) {
  // tau_x = q0 sqrt(1 - r^2/a^2) on a circle gives, per body, u_x(0) = pi q0 (2 - nu) a / (8 G)
  // (Johnson, Contact Mechanics, eq. 7.40 at the centre). Elements take the traction at their
  // centre; the error must fall as the grid is refined (10, 20, 40 cells across 2.2a).
  const double a = 1e-3, q0 = 1e8;
  const double exact = 2.0 * M_PI * q0 * (2.0 - kNu) * a / (8.0 * kG);
  double previous = 1e9;
  for (int m : {11, 21, 41}) {  // odd: an element centred on the origin
    const HalfspaceGrid g = HalfspaceGrid::covering(a, a, m, m);
    const InfluenceKernel k(g, kG, kNu);
    const int c = m / 2;
    double u = 0.0;
    for (int ix = 0; ix < m; ++ix)
      for (int iy = 0; iy < m; ++iy) {
        const double r2 = (g.xc(ix) * g.xc(ix) + g.yc(iy) * g.yc(iy)) / (a * a);
        if (r2 < 1.0) u += k.xx(c - ix, c - iy) * q0 * std::sqrt(1.0 - r2);
      }
    const double err = std::abs(u / exact - 1.0);
    EXPECT_LT(err, previous) << "m = " << m;
    previous = err;
  }
  EXPECT_LT(previous, 0.01);
}
