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

namespace {

Eigen::VectorXd hertzGap(const HalfspaceGrid& g, double A, double B) {
  Eigen::VectorXd h(g.size());
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy)
      h[g.index(ix, iy)] = A * g.xc(ix) * g.xc(ix) + B * g.yc(iy) * g.yc(iy);
  return h;
}

}  // namespace

TEST(HalfspaceNormal, GeneralGapSolverReproducesTheHertzSolverOnAHertzGap) {
  // The contact problem has one solution: from a different start set the general solver must
  // find the same loaded elements, pressures and approach (to rounding of the direct solves).
  const double a = 6e-3, b = 4e-3, fz = 8e4, G = 8.2e10, nu = 0.28;
  double A, B;
  hertzCurvatures(a, b, fz, G, nu, &A, &B);
  const HalfspaceGrid g = HalfspaceGrid::covering(a, b, 24, 24);
  const NormalSolution ref = solveNormalProblem(g, G, nu, A, B, fz, a, b);
  const NormalSolution gen = solveNormalGapLoad(g, G, nu, hertzGap(g, A, B), fz);
  ASSERT_TRUE(ref.converged);
  ASSERT_TRUE(gen.converged);
  EXPECT_NEAR(gen.approach, ref.approach, 1e-9 * ref.approach);
  EXPECT_NEAR(gen.fz, fz, 1e-9 * fz);
  EXPECT_NEAR((gen.p - ref.p).cwiseAbs().maxCoeff(), 0.0, 1e-9 * ref.p.maxCoeff());
}

TEST(HalfspaceNormal, PrescribedApproachNeedsTheLoadThatGivesThatApproach) {
  // Load -> approach -> load: the approach a load solve returns, prescribed, carries that load
  // on the same elements; a smaller approach carries less, and no approach carries nothing.
  const double G = 8.2e10, nu = 0.28;
  const HalfspaceGrid g = HalfspaceGrid::covering(5e-3, 7e-3, 24, 24);
  Eigen::VectorXd h(g.size());  // not Hertz: a flat-bottomed lateral profile and x^2 / (2 R)
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy) {
      const double y = g.yc(iy), x = g.xc(ix);
      h[g.index(ix, iy)] =
          x * x / (2 * 0.46) + 2e3 * std::pow(std::max(std::abs(y) - 2e-3, 0.0), 3);
    }
  const double fz = 6e4;
  const NormalSolution byLoad = solveNormalGapLoad(g, G, nu, h, fz);
  ASSERT_TRUE(byLoad.converged);
  const NormalSolution byApproach = solveNormalGapApproach(g, G, nu, h, byLoad.approach);
  ASSERT_TRUE(byApproach.converged);
  EXPECT_NEAR(byApproach.fz, fz, 1e-8 * fz);
  EXPECT_NEAR((byApproach.p - byLoad.p).cwiseAbs().maxCoeff(), 0.0, 1e-8 * byLoad.p.maxCoeff());
  const NormalSolution half = solveNormalGapApproach(g, G, nu, h, 0.5 * byLoad.approach);
  EXPECT_GT(half.fz, 0.0);
  EXPECT_LT(half.fz, fz);
  const NormalSolution none = solveNormalGapApproach(g, G, nu, h, h.minCoeff() - 1e-9);
  EXPECT_TRUE(none.converged);
  EXPECT_EQ(none.fz, 0.0);
}
