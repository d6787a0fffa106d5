// The calibrated FastSim's steady creep curves against our exact solver (issue 19, item 3), on the
// cached exact curves doc/data/steady_exact_curves.csv (20x20 elements; identify_calibration made
// them and checks one point of them live here, so the cache cannot drift from the solver). FastSim
// on 20x20 nodes. Errors: max over each curve of max(|dFx|, |dFy|) / (mu fz), and for spin max
// |dMz| / peak |Mz|. Tolerances: the targets where the calibration meets them (single
// creepages 0.01, xi with eta 0.02); where it does not (combined with spin, Mz), the measured
// error with a margin, and never worse than classic FastSim where the table in
// doc/calibrated_fastsim.md says it is better.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "core/exact/halfspace_solver.hpp"
#include "validation/steady_curves.hpp"

using namespace wheel_rail_contact;

namespace {

// The tool's setup (identify_calibration.cpp): G, nu, mu, fz, sqrt(ab) = 5 mm.
constexpr double kG = 8.2e10, kNu = 0.28, kMu = 0.3, kFz = 1e4;

struct CurvePoint {
  double e;
  Creepages c;
  double fx, fy, mz;  // exact, fx, fy over mu fz, mz over mu fz sqrt(ab)
};

// Exact curves by a/b and ray.
using Curves = std::map<std::pair<double, std::string>, std::vector<CurvePoint>>;

// An exact curves file of doc/data (identify_calibration's cache).
Curves readExact(const std::string& file = "steady_exact_curves.csv") {
  Curves curves;
  for (const SteadyCurvePoint& p :
       readSteadyCurves(std::string(WRC_SOURCE_DIR) + "/doc/data/" + file))
    if (p.epsilon > 0.0) curves[{p.aOverB, p.ray}].push_back({p.epsilon, p.c, p.fx, p.fy, p.mz});
  return curves;
}

struct CurveError {
  double force = 0.0, moment = 0.0;
};

CurveError fastsimError(double ab, const std::vector<CurvePoint>& curve,
                        const PatchCalibration& cal, int nx = 20, double nu = kNu) {
  const double a = 5e-3 * std::sqrt(ab), b = 5e-3 / std::sqrt(ab);
  const CreepCoefficients k = kalkerCoefficients(ab, nu);
  const PatchMesh mesh(nx, nx, a, b);
  TractionField f;
  f.resize(mesh.size());
  double peak = 0.0;
  for (const CurvePoint& p : curve) peak = std::max(peak, std::abs(p.mz));
  CurveError err;
  const double m = kMu * kFz;
  for (const CurvePoint& p : curve) {
    // The calibrated bound's shape depends on the creepages (spin's share): set per point.
    flattenedBound(mesh, a, b, kFz, kMu, cal.boundShape(a, b, kG, k, m, p.c), &f);
    const CreepForces x = steadyFastSim(mesh, cal.flexibilities(a, b, kG, k, m, p.c), p.c, &f);
    err.force = std::max({err.force, std::abs(x.fx / m - p.fx), std::abs(x.fy / m - p.fy)});
    err.moment = std::max(err.moment, std::abs(x.mz / (m * std::sqrt(a * b)) - p.mz) / peak);
  }
  return err;
}

class CalibratedSteady : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    curves_ = readExact();
    table_ = CalibrationTable::shipped().forMesh(20);
  }
  CurveError error(double ab, const char* ray, bool calibrated) const {
    const auto it = curves_.find({ab, ray});
    EXPECT_NE(it, curves_.end()) << ab << " " << ray;
    if (it == curves_.end()) return {1.0, 1.0};
    EXPECT_GE(it->second.size(), 12u) << ab << " " << ray;
    return fastsimError(ab, it->second, calibrated ? table_.at(ab) : CalibrationTable().at(ab));
  }
  // A held-out ray's calibrated force error below `tolerance` and under half of classic's.
  void expectWithinAndUnderHalfOfClassic(double ab, const std::string& ray,
                                         double tolerance) const {
    const double cal = error(ab, ray.c_str(), true).force;
    EXPECT_LT(cal, tolerance) << ab << " " << ray;
    EXPECT_LT(cal, 0.5 * error(ab, ray.c_str(), false).force) << ab << " " << ray;
  }
  static Curves curves_;
  static CalibrationTable table_;
};
Curves CalibratedSteady::curves_;
CalibrationTable CalibratedSteady::table_;

