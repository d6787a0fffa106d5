#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/exact/halfspace_normal.hpp"
#include "core/exact/halfspace_solver.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

const double kG = 8.2e10, kNu = 0.28;

double coefficient(const HalfspaceSolution& s, CreepageKind k, double a, double b, double c) {
  const double f = k == CreepageKind::kXi ? s.fx : s.fy;
  const double norm = k == CreepageKind::kPhi ? std::pow(a * b, 1.5) : a * b;
  return -f / (kG * norm * c);
}

}  // namespace

TEST(HalfspaceSolver, SteadyAdhesionEqualsTheFoldedCoefficients) {
  // The full solver and the y-folded linear system of nonsteady_coefficients are two codings of
  // the same discrete scheme: equal to rounding (1e-9).
  const double a = 5e-3, b = 2.5e-3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 20, 20), kG, kNu);
  s.setHertzPressure(a, b, 1e4);
  const double c = 1e-7;
  for (CreepageKind k : kCreepageKinds) {
    const Creepages w{k == CreepageKind::kXi ? c : 0.0, k == CreepageKind::kEta ? c : 0.0,
                      k == CreepageKind::kPhi ? c : 0.0};
    const HalfspaceSolution& r = s.solve(RollingMode::kSteady, w, 1e9);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_DOUBLE_EQ(r.adhesionFraction, 1.0);
    const double ref = exactSteadyCoefficient(k, a / b, kNu, 20, 20);
    EXPECT_NEAR(coefficient(r, k, a, b, c), ref, 1e-9 * ref) << toString(k);
  }
}

TEST(HalfspaceSolver, SignConventionPositiveCreepageNegativeForce) {
  const double a = 5e-3, b = 5e-3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 16, 16), kG, kNu);
  s.setHertzPressure(a, b, 1e4);
  EXPECT_LT(s.solve(RollingMode::kSteady, {1e-4, 0, 0}, 0.3).fx, 0.0);
  EXPECT_LT(s.solve(RollingMode::kSteady, {0, 1e-4, 0}, 0.3).fy, 0.0);
  EXPECT_LT(s.solve(RollingMode::kSteady, {0, 0, 1e-2}, 0.3).fy, 0.0);
}

TEST(HalfspaceSolver, TransientFromRestApproachesSteadyRolling) {
  // Partial slip (xi = 1e-3, mu = 0.3): after 12a of rolling from rest the transient force equals
  // the steady one to 1e-4 of mu fz (start-up decays with an e-folding length of about 1.1a).
  const double a = 5e-3, b = 5e-3, fz = 1e4, mu = 0.3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 16, 16), kG, kNu);
  s.setHertzPressure(a, b, fz);
  const Creepages w{2e-4, 5e-5, 0.05};
  const HalfspaceSolution steady = s.solve(RollingMode::kSteady, w, mu);
  ASSERT_TRUE(steady.converged);
  EXPECT_GT(steady.adhesionFraction, 0.2);
  EXPECT_LT(steady.adhesionFraction, 0.95);
  const int steps = static_cast<int>(12.0 * a / s.grid().dx);
  for (int k = 0; k < steps; ++k) ASSERT_TRUE(s.solve(RollingMode::kTransient, w, mu).converged);
  EXPECT_NEAR(s.solution().fx, steady.fx, 1e-4 * mu * fz);
  EXPECT_NEAR(s.solution().fy, steady.fy, 1e-4 * mu * fz);
  EXPECT_NEAR(s.solution().mz, steady.mz, 1e-4 * mu * fz * a);
}

TEST(HalfspaceSolver, ComplementarityHoldsElementWise) {
  // Coulomb's conditions per element, after a few transient steps in partial slip with spin:
  // adhesion elements inside the disc with zero slip (to 1e-6 of the creepage: the sweeps stop at
  // 1e-8 relative traction change), slip elements on the disc with the traction opposite to the
  // slip (cosine -1 to 1e-6), exterior elements free of traction.
  const double a = 5e-3, b = 3e-3, fz = 1e4, mu = 0.3, xi = 2e-4;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 20, 20), kG, kNu);
  s.setHertzPressure(a, b, fz);
  for (int k = 0; k < 5; ++k) s.solve(RollingMode::kTransient, {xi, -1e-4, 0.05}, mu);
  const HalfspaceSolution& r = s.solution();
  ASSERT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 0);
  const Eigen::VectorXd p = hertzianGridPressure(s.grid(), a, b, fz, kG, kNu);
  int slip = 0, adhesion = 0;
  for (int k = 0; k < s.grid().size(); ++k) {
    const double t = std::hypot(r.tx[k], r.ty[k]), v = std::hypot(r.sx[k], r.sy[k]);
    if (r.state[k] == ElementState::kExterior) {
      EXPECT_EQ(t, 0.0);
    } else if (r.state[k] == ElementState::kAdhesion) {
      ++adhesion;
      EXPECT_LT(t, mu * p[k]);
      EXPECT_LT(v, 1e-6 * xi) << k;
    } else {
      ++slip;
      EXPECT_NEAR(t, mu * p[k], 1e-9 * mu * p[k]);
      EXPECT_GT(v, 0.0);
      EXPECT_LT((r.tx[k] * r.sx[k] + r.ty[k] * r.sy[k]) / (t * v), -1.0 + 1e-6) << k;
    }
  }
  EXPECT_GT(slip, 5);
  EXPECT_GT(adhesion, 5);
}

TEST(HalfspaceSolver, FullSlidingGivesMuFz) {
  const double a = 5e-3, b = 5e-3, fz = 1e4, mu = 0.3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 16, 16), kG, kNu);
  s.setHertzPressure(a, b, fz);
  const HalfspaceSolution& r = s.solve(RollingMode::kTransient, {0.1, 0, 0}, mu);
  // Every element at its bound: sum |tau| dA = mu fz exactly; the directions turn slightly from x
  // (the xy coupling of the bodies), so Fx is mu fz to 1e-5.
  double sum = 0.0;
  for (int k = 0; k < s.grid().size(); ++k) sum += std::hypot(r.tx[k], r.ty[k]);
  EXPECT_NEAR(sum * s.grid().dx * s.grid().dy, mu * fz, 1e-9 * mu * fz);
  EXPECT_NEAR(r.fx, -mu * fz, 1e-5 * mu * fz);
  EXPECT_DOUBLE_EQ(r.adhesionFraction, 0.0);
}

TEST(HalfspaceSolver, ReportsNonConvergenceAtTheIterationCap) {
  SolverControl c;
  c.maxIterations = 2;
  const double a = 5e-3, b = 5e-3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 16, 16), kG, kNu, c);
  s.setHertzPressure(a, b, 1e4);
  const HalfspaceSolution& r = s.solve(RollingMode::kTransient, {1e-3, 0, 0}, 0.3);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 2);
}

TEST(HalfspaceSolver, CattaneoShiftFromRestConverges) {
  // Cattaneo-Mindlin, two identical spheres, nu = 0 (then the solution is exact): a tangential
  // shift d of the pair gives F = mu fz (1 - (1 - d/d_s)^(3/2)) with the sliding shift
  // d_s = 3 mu fz (2 - nu) / (8 G a) (twice one body's). The error must fall as the grid is
  // refined and be below 1.5 % at 32 x 32.
  const double a = 5e-3, fz = 1e4, mu = 0.3, nu = 0.0;
  const double ds = 3.0 * mu * fz * (2.0 - nu) / (8.0 * kG * a), d = 0.5 * ds;
  const double exact = mu * fz * (1.0 - std::pow(1.0 - d / ds, 1.5));
  double previous = 1.0;
  for (int m : {12, 20, 32}) {
    HalfspaceSolver s(HalfspaceGrid::covering(a, a, m, m), kG, nu);
    s.setHertzPressure(a, a, fz);
    const HalfspaceSolution& r = s.solve(RollingMode::kShift, {1.0, 0, 0}, mu, d);
    ASSERT_TRUE(r.converged);
    const double err = std::abs(-r.fx / exact - 1.0);
    EXPECT_LT(err, previous) << m;
    previous = err;
  }
  EXPECT_LT(previous, 0.015);
}

TEST(HalfspaceSolver, ElongatedPatchApproachesCarter) {
  // b = 12a: each lateral strip rolls like Carter's 2-D cylinder with local half-width a(y) and
  // peak pressure p(y): F(y) = mu N(y) (1 - (1 - xi/xi_c(y))^2), xi_c = 2 (1 - nu) mu p(y) / G.
  // Integrated over y, the steady 3-D solution must agree within 4 % (3-D end effects and a
  // 16-element strip).
  const double a = 2e-3, b = 24e-3, fz = 2e4, mu = 0.3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 16, 24), kG, kNu);
  s.setHertzPressure(a, b, fz);
  const double p0 = 3.0 * fz / (2.0 * M_PI * a * b);
  for (double ratio : {0.3, 0.7}) {
    const double xi = ratio * 2.0 * (1.0 - kNu) * mu * p0 / kG;
    double carter = 0.0;
    const int n = 2000;
    for (int j = 0; j < n; ++j) {
      const double y = -b + (j + 0.5) * 2.0 * b / n, f = std::sqrt(1.0 - y * y / (b * b));
      const double N = M_PI * a * f * p0 * f / 2.0, xic = 2.0 * (1.0 - kNu) * mu * p0 * f / kG;
      const double r = std::min(xi / xic, 1.0);
      carter += mu * N * (1.0 - (1.0 - r) * (1.0 - r)) * 2.0 * b / n;
    }
    const HalfspaceSolution& r = s.solve(RollingMode::kSteady, {xi, 0, 0}, mu);
    ASSERT_TRUE(r.converged);
    EXPECT_NEAR(-r.fx, carter, 0.04 * carter) << ratio;
  }
}