// One partial-slip point of rays 11 and 23 at a/b = 1 re-solved at Poisson's ratio nu (about a
// second): the cached curves are the solver's own, at that nu.
void expectTheSolversOwn(const Curves& c, double nu) {
  const double ab = 1.0, a = 5e-3, b = 5e-3;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, 20, 20), kG, nu);
  s.setHertzPressure(a, b, kFz);
  for (const char* ray : {"11", "23"}) {
    const auto it = c.find({ab, std::string(ray)});
    ASSERT_NE(it, c.end()) << ray;
    const CurvePoint& p = it->second[it->second.size() / 3];
    const HalfspaceSolution& x = s.solve(RollingMode::kSteady, p.c, kMu);
    EXPECT_NEAR(x.fx / (kMu * kFz), p.fx, 2e-5) << nu << " " << ray;
    EXPECT_NEAR(x.fy / (kMu * kFz), p.fy, 2e-5) << nu << " " << ray;
  }
}

}  // namespace

TEST_F(CalibratedSteady, TheCachedExactCurvesAreTheSolversOwn) {
  expectTheSolversOwn(curves_, kNu);
}

TEST_F(CalibratedSteady, SingleCreepageCurvesWithinOnePercentOfMuFz) {
  for (double ab : {0.2, 1.0, 5.0})
    for (const char* ray : {"11", "22", "23"}) {
      const CurveError cal = error(ab, ray, true), classic = error(ab, ray, false);
      EXPECT_LT(cal.force, 0.01) << ab << " " << ray;
      EXPECT_GT(classic.force, 0.02) << ab << " " << ray;  // what the calibration removes
    }
}

TEST_F(CalibratedSteady, LongitudinalWithLateralWithinTwoPercentOfMuFz) {
  for (double ab : {0.2, 1.0, 5.0}) EXPECT_LT(error(ab, "xe", true).force, 0.02) << ab;
}

TEST_F(CalibratedSteady, CombinedWithSpinWithinTwoPercentOfMuFz) {
  // The combined correction is identified on a grid of directions (identify_calibration: spin
  // shares 0.06-0.95, xi shares 0-1, both signs of eta phi); these rays are not on it: xep (e1 = e2
  // = e3), opp (e1, -e2, e3), spin (0.3, -0.3, 1), h1 (1, 0.5, 0.8), h2 (0.4, 1, -0.7). Issue 19's
  // 0.02 mu fz; measured 0.0020-0.0136 at these a/b (opp at a/b 5 the worst; classic 0.026-0.198),
  // doc/calibrated_fastsim.md.
  for (double ab : {0.2, 1.0, 5.0})
    for (const char* ray : {"xep", "opp", "spin", "h1", "h2"}) {
      const CurveError cal = error(ab, ray, true);
      EXPECT_LT(cal.force, 0.02) << ab << " " << ray;
      EXPECT_LT(cal.force, error(ab, ray, false).force) << ab << " " << ray;
    }
}

TEST_F(CalibratedSteady, SmallSpinShareWithinTwoPercentOfMuFz) {
  // h3 (1, -1, 0.2): spin 2 % of e^2, between xi with eta (no correction) and the grid's smallest
  // spin share (0.03; 0.06 before), the weakest direction: issue 19's 0.02 for combined curves;
  // measured 0.012 / 0.010 / 0.009 at a/b 0.2 / 1 / 5 since the spin share 0.03 (0.018 / 0.016 /
  // 0.015 before it; 0.014 at a/b 0.2 before the blend's span on wide
  // patches; 0.012 / 0.010 / 0.015 before the blend's earlier start where the coupling is held;
  // 0.013 / 0.013 / 0.0200 with the lateral coupling before linear theory's spin moment held for
  // the rest of e^2; classic 0.039-0.144; 0.027 at a/b 0.2 before the bound went towards Hertz's in
  // full slip, towardsFullSlip).
  for (double ab : {0.2, 1.0, 5.0}) {
    const double cal = error(ab, "h3", true).force;
    EXPECT_LT(cal, 0.02) << ab;
    EXPECT_LT(cal, 0.5 * error(ab, "h3", false).force) << ab;
  }
}

TEST_F(CalibratedSteady, SmallSpinShareWithEtaAlongPhiWithinTwoPercentOfMuFz) {
  // h4 (0.5, 1, 0.25): spin 5 % of e^2 with eta phi > 0, held out of every choice of the
  // calibration: measured 0.014 / 0.008 / 0.003 at a/b 0.2 / 1 / 5 (classic 0.029-0.121); at a/b 5
  // 0.016, 0.60 of classic's, before the small shares' fit from e = 0.35 off the round patch, 0.010
  // before linear theory's spin moment held for the rest of e^2, which took its Mz from 5.5-15 %
  // of the peak to 2.9-6.2 % at a/b 0.5-5 (classic's); with the coupling held at small spin
  // shares 5.0 / 4.0 / 7.2 / 2.7 % at a/b 0.5 / 1 / 2 / 5, with the fit from e = 0.35 off the
  // round patch 4.4 / 2.6 / 4.0 / 3.0 / 1.7 % at a/b 0.2 / 0.5 / 1 / 2 / 5.
  for (double ab : {0.2, 1.0, 5.0}) expectWithinAndUnderHalfOfClassic(ab, "h4", 0.02);
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) EXPECT_LT(error(ab, "h4", true).moment, 0.05) << ab;
}

TEST_F(CalibratedSteady, SmallSpinSharesMomentFromEtaNearerTheExactCurve) {
  // Where spin is a small share (2-8 % of e^2) the moment is mostly eta's, carried by the lateral
  // coupling: held there (PatchCalibration::heldCoupling) rather than faded with spin's share,
  // with the bound going towards Hertz's shape sooner where it is held (fullSlipFrom) and on wide
  // and long patches (wideness), and with the correction's small spin shares, the six such rays'
  // Mz is within issue 19's 5 % of the peak on all 30 curves: measured mean 2.5 %, worst 4.8 % (h4
  // at a/b 0.2); faded with spin's share instead, half of them were above
  // (doc/calibrated_fastsim.md, "What it is", items 6 and 8).
  int above = 0;
  double sum = 0.0, worst = 0.0;
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (const char* ray : {"h3", "h4", "h7", "r1", "r2", "r10"}) {
      const double m = error(ab, ray, true).moment;
      above += m > 0.05;
      sum += m;
      worst = std::max(worst, m);
    }
  EXPECT_EQ(above, 0);
  EXPECT_LT(sum / 30.0, 0.028);
  EXPECT_LT(worst, 0.05);
}

TEST_F(CalibratedSteady, SpinSharesBetweenTheSmallKnotsWithinTwoPercentOfMuFz) {
  // h5 (1, 0.6, -0.5), spin 15.5 % of e^2 with eta phi < 0 (between the knots 0.1 and 0.175), and
  // h6 (0.8, 0.8, 0.55), 19 % with eta phi > 0 (between 0.175 and 0.25), held out: measured
  // 0.005-0.008 and 0.002-0.005 (0.029-0.042 and 0.013-0.020 with the knots from 0.25 only; classic
  // 0.094-0.172 and 0.030-0.106). Their moment within issue 19's 5 % of the peak: measured
  // 1.4-4.5 % and 0.7-2.1 % (h5 at a/b 1 5.1 % before the correction's knots 3.75 and 5.5, at
  // e = 6).
  for (double ab : {0.2, 1.0, 5.0})
    for (const char* ray : {"h5", "h6"}) expectWithinAndUnderHalfOfClassic(ab, ray, 0.02);
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (const char* ray : {"h5", "h6"})
      EXPECT_LT(error(ab, ray, true).moment, 0.05) << ab << " " << ray;
}

TEST_F(CalibratedSteady, SpinSharesBelowTheFirstKnotWithinTwoPercentOfMuFz) {
  // h7 (0.6, 1, -0.33), spin 7.4 % of e^2 with eta phi < 0, and h8 (1, 0.4, 0.3), 7.2 % with
  // eta phi > 0 and xi 86 % of the rest, held out between h4 and the knot 0.1: measured
  // 0.004-0.012 and 0.003-0.015 (0.010-0.024 and 0.010-0.025 before the spin share 0.06 and the
  // xi share 0.875; classic 0.055-0.196 and 0.037-0.091).
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (const char* ray : {"h7", "h8"}) expectWithinAndUnderHalfOfClassic(ab, ray, 0.02);
}

TEST_F(CalibratedSteady, DirectionsSpreadBetweenTheGridsWithinTwoPercentOfMuFz) {
  // r1-r46: held-out directions between the grid's (spin shares 0.03-0.97, xi shares 0-1, both
  // signs of eta phi): r1-r16 placed by hand, r17-r28, r29-r40 and r41-r46 (spin shares
  // 0.03-0.1) drawn at random (r29-r40 after the grid and its smoothing were chosen, r41-r46
  // after the grid's spin and xi shares were chosen), so they test the interpolation between the
  // correction's directions, not the fit on them. Issue 19's 0.02 on every one, measured on 20x20
  // 0.001-0.017 (classic 0.011-0.214); under half of classic's wherever classic misses the target.
  // Mz within issue 19's 5 % of the peak, measured 0.2-4.6 % (doc/calibrated_fastsim.md, "Steady
  // accuracy"; the grid and its smoothing: "How it is identified").
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
    for (int r = 1; r <= 46; ++r) {
      const std::string ray = "r" + std::to_string(r);
      const CurveError cal = error(ab, ray.c_str(), true);
      const double classic = error(ab, ray.c_str(), false).force;
      EXPECT_LT(cal.force, 0.02) << ab << " " << ray;
      if (classic > 0.02) {
        EXPECT_LT(cal.force, 0.5 * classic) << ab << " " << ray;
      }
      EXPECT_LT(cal.moment, 0.05) << ab << " " << ray;
    }
}

TEST_F(CalibratedSteady, MomentFromEtaFollowsTheExactCurve) {
  // Without spin FastSim's saturated traction has one direction, so its moment from eta vanishes in
  // full slip where exact theory's decays as 1 / e (Poisson's ratio), and in linear theory it is
  // (3 pi a / 32) Fy against Kalker's sqrt(ab) C23 / C22 Fy: classic 15-51 % of the peak for eta
  // alone, 18-45 % for xi = eta. The lateral coupling (kind 22c) carries it, with xi beside eta
  // the slope of eta's drive (kind 22b), and without spin eta's own set (22n, 22cn, 22s): measured
  // 2.2 / 0.6 / 0.6 / 0.6 / 2.3 % for eta alone and 4.5 / 2.7 / 2.8 / 1.7 / 3.1 % for xi = eta at
  // a/b 0.2 / 0.5 / 1 / 2 / 5 (0.7-1.8 / 6.8 % and 2.5-4.8 / 5.7 % with the pair 22, 22c at every
  // share of spin), the forces within the single-creepage target and xi with eta's.
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) {
    const CurveError eta = error(ab, "22", true), both = error(ab, "xe", true);
    EXPECT_LT(eta.moment, 0.03) << ab;
    EXPECT_LT(both.moment, ab < 0.3 ? 0.05 : 0.035) << ab;
    EXPECT_LT(eta.moment, 0.5 * error(ab, "22", false).moment) << ab;
    EXPECT_LT(both.moment, 0.4 * error(ab, "xe", false).moment) << ab;
    EXPECT_LT(eta.force, 0.01) << ab;
    EXPECT_LT(both.force, 0.02) << ab;
  }
}

TEST_F(CalibratedSteady, CombinedWithSpinMomentNearTheExactPeak) {
  // Mz over the exact curve's peak |Mz| on the same rays, issue 19's 5 %: measured 0.3-2.8 %
  // (classic 7-18 %).
  for (double ab : {0.2, 1.0, 5.0})
    for (const char* ray : {"xep", "opp", "spin", "h1", "h2"})
      EXPECT_LT(error(ab, ray, true).moment, 0.05) << ab << " " << ray;
}

TEST_F(CalibratedSteady, LinearSpinMomentIsTheExactSolversAtEveryShareOfSpin) {
  // Near linear theory (e = 0.05: forces 5 % of mu fz) spin's moment comes from its longitudinal
  // drive alone, phi 8 a^2 b^3 / (15 L3x): with L3x = L3 (classic) it misses C33, by 2-64 % of the
  // exact moment at a/b 0.2-5. 23x's knot 0 holds at every share of spin: measured pure spin
  // within 0.7 %; the rays whose spin is 2-8 % of e^2 (h3, h4, h7, r1, r2, r10) within 4.5 % since
  // the coupling is held at small spin shares (11.5 % before; classic 2-28 %): the rest of their
  // moment is eta's, the coupling's.
  auto atLinear = [&](double ab, const char* ray, bool calibrated) {
    const auto it = curves_.find({ab, ray});
    EXPECT_NE(it, curves_.end()) << ab << " " << ray;
    if (it == curves_.end()) return 1.0;
    const std::vector<CurvePoint> first{it->second.front()};
    EXPECT_EQ(first.front().e, 0.05) << ab << " " << ray;
    return fastsimError(ab, first, calibrated ? table_.at(ab) : CalibrationTable().at(ab))
        .moment;  // over the point's own exact |Mz|
  };
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) {
    EXPECT_LT(atLinear(ab, "23", true), 0.01) << ab;
    EXPECT_LT(atLinear(ab, "23", true), 0.5 * atLinear(ab, "23", false)) << ab;
    for (const char* ray : {"h3", "h4", "h7", "r1", "r2", "r10"})
      EXPECT_LT(atLinear(ab, ray, true), 0.05) << ab << " " << ray;
  }
}

TEST_F(CalibratedSteady, SpinMomentWithinFivePercentOfThePeak) {
  // Pure spin, the target: measured 2.9 / 2.7 / 2.8 % at a/b 0.2 / 1 / 5 (the flatter
  // bound and spin's second parameter, calibration_table.hpp).
  for (double ab : {0.2, 1.0, 5.0}) EXPECT_LT(error(ab, "23", true).moment, 0.05) << ab;
}

TEST_F(CalibratedSteady, SpinMomentNoWorseThanClassic) {
  // Pure spin: Mz within 14 % of the peak (classic 10-18 %).
  for (double ab : {0.2, 1.0, 5.0}) {
    const double cal = error(ab, "23", true).moment, classic = error(ab, "23", false).moment;
    EXPECT_LT(cal, 0.14) << ab;
    EXPECT_LE(cal, classic + 1e-3) << ab;
  }
}

TEST_F(CalibratedSteady, EachMeshsTableMeetsTheSingleCreepageTargetOnItsOwnMesh) {
  // identify_calibration --nx 5,10,20,30,40: one table per FastSim mesh, each identified on that
  // mesh against the same exact curves; on the cached curves (the knots and 12 points between them,
  // linear theory to full slip), on its own mesh: issue 19's 0.01 mu fz for xi and eta on every
  // mesh and for spin from 20x20 on. Spin on the coarse meshes is FastSim's own limit there (5
  // nodes per strip cannot carry both the spin force and moment): at most 0.037 at 5x5 and 0.011
  // at 10x10 (the 20x20 table there: 0.053-0.107 and 0.024-0.039 on the 12 points),
  // doc/calibrated_fastsim.md "Per-mesh tables".
  const CalibrationTable shipped = CalibrationTable::shipped();
  ASSERT_EQ(shipped.meshes(), (std::vector<int>{5, 10, 20, 30, 40}));
  for (int nx : shipped.meshes()) {
    const CalibrationTable t = shipped.forMesh(nx);
    for (double ab : {0.2, 1.0, 5.0})
      for (const char* ray : {"11", "22", "23"}) {
        const auto it = curves_.find({ab, ray});
        ASSERT_NE(it, curves_.end()) << ab << " " << ray;
        const bool coarseSpin = std::string(ray) == "23" && nx < 20;
        const double bound = !coarseSpin ? 0.01 : nx == 5 ? 0.04 : 0.0125;
        EXPECT_LT(fastsimError(ab, it->second, t.at(ab), nx).force, bound)
            << nx << "x" << nx << " " << ab << " " << ray;
      }
    // Eta's moment, which the lateral coupling and eta's own set without spin carry, within
    // issue 19's 5 % of the peak on every mesh, xi with eta too: measured eta 0.4-3.4 %, xi = eta
    // 1.4-4.5 % (eta on 10x10 at a/b 5 7.1 % while the set's pull towards the pair kept the pair).
    for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
      for (const char* ray : {"22", "xe"}) {
        const auto it = curves_.find({ab, ray});
        ASSERT_NE(it, curves_.end()) << ab << " " << ray;
        const double m = fastsimError(ab, it->second, t.at(ab), nx).moment;
        EXPECT_LT(m, 0.05) << nx << "x" << nx << " " << ab << " " << ray;
      }
  }
}

TEST_F(CalibratedSteady, MeshesBetweenTheTablesAreNearerTheExactCurvesInterpolated) {
  // A mesh between two identified ones takes their ratios interpolated in 1/nx (forMesh), not the
  // nearest mesh's. On every cached curve (the rays and the correction's grid directions, a/b
  // 0.2-5) at 12x12 and 13x13 (nearest: 10x10), measured: single creepages at most 0.027 / 0.054
  // mu fz on the nearest table, 0.017 / 0.026 interpolated; curves above 0.02 mu fz 116 / 428
  // against 35 / 123 of 1410 (doc/calibrated_fastsim.md, "Per-mesh tables"). Neither meets issue
  // 19's targets for spin there: an identified mesh does.
  const CalibrationTable shipped = CalibrationTable::shipped();
  for (const int nx : {12, 13}) {
    const CalibrationTable between = shipped.forMesh(nx), nearest = shipped.forMesh(10);
    ASSERT_EQ(between.meshes(), (std::vector<int>{nx}));
    double single[2] = {0.0, 0.0};
    int misses[2] = {0, 0};
    for (const auto& [key, curve] : curves_) {
      const auto& [ab, ray] = key;
      const bool one = ray == "11" || ray == "22" || ray == "23";
      const double err[2] = {fastsimError(ab, curve, between.at(ab), nx).force,
                             fastsimError(ab, curve, nearest.at(ab), nx).force};
      for (int i = 0; i < 2; ++i) {
        if (one) single[i] = std::max(single[i], err[i]);
        misses[i] += err[i] > 0.02;
      }
    }
    EXPECT_LT(single[0], 0.7 * single[1]) << nx << "x" << nx;
    EXPECT_LT(single[0], 0.03) << nx << "x" << nx;
    EXPECT_LT(misses[0], misses[1] / 2) << nx << "x" << nx;
  }
}

TEST(CalibratedSteadyAtOtherNu, TheTableIdentifiedAtNu028HoldsOverSteelsRange) {
  // The table is identified at nu 0.28 and applied at any nu on that nu's own Kalker
  // coefficients (doc/calibrated_fastsim.md, "Other Poisson's ratios"). Against the exact curves
  // solved at 0.25 and 0.30 (identify_calibration --nu NU --exact
  // doc/data/steady_exact_curves_nuNU.csv; re-solved at two points here), every ray at a/b
  // 0.2-5: forces within issue 19's targets as at 0.28 (measured single creepages 0.0071 /
  // 0.0091, combined 0.019 / 0.017; r10 at a/b 0.2 0.0188 / 0.0214 before spin's share 0.045 and
  // xi's 0.9375, 0.004 / 0.003 now), and under half of classic's wherever classic misses the
  // target (r25 at a/b 5: 0.49 / 0.47 of it); pure spin's Mz within 5 % (2.6-2.9 %); eta's moment,
  // which the lateral coupling and eta's set without spin carry (identified at 0.28), within
  // 4.5 % at a/b 0.5-5 and 5.5 % at a/b 0.2 (measured 5.0 / 3.4 % there, up to 2.7 % elsewhere),
  // and xi = eta's, which the slope of eta's drive carries besides, within 5.5 % (measured up to
  // 4.9 / 2.8 %, at a/b 0.2).
  const CalibrationTable table = CalibrationTable::shipped().forMesh(20);
  for (const double nu : {0.25, 0.30}) {
    char file[64];
    std::snprintf(file, sizeof file, "steady_exact_curves_nu%.2f.csv", nu);
    const Curves curves = readExact(file);
    expectTheSolversOwn(curves, nu);
    ASSERT_EQ(curves.size(), 5u * 61u) << file;
    for (const auto& [key, curve] : curves) {
      const auto& [ab, ray] = key;
      EXPECT_EQ(curve.size(), 12u) << nu << " " << ab << " " << ray;
      const CurveError cal = fastsimError(ab, curve, table.at(ab), 20, nu);
      const CurveError classic = fastsimError(ab, curve, CalibrationTable().at(ab), 20, nu);
      const bool single = ray == "11" || ray == "22" || ray == "23";
      EXPECT_LT(cal.force, single ? 0.01 : 0.02) << nu << " " << ab << " " << ray;
      if (classic.force > 0.02) {
        EXPECT_LT(cal.force, 0.5 * classic.force) << nu << " " << ab << " " << ray;
      }
      if (ray == "23") {
        EXPECT_LT(cal.moment, 0.05) << nu << " " << ab;
      }
      if (ray == "22") {
        EXPECT_LT(cal.moment, ab < 0.3 ? 0.055 : 0.045) << nu << " " << ab;
      }
      if (ray == "xe") {
        EXPECT_LT(cal.moment, 0.055) << nu << " " << ab;
      }
    }
  }
}
