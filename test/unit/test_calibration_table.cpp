// The calibrated FastSim's table (calibration_table.hpp) and the `fastsim` parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "core/calibration/correction_lanes.hpp"
#include "core/fastsim/patch_mesh.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"

using namespace wheel_rail_contact;

namespace {

std::string writeTable(const std::string& body) {
  const std::string path = testing::TempDir() + "steady_calibration_test.csv";
  std::ofstream(path) << body;
  return path;
}

const char* const kTwoRows =
    "# test table\n"
    "a_over_b,kind,epsilon,ratio,fit_error\n"
    "0.5,11,0,1,0\n0.5,11,1,2,0\n0.5,22,0,1,0\n0.5,22,1,0.5,0\n0.5,23,0,1,0\n0.5,23,2,3,0\n"
    "2,11,0,1,0\n2,11,1,4,0\n2,22,0,1,0\n2,22,1,0.5,0\n2,23,0,1,0\n2,23,2,1,0\n";

// The round patch the flexibility tests step on: a = b = 5 mm, steel, mu fz = 3 kN, nu 0.28.
struct RoundPatch {
  double a = 5e-3, b = 5e-3, G = 8.2e10, muFz = 3e3;
  CreepCoefficients k = kalkerCoefficients(1.0, 0.28);
  // The creepages whose normalised parts (PatchCalibration::normalisedCreepage) are e1,
  // e2, e3.
  Creepages normalised(double e1, double e2, double e3) const {
    const double unit = muFz / (G * a * b);
    return {e1 * unit / k.c11, e2 * unit / k.c22, e3 * unit / (k.c23 * std::sqrt(a * b))};
  }
  CalibratedStep step(const PatchCalibration& c, const Creepages& cr) const {
    return c.step(a, b, G, k, muFz, cr);
  }
};

// A table at a/b 1 whose rule is 1 everywhere (kinds 11, 22, 23, 23x, 23s, knots 0 and 1) and
// whose combined correction has one spin share (0.5), the xi shares 0 and 1 and both signs, with
// knots 0 and 1: kind k's ratio at e = 1 in the direction (t, sign) is ratio(k, t, sign).
const char* const kRuleOfOnes =
    "a_over_b,kind,epsilon,ratio,fit_error,spin_share,xi_share,sign\n1,11,0,1\n1,11,1,1\n"
    "1,22,0,1\n1,22,1,1\n1,23,0,1\n1,23,1,1\n1,23x,0,1\n1,23x,1,1\n1,23s,0,1\n1,23s,1,1\n";
template <class Ratio>
std::string oneShareCorrection(const Ratio& ratio) {
  std::string body = kRuleOfOnes;
  for (const std::string k : {"c1", "c2", "c3", "cs"})
    for (const std::string t : {"0", "1"})
      for (const std::string sign : {"1", "-1"}) {
        body += "1," + k + ",0,1,0,0.5," + t + "," + sign + "\n";
        body += "1," + k + ",1," + ratio(k, t, sign) + ",0,0.5," + t + "," + sign + "\n";
      }
  return body;
}

std::string message(const std::string& body) {
  try {
    CalibrationTable::load(writeTable(body));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

/// Creepages of every size and sign (some zero) from linear theory to full slip, from a seeded
/// generator: each component zero one time in ten, else of either sign and of size scale 10^(-4u),
/// u uniform in [0, 1); longitudinal and lateral at scale 0.05, spin at 20.
class RandomCreepages {
 public:
  explicit RandomCreepages(unsigned seed) : rng_(seed) {}
  double unit() { return unit_(rng_); }
  Creepages next() { return Creepages{creepage(0.05), creepage(0.05), creepage(20.0)}; }

 private:
  double creepage(double scale) {
    const double u = unit();
    return u < 0.1 ? 0.0 : (u < 0.55 ? -1.0 : 1.0) * scale * std::pow(10.0, -4.0 * unit());
  }
  std::mt19937 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

/// Steps `x` and `y` `n` times on the patch of a/b = ab (a b = 36 mm^2) at creepages from
/// `draw`, on both branches and between them (every third step a random weight of the opposed
/// branch): adds the steps to *compared and those `equal` tells apart to *differ.
template <class Equal>
void compareSteps(const PatchCalibration& x, const PatchCalibration& y, double ab, int n,
                  RandomCreepages* draw, Equal equal, int* compared, int* differ) {
  const double a = 6e-3 * std::sqrt(ab), b = 6e-3 / std::sqrt(ab), G = 8.2e10, muFz = 2.4e4;
  const CreepCoefficients k = kalkerCoefficients(ab, 0.28);
  for (int i = 0; i < n; ++i) {
    const Creepages c = draw->next();
    const double opposed = i % 3 == 0 ? draw->unit() : PatchCalibration::opposedBranch(c);
    ++*compared;
    if (!equal(x.step(a, b, G, k, muFz, c, opposed), y.step(a, b, G, k, muFz, c, opposed)))
      ++*differ;
  }
}

}  // namespace

TEST(CalibrationTable, InterpolatesInCreepageAndLogAOverBAndHoldsBeyondTheLastKnot) {
  const CalibrationTable t = CalibrationTable::load(writeTable(kTwoRows));
  const PatchCalibration lo = t.at(0.5), mid = t.at(1.0), below = t.at(0.1);
  EXPECT_DOUBLE_EQ(lo.ratio(0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(lo.ratio(0, 0.5), std::sqrt(2.0));  // ln ratio linear in e
  EXPECT_DOUBLE_EQ(lo.ratio(0, 7.0), 2.0);             // held
  EXPECT_NEAR(lo.ratio(2, 1.0), std::sqrt(3.0), 1e-15);
  EXPECT_DOUBLE_EQ(mid.ratio(0, 1.0), 3.0);  // ln(1) halfway between ln(0.5) and ln(2)
  EXPECT_DOUBLE_EQ(mid.ratio(2, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(below.ratio(0, 1.0), 2.0);  // clamped at the table's end
  EXPECT_DOUBLE_EQ(t.at(9.0).ratio(0, 1.0), 4.0);
}

TEST(CalibrationTable, NumbersFromCharsRefusesReadAsStrtodReadsThem) {
  // A sign '+', leading space and hex are the C library's forms of the same numbers.
  std::string other = kTwoRows;
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"0.5,11,1,2,", "+0.5,11,1, 2,"},
        {"2,23,2,1,", "0x2,23,2,1,"}})
    other.replace(other.find(from), from.size(), to);
  const CalibrationTable a = CalibrationTable::load(writeTable(kTwoRows)),
                         b = CalibrationTable::load(writeTable(other));
  for (const double ab : {0.5, 2.0})
    for (int kind = 0; kind < 3; ++kind)
      for (const double e : {0.5, 1.5}) EXPECT_EQ(a.at(ab).ratio(kind, e), b.at(ab).ratio(kind, e));
  EXPECT_NE(message(std::string(kTwoRows) + "2,23,3,1e999,0\n").find(":15: not a finite"),
            std::string::npos);
}

TEST(CalibrationTable, ScalesEachFlexibilityByItsKindsRatioAtTheNormalisedCreepage) {
  const CalibrationTable t = CalibrationTable::load(writeTable(kTwoRows));
  const PatchCalibration c = t.at(0.5);
  const double a = 4e-3, b = 8e-3, G = 8.2e10, muFz = 3e3;
  const CreepCoefficients k = kalkerCoefficients(0.5, 0.28);
  // e = G a b C11 xi / (mu fz) = 0.5 for xi alone: ratio sqrt(2) (ln ratio halfway to ln 2).
  const Creepages c1{0.5 * muFz / (G * a * b * k.c11), 0.0, 0.0};
  EXPECT_NEAR(PatchCalibration::normalisedCreepage(a, b, G, k, muFz, c1), 0.5, 1e-12);
  const Flexibilities L0 = kalkerFlexibilities(a, b, G, k),
                      L = c.flexibilities(a, b, G, k, muFz, c1);
  // A single creepage: its kind's ratio, the others blended towards L_crss = L1 with w = e / 5.
  const double r = std::sqrt(2.0);
  EXPECT_NEAR(L.L1, r * L0.L1, 1e-12 * L0.L1);
  EXPECT_NEAR(L.L2, r * (0.9 * L0.L2 + 0.1 * L0.L1), 1e-12 * L0.L2);
  EXPECT_NEAR(L.L3, r * (0.9 * L0.L3 + 0.1 * L0.L1), 1e-12 * L0.L3);
  // Two kinds at e = 1 (e1 = e2): ln rho is the mean of their ln ratios, 2 and 0.5: rho = 1.
  const Creepages c12{c1.xi / 0.5 / std::sqrt(2.0), c1.xi / 0.5 / std::sqrt(2.0) * k.c11 / k.c22,
                      0.0};
  EXPECT_NEAR(PatchCalibration::normalisedCreepage(a, b, G, k, muFz, c12), 1.0, 1e-12);
  const Flexibilities L12 = c.flexibilities(a, b, G, k, muFz, c12);
  const double x2 = c12.xi * c12.xi, y2 = c12.eta * c12.eta;
  const double crss = (x2 + y2) / (x2 / L0.L1 + y2 / L0.L2);
  EXPECT_NEAR(L12.L1, 0.8 * L0.L1 + 0.2 * crss, 1e-12 * L0.L1);
  // Spin and signs: e is the norm of the three linear forces over mu fz.
  const Creepages c3{-c1.xi, 0.0, 0.5 * muFz / (G * std::pow(a * b, 1.5) * k.c23)};
  EXPECT_NEAR(PatchCalibration::normalisedCreepage(a, b, G, k, muFz, c3), std::sqrt(0.5), 1e-12);
  // No friction: full slip, the last knots.
  const Flexibilities Lf = c.flexibilities(a, b, G, k, 0.0, c1);
  EXPECT_NEAR(Lf.L1, 2.0 * L0.L1, 1e-12 * L0.L1);
}

TEST(CalibrationTable, OneStepCallIsTheRuleKindByKind) {
  // The shipped table's kinds share their knots: step() locates e once for all of them and folds
  // the combined correction into the ratios' exp. It must give what the rule gives kind by kind:
  // each kind's own ratio(), the correction's multipliers (L3x's besides L3's), the blend towards
  // L_crss.
  const PatchCalibration c = CalibrationTable::shipped().forMesh(20).at(0.7);
  const double a = 5e-3, b = a / 0.7, G = 8.2e10, muFz = 2.4e4;
  const CreepCoefficients k = kalkerCoefficients(0.7, 0.28);
  const Flexibilities L0 = kalkerFlexibilities(a, b, G, k);
  for (const Creepages cr : {Creepages{1e-3, -4e-4, 0.6}, Creepages{-3e-3, 2e-3, 1.5},
                             Creepages{2e-4, 1e-3, -0.3}, Creepages{0.05, 0.02, 8.0}}) {
    double e2[3];
    const double e = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, cr, e2);
    double m[calibration::kMultipliers];
    c.correction(e2, e, cr.eta * cr.phi < 0.0, 0, calibration::kMultipliers, m);
    const double rho = std::exp(
        (e2[0] * c.logRatio(0, e) + e2[1] * c.logRatio(1, e) + e2[2] * c.logRatio(2, e)) / (e * e));
    const double kphi = 3.0 * M_PI * a / 32.0 * cr.phi, x2 = cr.xi * cr.xi, y2 = cr.eta * cr.eta;
    const double crss = (x2 + y2 + kphi * kphi) / (x2 / L0.L1 + y2 / L0.L2 + kphi * kphi / L0.L3);
    const double w = std::min(1.0, e / 5.0);
    const CalibratedStep s = c.step(a, b, G, k, muFz, cr);
    EXPECT_NEAR(s.L.L1, rho * m[0] * ((1 - w) * L0.L1 + w * crss), 1e-14 * s.L.L1) << e;
    EXPECT_NEAR(s.L.L2, rho * m[1] * ((1 - w) * L0.L2 + w * crss), 1e-14 * s.L.L2) << e;
    EXPECT_NEAR(s.L.L3, rho * m[2] * ((1 - w) * L0.L3 + w * crss), 1e-14 * s.L.L3) << e;
    const double s3 = e2[2] / (e * e);
    EXPECT_NEAR(s.L.L3x,
                s.L.L3 *
                    std::exp(s3 * c.logRatio(3, e) + (1.0 - s3) * c.logRatio(3, 0.0) *
                                                         PatchCalibration::linearSpinMoment(e)) *
                    m[4],
                1e-14 * s.L.L3x);
    EXPECT_NEAR(s.boundShape, c.towardsFullSlip(c.ratio(4, e) * s3 * m[3], e, s3, a / b),
                1e-14 * s.boundShape);
    EXPECT_NE(m[0], 1.0);  // the correction acts on these directions
    // The separate calls are the same step.
    EXPECT_EQ(c.flexibilities(a, b, G, k, muFz, cr).L1, s.L.L1);
    EXPECT_EQ(c.boundShape(a, b, G, k, muFz, cr), s.boundShape);
  }
}

TEST(CalibrationTable, SmallSpinSharesGoTowardsHertzsShapeInFullSlipOnly) {
  // Below kSmallSpinShare (0.25), in full slip (e >= 5), the shape is Hertz's moment shape; in
  // partial slip, from kSmallSpinShare on and without spin it is the table's own. The blend starts
  // at e = 2.5, and at 1.5 where the lateral coupling is held (spin's share up to 0.06, linearly
  // between 0.06 and 0.12: 2 at 0.09).
  const PatchCalibration c = CalibrationTable::shipped().forMesh(20).at(1.0);
  constexpr double hertz = calibration::kHertzMomentShape;
  EXPECT_EQ(PatchCalibration::fullSlipFrom(0.02, 1.0), 1.5);
  EXPECT_DOUBLE_EQ(PatchCalibration::fullSlipFrom(0.09, 1.0), 2.0);
  EXPECT_EQ(PatchCalibration::fullSlipFrom(0.15, 1.0), 2.5);
  for (double shape : {0.0, 0.3, 1.8}) {
    EXPECT_EQ(c.towardsFullSlip(shape, 1.5, 0.02, 1.0), shape);
    EXPECT_EQ(c.towardsFullSlip(shape, 2.0, 0.09, 1.0), shape);
    EXPECT_EQ(c.towardsFullSlip(shape, 2.5, 0.15, 1.0), shape);
    EXPECT_EQ(c.towardsFullSlip(shape, 13.0, 0.0, 1.0), shape);
    EXPECT_EQ(c.towardsFullSlip(shape, 13.0, 0.25, 1.0), shape);
    EXPECT_EQ(c.towardsFullSlip(shape, 13.0, 1.0, 1.0), shape);
    EXPECT_NEAR(c.towardsFullSlip(shape, 5.0, 0.01, 1.0), shape + (hertz - shape) * 0.96, 1e-12);
    // Continuous in e and s3: half way in e, half the blend, times (1 - s3 / 0.25).
    EXPECT_NEAR(c.towardsFullSlip(shape, 3.25, 0.01, 1.0), shape + (hertz - shape) * 0.48, 1e-12);
    EXPECT_NEAR(c.towardsFullSlip(shape, 3.5, 0.09, 1.0), shape + (hertz - shape) * 0.32, 1e-12);
    EXPECT_NEAR(c.towardsFullSlip(shape, 3.75, 0.15, 1.0), shape + (hertz - shape) * 0.2, 1e-12);
  }
}

TEST(CalibrationTable, TheBlendSpansLessCreepageOnAWidePatch) {
  // From a/b 0.5 on the span is the one above; at a/b 0.2 and below the held shares start at 0.75
  // and every small share is fully blended from 3.5; linear in a/b between (half way at 0.35).
  EXPECT_EQ(PatchCalibration::wideness(0.5), 0.0);
  EXPECT_EQ(PatchCalibration::wideness(5.0), 0.0);
  EXPECT_EQ(PatchCalibration::wideness(0.2), 1.0);
  EXPECT_EQ(PatchCalibration::wideness(0.1), 1.0);
  EXPECT_DOUBLE_EQ(PatchCalibration::wideness(0.35), 0.5);
  EXPECT_EQ(PatchCalibration::fullSlipFrom(0.02, 0.2), 0.75);
  EXPECT_EQ(PatchCalibration::fullSlipFrom(0.15, 0.2), 2.5);
  EXPECT_DOUBLE_EQ(PatchCalibration::fullSlipFrom(0.02, 0.35), 1.125);
  EXPECT_EQ(PatchCalibration::fullSlipTo(0.2), 3.5);
  EXPECT_EQ(PatchCalibration::fullSlipTo(1.0), 5.0);
  const double shape = 0.3, hertz = calibration::kHertzMomentShape;
  const double w = (1.0 - 0.02 / 0.25);  // full blend's share factor at s3 = 0.02
  // Held share at a/b 0.2: from 0.75 to 3.5, half way at 2.125.
  EXPECT_EQ(PatchCalibration::hertzShapeBlend(shape, 0.75, 0.02, 0.2), shape);
  EXPECT_NEAR(PatchCalibration::hertzShapeBlend(shape, 2.125, 0.02, 0.2),
              shape + (hertz - shape) * 0.5 * w, 1e-12);
  EXPECT_NEAR(PatchCalibration::hertzShapeBlend(shape, 3.5, 0.02, 0.2), shape + (hertz - shape) * w,
              1e-12);
  // A share beyond the hold: from 2.5 to 3.5 there.
  EXPECT_EQ(PatchCalibration::hertzShapeBlend(shape, 2.5, 0.15, 0.2), shape);
  EXPECT_NEAR(PatchCalibration::hertzShapeBlend(shape, 3.0, 0.15, 0.2),
              shape + (hertz - shape) * 0.5 * (1.0 - 0.15 / 0.25), 1e-12);
  // The same creepage on a round patch is still early in its blend.
  EXPECT_LT(PatchCalibration::hertzShapeBlend(shape, 2.125, 0.02, 1.0),
            PatchCalibration::hertzShapeBlend(shape, 2.125, 0.02, 0.2));
}

TEST(CalibrationTable, ClassicHasNoBlendTowardsHertzsShape) {
  // Classic (no correction table): nothing to fill in.
  EXPECT_EQ(CalibrationTable().at(1.0).towardsFullSlip(0.3, 13.0, 0.02, 1.0), 0.3);
}

TEST(CalibrationTable, HertzMomentShapeGivesHertzsFullSlipSpinMoment) {
  // Pure spin in full slip on a circle: the traction is mu p around the spin pole at the centre,
  // so Mz = mu fz a times 8/15 on the parabolic bound and 3 pi / 16 on Hertz's; the flattened
  // bound with kHertzMomentShape must give Hertz's (within the 40x40 mesh's quadrature).
  const double a = 5e-3, fz = 1e4, mu = 0.3;
  const PatchMesh mesh(40, 40, a, a);
  TractionField f;
  f.resize(mesh.size());
  const Flexibilities L = kalkerFlexibilities(a, a, 8.2e10, kalkerCoefficients(1.0, 0.28));
  auto moment = [&](double shape) {
    flattenedBound(mesh, a, a, fz, mu, shape, &f);
    return -steadyFastSim(mesh, L, {0.0, 0.0, 1e3}, &f).mz / (mu * fz * a);  // phi > 0: Mz < 0
  };
  EXPECT_NEAR(moment(0.0), 8.0 / 15.0, 1e-3);
  EXPECT_NEAR(moment(calibration::kHertzMomentShape), 3.0 * M_PI / 16.0, 1e-3);
}

TEST(CalibrationTable, CreepagesWhoseSquaresAreSubnormalGiveFiniteFlexibilities) {
  // xi = 2.4e-159 (found by fuzzing, nss fixed): e1^2 is subnormal, so one reciprocal of the
  // squares' sum overflowed to infinity and the kinds' shares, then L1, were NaN. As e -> 0 the
  // step must tend to linear theory: Kalker's flexibilities.
  const PatchCalibration c = CalibrationTable::shipped().forMesh(20).at(1.5);
  const double a = 6e-3, b = 4e-3, G = 8.2e10, muFz = 0.3 * 8e4;
  const CreepCoefficients k = kalkerCoefficients(1.5, 0.28);
  const Flexibilities L0 = kalkerFlexibilities(a, b, G, k);
  for (const Creepages cr : {Creepages{2.3918967980787076e-159, 0.0, 0.0},
                             Creepages{1e-160, -3e-160, 0.0}, Creepages{0.0, 2e-158, 1e-157}}) {
    const CalibratedStep s = c.step(a, b, G, k, muFz, cr);
    EXPECT_NEAR(s.L.L1, L0.L1, 1e-12 * L0.L1);
    EXPECT_NEAR(s.L.L2, L0.L2, 1e-12 * L0.L2);
    EXPECT_NEAR(s.L.L3, L0.L3, 1e-12 * L0.L3);
    EXPECT_TRUE(std::isfinite(s.L.L3x) && std::isfinite(s.boundShape));
  }
  ContactParameters p;
  p.model = "nss";
  const StepOutput out =
      makeContactModel(p)->step({1e-3, 20.0, 2.3918967980787076e-159, 0.0, 0.0, 8e4});
  EXPECT_TRUE(std::isfinite(out.fx) && std::isfinite(out.fy) && std::isfinite(out.mz));
}

TEST(CalibrationTable, EmptyIsClassicFastSimExactly) {
  const PatchCalibration c = CalibrationTable().at(1.0);
  EXPECT_TRUE(c.classic());
  const CreepCoefficients k = kalkerCoefficients(1.0, 0.28);
  const Flexibilities L = c.flexibilities(5e-3, 5e-3, 8.2e10, k, 3e3, {0.01, 0.02, 1.0}),
                      L0 = kalkerFlexibilities(5e-3, 5e-3, 8.2e10, k);
  EXPECT_EQ(L.L1, L0.L1);
  EXPECT_EQ(L.L2, L0.L2);
  EXPECT_EQ(L.L3, L0.L3);
}

TEST(CalibrationTable, RefusesMalformedTablesNamingTheLine) {
  const std::string h = "a_over_b,kind,epsilon,ratio\n";
  EXPECT_NE(message("").find("no header"), std::string::npos);
  EXPECT_NE(message("a,b\n").find(":1: expected header"), std::string::npos);
  EXPECT_NE(message(h + "1,11,0.1,1\n").find(":2: the knots"), std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,11,1,0\n").find(":3: ratio must be > 0"), std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,11,1,nan\n").find(":3: not a finite"), std::string::npos);
  EXPECT_NE(message(h + "1,12,0,1\n").find("kind must be"), std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n").find("every a/b must hold every kind"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,11,1,2\n1,22,0,1\n1,23,0,1\n2,11,0,1\n2,11,2,2\n2,22,0,1\n"
                        "2,23,0,1\n")
                .find("same epsilon knots"),
            std::string::npos);
  EXPECT_EQ(message(kTwoRows), "");
  // Spin's second parameter and bound shape: optional, but then in every a/b; the shape in (0, 1].
  const std::string one = h + "1,11,0,1\n1,22,0,1\n1,23,0,1\n";
  EXPECT_NE(message(one + "1,23s,0,1.5\n").find(":5: a bound shape (23s) must be in (0, 1]"),
            std::string::npos);
  EXPECT_EQ(message(one + "1,23x,0,1\n1,23s,0,0.5\n"), "");
  // 23x's knot 0 is linear theory's spin moment, any ratio; 11, 22 and 23 start at 1.
  EXPECT_EQ(message(one + "1,23x,0,0.4\n"), "");
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n1,23,0,0.9\n").find(":4: the knots"),
            std::string::npos);
  EXPECT_NE(message(one + "1,23x,0,1\n2,11,0,1\n2,22,0,1\n2,23,0,1\n")
                .find("every a/b must hold every kind"),
            std::string::npos);
}

TEST(CalibrationTable, LateralCouplingIsEtasCouplingFadingWithSpin) {
  // Kind 22c: the coupling c per a/b and knot, any sign, interpolated linearly in e and in
  // ln(a/b); Flexibilities::lateralCoupling = 3 C11 c / (8 a b) times eta's share of the lateral
  // creepages' squares to the sixth; 0 without eta or without the kind.
  const std::string h = "a_over_b,kind,epsilon,ratio\n";
  const std::string body =
      h +
      "0.5,11,0,1\n0.5,11,1,1\n0.5,22,0,1\n0.5,22,1,1\n0.5,23,0,1\n0.5,23,1,1\n"
      "0.5,22c,0,-0.4\n0.5,22c,1,-0.2\n"
      "2,11,0,1\n2,11,1,1\n2,22,0,1\n2,22,1,1\n2,23,0,1\n2,23,1,1\n"
      "2,22c,0,-0.8\n2,22c,1,0.2\n";
  const CalibrationTable t = CalibrationTable::load(writeTable(body));
  EXPECT_DOUBLE_EQ(t.at(0.5).coupling(0.5), -0.3);
  EXPECT_DOUBLE_EQ(t.at(0.5).coupling(9.0), -0.2);  // held
  EXPECT_DOUBLE_EQ(t.at(1.0).coupling(1.0), 0.0);   // halfway in ln(a/b)
  EXPECT_DOUBLE_EQ(CalibrationTable::load(writeTable(kTwoRows)).at(1.0).coupling(1.0), 0.0);
  const double a = 4e-3, b = 8e-3, G = 8.2e10, muFz = 3e3;
  const CreepCoefficients k = kalkerCoefficients(a / b, 0.28);
  const PatchCalibration c = t.at(0.5);
  const Creepages eta{0.0, 2e-4, 0.0}, xi{2e-4, 0.0, 0.0};
  const double e = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, eta);
  ASSERT_LT(e, 1.0);
  const double full = 3.0 * k.c11 * c.coupling(e) / (8.0 * a * b);
  EXPECT_DOUBLE_EQ(c.step(a, b, G, k, muFz, eta).L.lateralCoupling, full);
  EXPECT_EQ(c.step(a, b, G, k, muFz, xi).L.lateralCoupling, 0.0);
  // No friction (mu fz = 0: e infinite, spin's square 0 * inf): no coupling, not NaN.
  EXPECT_EQ(c.step(a, b, G, k, 0.0, eta).L.lateralCoupling, 0.0);
  // Spin as large as eta in e^2: (1/2)^6 of the coupling at that e.
  const double phi = k.c22 * eta.eta / (k.c23 * std::sqrt(a * b));
  const Creepages both{0.0, eta.eta, phi};
  double squares[3];
  const double eb = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, both, squares);
  ASSERT_NEAR(squares[1], squares[2], 1e-12 * squares[1]);
  EXPECT_NEAR(c.step(a, b, G, k, muFz, both).L.lateralCoupling,
              3.0 * k.c11 * c.coupling(eb) / (8.0 * a * b) / 64.0, 1e-12 * std::abs(full));
  // In every a/b or in none; a negative value is no malformed ratio.
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n1,23,0,1\n1,22c,0,-0.3\n2,11,0,1\n2,22,0,1\n"
                        "2,23,0,1\n")
                .find("every a/b must hold every kind"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n1,23,0,1\n1,22c,0.5,-0.3\n").find(":5: the knots"),
            std::string::npos);
}

TEST(CalibrationTable, EtasDriveSlopeActsWhereXiIsBesideEta) {
  // Kind 22b: the slope beta per a/b and knot, any sign, interpolated linearly in e; applied with
  // the weight 4 t (1 - t), t xi's share of e1^2 + e2^2, falling with spin's share to 0 at the
  // first spin-share knot, 0.03: full at xi = eta, none on eta alone or xi alone.
  const std::string h = "a_over_b,kind,epsilon,ratio\n";
  const std::string body = h +
                           "1,11,0,1\n1,11,1,1\n1,22,0,1\n1,22,1,1\n1,23,0,1\n1,23,1,1\n"
                           "1,22c,0,-0.5\n1,22c,1,-0.5\n1,22b,0,0\n1,22b,1,-0.4\n";
  const PatchCalibration c = CalibrationTable::load(writeTable(body)).at(1.0);
  EXPECT_DOUBLE_EQ(c.etaSlope(0.5), -0.2);
  EXPECT_DOUBLE_EQ(c.etaSlope(3.0), -0.4);  // held
  const double a = 6e-3, b = 6e-3, G = 8.2e10, muFz = 3e3;
  const CreepCoefficients k = kalkerCoefficients(1.0, 0.28);
  const double xi = 1e-4, eta = xi * k.c11 / k.c22;  // e1 = e2
  const Creepages both{xi, eta, 0.0};
  const double e = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, both);
  ASSERT_LT(e, 1.0);
  const Flexibilities L = c.step(a, b, G, k, muFz, both).L;
  EXPECT_NEAR(L.etaSlope * a, c.etaSlope(e), 1e-12);
  EXPECT_NEAR(L.etaGain, 1.0 / (1.0 - 3.0 * M_PI / 32.0 * c.etaSlope(e)), 1e-12);
  for (const Creepages one : {Creepages{0.0, eta, 0.0}, Creepages{xi, 0.0, 0.0}}) {
    EXPECT_EQ(c.step(a, b, G, k, muFz, one).L.etaSlope, 0.0);
    EXPECT_EQ(c.step(a, b, G, k, muFz, one).L.etaGain, 1.0);
  }
  // xi's share 0.9: weight 4 (0.9)(0.1).
  const Creepages mostlyXi{3.0 * xi, eta, 0.0};
  const double em = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, mostlyXi);
  EXPECT_NEAR(c.step(a, b, G, k, muFz, mostlyXi).L.etaSlope * a, 0.36 * c.etaSlope(em), 1e-12);
  // Spin 1.5 % of e^2: half the weight; 3 % and more: none (the combined correction decides).
  const double perSqrtAb = 1.0 / std::sqrt(a * b);
  for (const auto& [s3, weight] : {std::pair{0.015, 0.5}, std::pair{0.03, 0.0}, {0.2, 0.0}}) {
    // e3^2 = s3 / (1 - s3) (e1^2 + e2^2), e3 = G (ab)^1.5 C23 |phi| / (mu fz).
    const double e3 = std::sqrt(s3 / (1.0 - s3)) * std::sqrt(2.0) * G * a * b * k.c11 * xi / muFz;
    const Creepages spun{xi, eta, e3 * muFz / (G * a * b * k.c23) * perSqrtAb};
    const double es = PatchCalibration::normalisedCreepage(a, b, G, k, muFz, spun);
    EXPECT_NEAR(c.step(a, b, G, k, muFz, spun).L.etaSlope * a, weight * c.etaSlope(es), 1e-9) << s3;
  }
  // Out of range, or in some a/b only: errors naming the line.
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n1,23,0,1\n1,22b,0,3\n").find(":5: eta's drive"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n1,22,0,1\n1,23,0,1\n1,22b,0,0\n2,11,0,1\n2,22,0,1\n"
                        "2,23,0,1\n")
                .find("every a/b must hold every kind"),
            std::string::npos);
}

TEST(CalibrationTable, EtaWithoutSpinReplacesThePairWhereSpinIsNoShare) {
  // Kinds 22n, 22cn, 22s: eta's ratio, coupling and bound shape where spin has no share, in
  // place of 22 and 22c, fading linearly with spin's share to the pair at 0.03 (noSpinWeight).
  const std::string h = "a_over_b,kind,epsilon,ratio\n";
  const std::string pair = h +
                           "1,11,0,1\n1,11,1,1.1\n1,22,0,1\n1,22,1,1.2\n1,23,0,1\n1,23,1,0.9\n"
                           "1,22c,0,-0.5\n1,22c,1,-0.5\n";
  const std::string own =
      "1,22n,0,1\n1,22n,1,0.8\n1,22cn,0,-0.3\n1,22cn,1,-0.3\n"
      "1,22s,0,0.6\n1,22s,1,0.6\n";
  const PatchCalibration withPair = CalibrationTable::load(writeTable(pair)).at(1.0);
  const PatchCalibration c = CalibrationTable::load(writeTable(pair + own)).at(1.0);
  const double a = 6e-3, b = 6e-3, G = 8.2e10, muFz = 3e3;
  const CreepCoefficients k = kalkerCoefficients(1.0, 0.28);
  const Flexibilities kalker = kalkerFlexibilities(a, b, G, k);
  // Eta alone, e = 0.5: L2 by 22n's ratio (ln interpolated), 22cn's coupling, 22s's shape.
  const double eta = 0.5 * muFz / (G * a * b * k.c22);
  const CalibratedStep alone = c.step(a, b, G, k, muFz, {0.0, eta, 0.0});
  EXPECT_NEAR(alone.L.L2, kalker.L2 * std::sqrt(0.8), 1e-12 * kalker.L2);
  EXPECT_NEAR(alone.L.lateralCoupling, PatchCalibration::lateralCoupling(-0.3, a, b, k),
              1e-12 * std::abs(alone.L.lateralCoupling));
  EXPECT_DOUBLE_EQ(alone.boundShape, 0.6);
  EXPECT_EQ(withPair.step(a, b, G, k, muFz, {0.0, eta, 0.0}).boundShape, 0.0);
  // With spin's share s3 of e^2 (eta and spin): half of the way at 1.5 %, the pair's own step
  // bit for bit from 3 % on.
  for (const double s3 : {0.015, 0.03, 0.2, 1.0}) {
    const double e3 = 0.5 * std::sqrt(s3), e2 = 0.5 * std::sqrt(1.0 - s3);
    const Creepages cr{0.0, e2 * muFz / (G * a * b * k.c22),
                       e3 * muFz / (G * std::pow(a * b, 1.5) * k.c23)};
    const CalibratedStep x = c.step(a, b, G, k, muFz, cr), y = withPair.step(a, b, G, k, muFz, cr);
    if (s3 < 0.03) {
      EXPECT_NEAR(x.L.lateralCoupling / y.L.lateralCoupling, 0.8, 1e-12);  // -0.4 against -0.5
      EXPECT_NEAR(x.boundShape, 0.5 * (1.0 - s3) * 0.6, 1e-12);
      // ln ratio half of the way from 22's to 22n's (at e = 0.5: half of each knot's ln), times
      // eta's share of e^2 in the step's one ratio.
      EXPECT_NEAR(x.L.L2 / y.L.L2, std::exp((1.0 - s3) * 0.5 * 0.5 * std::log(0.8 / 1.2)), 1e-12);
      continue;
    }
    EXPECT_EQ(x.L.L1, y.L.L1) << s3;
    EXPECT_EQ(x.L.L2, y.L.L2) << s3;
    EXPECT_EQ(x.L.L3, y.L.L3) << s3;
    EXPECT_EQ(x.L.spinX(), y.L.spinX()) << s3;
    EXPECT_EQ(x.L.lateralCoupling, y.L.lateralCoupling) << s3;
    EXPECT_EQ(x.boundShape, y.boundShape) << s3;
  }
  // The three together and with 22c; 22n a ratio, 1 at knot 0; 22s in [-1, 2].
  EXPECT_NE(message(pair + "1,22n,0,1\n1,22n,1,0.8\n").find(":11: 22n, 22cn and 22s come together"),
            std::string::npos);
  EXPECT_NE(message(pair + "1,22n,0,1.1\n").find(":10: the knots of a kind start"),
            std::string::npos);
  EXPECT_NE(message(pair + "1,22s,0,2.5\n").find(":10: eta's bound shape (22s)"),
            std::string::npos);
}

TEST(CalibrationTable, CouplingHeldAtSmallSpinSharesKeepsLinearTheorysSuperposition) {
  // In linear theory forces and moment add up over the creepages: eta with spin a small share
  // (3 % of e^2) must give eta's moment (its coupling) plus spin's (23x's knot 0). The coupling
  // is held there (heldCoupling: 1 - e / 4.5 below spin's share 0.06, none from 0.12) and its
  // moment on spin's traction taken back through L3x. Faded as (e2^2 / (e2^2 + e3^2))^6 alone
  // (a sixth of the coupling gone here) the sum was off by 8.3 % of eta's moment; held, 0.4 %.
  // Shipped 20x20 table, e = 0.02.
  EXPECT_DOUBLE_EQ(PatchCalibration::heldCoupling(0.9, 0.03), 0.8);
  EXPECT_DOUBLE_EQ(PatchCalibration::heldCoupling(0.9, 0.09), 0.4);
  EXPECT_EQ(PatchCalibration::heldCoupling(0.9, 0.12), 0.0);
  EXPECT_EQ(PatchCalibration::heldCoupling(4.5, 0.03), 0.0);
  const RoundPatch p;
  const PatchCalibration c = CalibrationTable::shipped().forMesh(20).at(1.0);
  const PatchMesh mesh(20, 20, p.a, p.b);
  TractionField f;
  f.resize(mesh.size());
  auto moment = [&](const Creepages& cr) {
    const CalibratedStep s = p.step(c, cr);
    flattenedBound(mesh, p.a, p.b, p.muFz / 0.3, 0.3, s.boundShape, &f);
    return steadyFastSim(mesh, s.L, cr, &f).mz;
  };
  const double e = 0.02, s3 = 0.03;
  const Creepages both = p.normalised(0.0, e * std::sqrt(1.0 - s3), -e * std::sqrt(s3));
  const double eta = moment({0.0, both.eta, 0.0}), spin = moment({0.0, 0.0, both.phi});
  ASSERT_GT(std::abs(eta), 0.2 * std::abs(spin));  // both parts worth the name
  EXPECT_NEAR(moment(both), eta + spin, 0.01 * std::abs(eta + spin));
  // Where spin is no small share the coupling fades as before: spin's 25 %, (3/4)^6 of c.
  const Creepages quarter = p.normalised(0.0, e * std::sqrt(0.75), e * 0.5);
  EXPECT_NEAR(p.step(c, quarter).L.lateralCoupling,
              PatchCalibration::lateralCoupling(c.coupling(PatchCalibration::normalisedCreepage(
                                                    p.a, p.b, p.G, p.k, p.muFz, quarter)),
                                                p.a, p.b, p.k) *
                  std::pow(0.75, 6),
              1e-9 * std::abs(p.step(c, {0.0, both.eta, 0.0}).L.lateralCoupling));
}

TEST(CalibrationTable, OneBlockPerMeshInterpolatedInOneOverNxBetweenThem) {
  // Two meshes, 5 and 20 nodes per strip (columns found by name, in any order after ratio).
  const std::string h = "a_over_b,kind,epsilon,ratio,fastsim_nx,fit_error\n";
  auto mesh = [](int nx, double r, const char* knot = "1") {
    const std::string n = std::to_string(nx), v = std::to_string(r);
    return "1,11,0,1," + n + "\n1,11," + knot + "," + v + "," + n + ",0\n1,22,0,1," + n +
           "\n1,23,0,1," + n + "\n";
  };
  const CalibrationTable t = CalibrationTable::load(writeTable(h + mesh(20, 2) + mesh(5, 4)));
  EXPECT_EQ(t.meshes(), (std::vector<int>{5, 20}));
  EXPECT_THROW(t.at(1.0), std::logic_error);           // which mesh is the caller's to say
  EXPECT_EQ(t.forMesh(5).at(1.0).ratio(0, 1.0), 4.0);  // an identified mesh: its own, exactly
  EXPECT_EQ(t.forMesh(20).at(1.0).ratio(0, 1.0), 2.0);
  EXPECT_EQ(t.forMesh(20).meshes(), (std::vector<int>{20}));
  // Between them, ln ratio linear in 1/nx: 8 is half way (1/5 - 1/8 = 1/8 - 1/20), 7 at
  // (1/5 - 1/7) / (1/5 - 1/20) = 8/21 of the way.
  EXPECT_NEAR(t.forMesh(8).at(1.0).ratio(0, 1.0), std::pow(2.0, 1.5), 1e-12);
  EXPECT_NEAR(t.forMesh(7).at(1.0).ratio(0, 1.0), std::pow(2.0, 2.0 - 8.0 / 21.0), 1e-12);
  EXPECT_EQ(t.forMesh(7).meshes(), (std::vector<int>{7}));
  // Beyond the table's meshes, the nearest.
  EXPECT_EQ(t.forMesh(40).at(1.0).ratio(0, 1.0), 2.0);
  EXPECT_EQ(t.forMesh(3).at(1.0).ratio(0, 1.0), 4.0);
  // Meshes identified on other knots are not blended: the nearest in 1/nx, a tie (8) for the
  // finer mesh.
  const CalibrationTable other =
      CalibrationTable::load(writeTable(h + mesh(20, 2) + mesh(5, 4, "1.5")));
  EXPECT_EQ(other.forMesh(8).at(1.0).ratio(0, 1.5), 2.0);
  EXPECT_EQ(other.forMesh(7).at(1.0).ratio(0, 1.5), 4.0);
  EXPECT_EQ(other.forMesh(7).meshes(), (std::vector<int>{5}));
  // A table without fastsim_nx serves every mesh.
  const CalibrationTable any = CalibrationTable::load(writeTable(kTwoRows));
  EXPECT_EQ(any.meshes(), (std::vector<int>{0}));
  EXPECT_DOUBLE_EQ(any.forMesh(5).at(0.5).ratio(0, 1.0), 2.0);
  // Errors name the line.
  EXPECT_NE(message(h + mesh(20, 2) + mesh(5, 4) + mesh(20, 2)).find(":10: fastsim_nx 20: each"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1\n").find(":2: fastsim_nx missing"), std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1,1\n").find(":2: fastsim_nx must be an integer >= 2"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1,5.5\n").find(":2: fastsim_nx must be an integer"),
            std::string::npos);
  EXPECT_NE(message(h + "1,11,0,1,5,0,7\n").find(":2: more fields than the header"),
            std::string::npos);
  // A trailing comma is one more (empty) field, as every reader of the package counts them.
  EXPECT_NE(message(h + "1,11,0,1,5,0,\n").find(":2: more fields than the header"),
            std::string::npos);
  EXPECT_NE(message("a_over_b,kind,epsilon,ratio,nx\n").find(":1: unknown column 'nx'"),
            std::string::npos);
  EXPECT_NE(message("a_over_b,kind,epsilon,ratio,sign,sign\n").find(":1: column 'sign' repeated"),
            std::string::npos);
  // Each mesh is checked on its own, and named.
  EXPECT_NE(message(h + mesh(20, 2) + "1,11,0,1,5\n").find("same epsilon knots (fastsim_nx 5)"),
            std::string::npos);
}

TEST(CalibrationTable, SpinsSecondParameterAndBoundShapeFollowSpinsShare) {
  const std::string path = writeTable(
      "a_over_b,kind,epsilon,ratio\n1,11,0,1\n1,11,1,1\n1,22,0,1\n1,22,1,1\n1,23,0,1\n"
      "1,23,1,1\n1,23x,0,1\n1,23x,1,4\n1,23s,0,0.5\n1,23s,1,0.5\n");
  const PatchCalibration c = CalibrationTable::load(path).at(1.0);
  const RoundPatch p;
  // e1 = e3 = 1 / sqrt(2): e = 1, spin's share 1/2.
  const Creepages c13 = p.normalised(std::sqrt(0.5), 0.0, std::sqrt(0.5));
  const CalibratedStep s = p.step(c, c13);
  EXPECT_NEAR(s.L.L3x, s.L.L3 * 2.0, 1e-12 * s.L.L3);  // 4^(1/2)
  EXPECT_NEAR(s.boundShape, 0.25, 1e-12);
  // No spin: Kalker's L3x (0: L3) and the parabolic bound, as classic.
  const CalibratedStep s1 = p.step(c, p.normalised(1.0, 0.0, 0.0));
  EXPECT_EQ(s1.L.spinX(), s1.L.L3);
  EXPECT_EQ(s1.boundShape, 0.0);
  EXPECT_EQ(p.step(CalibrationTable().at(1.0), c13).boundShape, 0.0);
}

TEST(CalibrationTable, LinearSpinMomentHoldsAtEveryShareOfSpinUntilThePatchSlips) {
  // 23x is 0.5 at knot 0 (linear theory's spin moment) and 4 at e = 5: spin's own curve carries
  // spin's share of e^2, the rest keeps knot 0's ratio up to kLinearSpinMomentTo and loses it by
  // kLinearSpinMomentEnd.
  const std::string path = writeTable(
      "a_over_b,kind,epsilon,ratio\n1,11,0,1\n1,11,5,1\n1,22,0,1\n1,22,5,1\n1,23,0,1\n"
      "1,23,5,1\n1,23x,0,0.5\n1,23x,5,4\n");
  const PatchCalibration c = CalibrationTable::load(path).at(1.0);
  const RoundPatch p;
  // xi with a tenth of e^2 spin's, at normalised creepage e.
  auto spinX = [&](double e) {
    const Flexibilities L = p.step(c, p.normalised(std::sqrt(0.9) * e, 0.0, std::sqrt(0.1) * e)).L;
    return L.L3x / L.L3;
  };
  for (double e : {0.01, 0.5 * calibration::kLinearSpinMomentTo,
                   0.5 * (calibration::kLinearSpinMomentTo + calibration::kLinearSpinMomentEnd),
                   calibration::kLinearSpinMomentEnd + 0.1}) {
    const double own = std::log(0.5) + e / 5.0 * std::log(8.0);  // 23x's ln ratio at e
    const double expected =
        std::exp(0.1 * own + 0.9 * std::log(0.5) * PatchCalibration::linearSpinMoment(e));
    EXPECT_NEAR(spinX(e), expected, 1e-12 * expected) << e;
  }
  EXPECT_EQ(PatchCalibration::linearSpinMoment(0.0), 1.0);
  EXPECT_EQ(PatchCalibration::linearSpinMoment(calibration::kLinearSpinMomentTo), 1.0);
  EXPECT_EQ(PatchCalibration::linearSpinMoment(calibration::kLinearSpinMomentEnd), 0.0);
  // Near linear theory L3x is knot 0's, whatever the share of spin.
  EXPECT_NEAR(spinX(1e-3), 0.5, 1e-3);
}

TEST(CalibrationTable, CombinedCorrectionInterpolatesOverTheDirectionAndIsOneOnItsEdges) {
  // One spin share (0.5), xi shares 0 and 1, both signs, knots 0 and 1: c1 is 2 at t = 0 and 8
  // at t = 1 where eta and phi have one sign, 1 where they oppose; cs (the bound's shape) 3.
  const std::string body =
      oneShareCorrection([](const std::string& k, const std::string& t, const std::string& sign) {
        return k == "c1" && sign == "1" ? (t == "0" ? "2" : "8") : k == "cs" ? "3" : "1";
      });
  const PatchCalibration c = CalibrationTable::load(writeTable(body)).at(1.0);
  double m[calibration::kMultipliers];
  auto m1 = [&](double e1, double e2, double e3, bool opposed) {
    const double sq[3] = {e1 * e1, e2 * e2, e3 * e3};
    c.correction(sq, std::sqrt(sq[0] + sq[1] + sq[2]), opposed, 0, calibration::kMultipliers, m);
    return m[0];
  };
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(m1(0.0, h, h, false), 2.0, 1e-12);  // on the grid: t = 0, s3 = 0.5, e = 1
  EXPECT_NEAR(m[1], 1.0, 1e-12);
  EXPECT_NEAR(m[3], 3.0, 1e-12);
  EXPECT_NEAR(m[4], 1.0, 1e-12);                                         // no c3x in the table: 1
  EXPECT_NEAR(m1(h, 0.0, h, false), 8.0, 1e-12);                         // t = 1
  EXPECT_NEAR(m1(0.5, 0.5, h, false), 4.0, 1e-12);                       // t = 1/2: ln halfway
  EXPECT_NEAR(m1(0.0, h, h, true), 1.0, 1e-12);                          // the other sign's table
  EXPECT_NEAR(m1(0.0, 0.5 * h, 0.5 * h, false), std::sqrt(2.0), 1e-12);  // e = 1/2
  EXPECT_NEAR(m1(0.0, std::sqrt(0.75), 0.5, false), std::sqrt(2.0), 1e-12);  // s3 = 1/4
  EXPECT_NEAR(m1(0.0, 0.5, std::sqrt(0.75), false), std::sqrt(2.0), 1e-12);  // s3 = 3/4
  EXPECT_NEAR(m1(0.0, 0.0, 1.0, false), 1.0, 1e-12);          // spin alone: the rule alone
  EXPECT_NEAR(m1(h, h, 0.0, false), 1.0, 1e-12);              // no spin
  EXPECT_NEAR(m1(0.0, 2.0 * h, 2.0 * h, false), 2.0, 1e-12);  // held beyond the last knot
  // The bound's shape: spin's share (1/2) times the table's 23s (1) times cs (3), capped at 2.
  const RoundPatch p;
  EXPECT_NEAR(p.step(c, p.normalised(0.0, h, h)).boundShape, 1.5, 1e-12);
  EXPECT_NEAR(p.step(c, p.normalised(0.0, 4.0 * h, 4.0 * h)).boundShape, 1.5, 1e-12);
  // Malformed correction rows and a grid missing a direction are refused, naming the line.
  const std::string single = body.substr(0, body.find("1,c1,"));
  EXPECT_NE(message(single + "1,c1,0,1,0\n").find(":12: a c-kind row needs"), std::string::npos);
  EXPECT_NE(message(single + "1,c1,0,1,0,1,0,1\n").find(":12: spin_share must be in (0, 1)"),
            std::string::npos);
  EXPECT_NE(message(single + "1,c1,0,1,0,0.5,0,2\n").find(":12: sign must be 1 or -1"),
            std::string::npos);
  EXPECT_NE(message(single + "1,c1,0.5,1,0,0.5,0,1\n").find(":12: the knots"), std::string::npos);
  EXPECT_NE(message(body.substr(0, body.rfind("1,cs,0,1"))).find("misses a direction"),
            std::string::npos);
}

TEST(CalibrationTable, VectorisedStepIsTheScalarStepWithinRoundOff) {
  if (!stripLanesAvailable()) GTEST_SKIP() << "this CPU has no lanes: only the scalar reference";
  // Not bit for bit: the lanes fuse multiply-adds and take Highway's exp (within 1 ulp) where the
  // scalar reference takes std::exp, so a field may move by a few ulps; 1e-12 relative is the
  // marches' bound for their lanes (strip_lanes.hpp), and a wrong corner, weight or lane would
  // be off by far more.
  auto same = [](const CalibratedStep& x, const CalibratedStep& y) {
    const double u[] = {x.L.L1,       x.L.L2,      x.L.L3,      x.L.L3x, x.L.lateralCoupling,
                        x.L.etaSlope, x.L.etaGain, x.boundShape};
    const double v[] = {y.L.L1,       y.L.L2,      y.L.L3,      y.L.L3x, y.L.lateralCoupling,
                        y.L.etaSlope, y.L.etaGain, y.boundShape};
    for (std::size_t q = 0; q < sizeof u / sizeof u[0]; ++q)
      if (!(std::abs(u[q] - v[q]) <= 1e-12 * std::abs(v[q]))) return false;  // NaN: differs
    return true;
  };
  // The shipped table on three meshes and three a/b, creepages of every size and sign (some
  // zero) from linear theory to full slip, on both branches and between them.
  RandomCreepages draw(19);
  int compared = 0, differ = 0;
  for (int nx : {5, 10, 40})
    for (double ab : {0.2, 1.0, 3.7}) {
      PatchCalibration scalar = CalibrationTable::shipped().forMesh(nx).at(ab);
      const PatchCalibration lanes = scalar;
      ASSERT_TRUE(lanes.vectorised());
      scalar.setVectorised(false);
      ASSERT_FALSE(scalar.vectorised());
      compareSteps(lanes, scalar, ab, 4000, &draw, same, &compared, &differ);
    }
  EXPECT_EQ(differ, 0) << "of " << compared;
  // A lane whose exp leaves Highway's range (|x| >= 700) takes std::exp, as the scalar path: a
  // table whose c1 multiplies L1 by 1e-310 (a subnormal) at e = 1.
  const std::string body =
      oneShareCorrection([](const std::string& k, const std::string&, const std::string&) {
        return k == "c1" ? "1e-310" : "2";
      });
  PatchCalibration scalar = CalibrationTable::load(writeTable(body)).at(1.0);
  const PatchCalibration lanes = scalar;
  scalar.setVectorised(false);
  const RoundPatch p;
  const double h = std::sqrt(0.5);
  // At spin's share 1/2 (its knot) and e >= 1 (the last knot, held) ln c1 is -714: 2^m below the
  // normal range.
  for (double e : {0.5, 0.99, 1.0, 3.0}) {
    const Creepages c = p.normalised(0.6 * e * h, 0.8 * e * h, e * h);
    EXPECT_TRUE(same(p.step(lanes, c), p.step(scalar, c))) << "e = " << e;
  }
  const Flexibilities kalker = kalkerFlexibilities(p.a, p.b, p.G, p.k);
  EXPECT_LT(p.step(lanes, p.normalised(0.6 * h, 0.8 * h, h)).L.L1 / kalker.L1, 1e-302);
}

TEST(CalibrationTable, RePickingFillsTheCorrectionAsStepsNeedItWithTheWholeGridsValues) {
  // at(a_over_b, &c) leaves the correction's grid points to c's steps (computed as a step first
  // reaches them); at(a_over_b) computes them all. The values are the same expressions: the steps
  // must agree bit for bit, whatever the a/b picked before (rows crossed, a table of other knots
  // between), on either path, and after the table c was picked from is gone.
  auto identical = [](const CalibratedStep& x, const CalibratedStep& y) {
    return x.L.L1 == y.L.L1 && x.L.L2 == y.L.L2 && x.L.L3 == y.L.L3 && x.L.L3x == y.L.L3x &&
           x.L.lateralCoupling == y.L.lateralCoupling && x.L.etaSlope == y.L.etaSlope &&
           x.L.etaGain == y.L.etaGain && x.boundShape == y.boundShape;
  };
  RandomCreepages draw(46);
  const CalibrationTable mesh20 = CalibrationTable::shipped().forMesh(20);
  const CalibrationTable other = CalibrationTable::load(writeTable(kTwoRows));
  int compared = 0, differ = 0;
  for (bool lanes : {true, false}) {
    PatchCalibration picked;
    // a/b within one row pair, across rows, back, beyond the table's ends; 0 (c) is the other
    // table.
    for (double ab : {0.7, 0.71, 0.705, 1.3, 0.3, 0.0, 0.7, 4.9, 7.0, 0.15, 1.0}) {
      const bool fromOther = ab == 0.0;
      (fromOther ? other : mesh20).at(fromOther ? 1.0 : ab, &picked);
      PatchCalibration whole = (fromOther ? other : mesh20).at(fromOther ? 1.0 : ab);
      picked.setVectorised(lanes);
      whole.setVectorised(lanes);
      compareSteps(picked, whole, fromOther ? 1.0 : ab, 300, &draw, identical, &compared, &differ);
    }
  }
  EXPECT_EQ(differ, 0) << "of " << compared;
  // Picked from a table that is then destroyed (mesh 7: rows of its own, blended from 5 and 10).
  PatchCalibration orphan;
  CalibrationTable::shipped().forMesh(7).at(0.6, &orphan);
  const PatchCalibration whole = CalibrationTable::shipped().forMesh(7).at(0.6);
  const double a = 6e-3 * std::sqrt(0.6), b = 6e-3 / std::sqrt(0.6);
  const CreepCoefficients k = kalkerCoefficients(0.6, 0.28);
  for (int n = 0; n < 200; ++n) {
    const Creepages c = draw.next();
    EXPECT_TRUE(
        identical(orphan.step(a, b, 8.2e10, k, 2.4e4, c), whole.step(a, b, 8.2e10, k, 2.4e4, c)));
  }
}

TEST(CalibrationTable, TheLanesExpIsStdExpWithinTwoUlpsAndFallsBackOutsideItsRange) {
  if (!stripLanesAvailable()) GTEST_SKIP() << "this CPU has no lanes: only the scalar reference";
  // The lanes' table exp (within 1 ulp of exp) against std::exp (within 1 ulp too): at most 2 ulps
  // apart over the step's range, |x| < 700, densely and at its ends.
  double worst = 0.0;  // in ulps of std::exp's value
  auto check = [&](const double* x) {
    double r[4];
    calibration::expsInLanes(x, r);
    for (int q = 0; q < 4; ++q) {
      const double want = std::exp(x[q]);
      const double ulp = std::nextafter(want, std::numeric_limits<double>::infinity()) - want;
      worst = std::max(worst, std::abs(r[q] - want) / ulp);
    }
  };
  const int n = 400000;
  for (int i = 0; i < n; i += 4) {
    double x[4];
    for (int q = 0; q < 4; ++q) x[q] = -700.0 + 1400.0 * (i + q) / n;
    check(x);
  }
  const double ends[4] = {std::nextafter(-700.0, 0.0), std::nextafter(700.0, 0.0), 0.0, -0.0};
  check(ends);
  const double small[4] = {1e-300, -1e-17, 0.3465735902799727, -0.3465735902799727};  // ln 2 / 2
  check(small);
  EXPECT_LE(worst, 2.0);
  // Outside |x| < 700, and NaN and infinities: std::exp itself, lane by lane, the other lanes
  // untouched.
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  for (const auto& x : {std::vector<double>{700.0, -700.0, 705.0, 1.0},
                        std::vector<double>{710.0, -745.0, -708.5, -1000.0},
                        std::vector<double>{nan, inf, -inf, 2.0}}) {
    double r[4];
    calibration::expsInLanes(x.data(), r);
    for (int q = 0; q < 4; ++q) {
      const double want = std::exp(x[q]);
      if (std::fabs(x[q]) < 700.0)
        EXPECT_NEAR(r[q], want, 4.5e-16 * want) << x[q];  // 2 ulps
      else if (std::isnan(want))
        EXPECT_TRUE(std::isnan(r[q])) << x[q];
      else
        EXPECT_EQ(r[q], want) << x[q];  // bit for bit (0 == -0 aside, which exp never gives)
    }
  }
}

TEST(CalibrationTable, FifthCorrectionScalesTheLongitudinalSpinDriveAlone) {
  // The grid of the test above with every multiplier 1, and c3x 4 at e = 1 in every direction.
  std::string plain = kRuleOfOnes;
  std::string c3x;
  for (const char* kind : {"c1", "c2", "c3", "cs", "c3x"})
    for (const char* t : {"0", "1"})
      for (const char* sign : {"1", "-1"}) {
        const std::string k = kind, row = "1," + k + ",";
        const std::string dir = std::string(",0,0.5,") + t + "," + sign + "\n";
        (k == "c3x" ? c3x : plain) +=
            row + "0,1" + dir + row + "1," + (k == "c3x" ? "4" : "1") + dir;
      }
  const PatchCalibration without = CalibrationTable::load(writeTable(plain)).at(1.0);
  const PatchCalibration with = CalibrationTable::load(writeTable(plain + c3x)).at(1.0);
  const RoundPatch p;
  const double h = std::sqrt(0.5);
  const Creepages c = p.normalised(0.0, h, h);  // e = 1
  const CalibratedStep s0 = p.step(without, c), s1 = p.step(with, c);
  EXPECT_EQ(s1.L.L1, s0.L.L1);
  EXPECT_EQ(s1.L.L2, s0.L.L2);
  EXPECT_EQ(s1.L.L3, s0.L.L3);
  EXPECT_EQ(s1.boundShape, s0.boundShape);
  EXPECT_NEAR(s1.L.spinX(), 4.0 * s0.L.spinX(), 1e-12 * s0.L.spinX());
  // Half way to the knot, ln halfway: 2. Without spin there is no correction: L3x is L3.
  const Creepages half{0.0, 0.5 * c.eta, 0.5 * c.phi};
  const double halfWithout = p.step(without, half).L.spinX();
  EXPECT_NEAR(p.step(with, half).L.spinX(), 2.0 * halfWithout, 1e-12 * halfWithout);
  const Flexibilities noSpin = p.step(with, {0.0, c.eta, 0.0}).L;
  EXPECT_EQ(noSpin.spinX(), noSpin.L3);
  // c3x in some directions only is refused.
  EXPECT_NE(message(plain + c3x.substr(0, c3x.rfind("1,c3x,0,1"))).find("misses a direction"),
            std::string::npos);
}

namespace {

// The force of a traction at the bound along x everywhere: the bound through the force's
// quadrature (end nodes weighted as the march weights them).
double saturatedForce(const PatchMesh& mesh, TractionField f) {
  f.tx = f.bound;
  f.ty.setZero();
  f.slip.setConstant(true);
  return integrateTraction(mesh, f).fx;
}

}  // namespace

TEST(CalibrationTable, FlattenedBoundKeepsTheTotalAndThePatch) {
  // Saturated everywhere, FastSim's force is the bound's quadrature: the blend must keep it (mu fz)
  // and the patch (where the bound is positive); s = 0 is the parabolic bound bit for bit. Down to
  // patches covering a node or two of a fixed mesh, where the end nodes' weights decide the total.
  for (const double scale : {1.0, 0.7, 0.2, 0.1}) {
    const PatchMesh mesh(20, 20, 5e-3, 4e-3);
    const double a = 5e-3 * scale, b = 4e-3 * scale, fz = 1e4, mu = 0.3;
    TractionField f, g;
    f.resize(mesh.size());
    g.resize(mesh.size());
    parabolicBound(mesh, a, b, fz, mu, &f);
    flattenedBound(mesh, a, b, fz, mu, 0.0, &g);
    EXPECT_TRUE((f.bound == g.bound).all());
    flattenedBound(mesh, a, b, fz, mu, 1.0, &g);
    for (int n = 0; n < mesh.size(); ++n) EXPECT_EQ(f.bound[n] > 0.0, g.bound[n] > 0.0) << n;
    const double before = saturatedForce(mesh, f), after = saturatedForce(mesh, g);
    EXPECT_NEAR(before, mu * fz, 1e-12 * mu * fz) << scale;
    EXPECT_NEAR(after, before, 1e-12 * before) << scale;
    // Flatter: the centre node carries less than the parabola's peak (where a strip has more
    // nodes than its two ends).
    const int centre = mesh.index(mesh.nx() / 2, mesh.ny() / 2);
    if (scale > 0.5) {
      EXPECT_LT(g.bound[centre], f.bound[centre]);
    }
  }
}

TEST(CalibrationTable, FlattenedBoundOfAClippedPatchStaysPositive) {
  // A patch longer or wider than the fixed mesh is clipped to it, its bound scaled to carry mu fz
  // on the part left, above the parabola's peak p0: flattened relative to p0 at the largest shape,
  // the bound went negative at the strips' ends and to zero in the middle (found by fuzzing: a
  // patch four times the mesh's length). It must stay positive wherever the parabolic bound is,
  // and keep the total.
  const PatchMesh mesh(54, 53, 6e-3, 4e-3);
  for (const double ka : {4.0, 1.5, 1.0})
    for (const double kb : {1.0, 2.0}) {
      const double a = 6e-3 * ka, b = 4e-3 * kb, fz = 8e4, mu = 0.3;
      TractionField f, g;
      f.resize(mesh.size());
      g.resize(mesh.size());
      parabolicBound(mesh, a, b, fz, mu, &f);
      flattenedBound(mesh, a, b, fz, mu, calibration::kMaxBoundShape, &g);
      for (int n = 0; n < mesh.size(); ++n) {
        ASSERT_GE(g.bound[n], 0.0) << ka << " " << kb << " " << n;
        EXPECT_EQ(f.bound[n] > 0.0, g.bound[n] > 0.0) << ka << " " << kb << " " << n;
      }
      EXPECT_NEAR(saturatedForce(mesh, g), mu * fz, 1e-12 * mu * fz) << ka << " " << kb;
    }
}

TEST(CalibrationTable, FlattenedBoundsClosedFormSumsAreTheNodeSums) {
  // flattenedBound takes the node sums of the parabolic bound per strip in closed form: it must
  // give the blend whose rescale is computed from the written parabolic bound's own nodes, on
  // meshes of odd and even nx, a patch filling the mesh, smaller (end nodes at their part's mean,
  // strips with one or two loaded nodes) and larger than it (clipped).
  for (const int nx : {7, 20, 21})
    for (const double scale : {1.0, 0.93, 0.55, 0.31, 0.12, 1.2})
      for (const double s : {0.3, 1.0, 2.0}) {  // 2: the calibration's largest shape
        const PatchMesh mesh(nx, 13, 5e-3, 4e-3);
        const double a = 5e-3 * scale, b = 4e-3 * scale, fz = 1e4, mu = 0.3;
        TractionField f, g;
        f.resize(mesh.size());
        g.resize(mesh.size());
        parabolicBound(mesh, a, b, fz, mu, &f);
        flattenedBound(mesh, a, b, fz, mu, s, &g);
        // Node sums with the force quadrature's weights: 1, the end nodes 1 + w each (a single
        // loaded node, both ends, 1 + 2 w).
        double sum1 = 0.0, sum2 = 0.0;
        for (int j = 0; j < mesh.ny(); ++j)
          for (int i = 0; i < mesh.nx(); ++i) {
            const double q = f.bound[mesh.index(i, j)];
            const StripEntry& e = f.entry[j];
            const double w = 1.0 + (i == e.first ? e.w : 0.0) + (i == nx - 1 - e.first ? e.w : 0.0);
            sum1 += mesh.halfNorm(j) * w * q;
            sum2 += mesh.halfNorm(j) * w * q * q;
          }
        // Flattened relative to the parabola's peak p0, or, for a patch clipped to the mesh,
        // relative to the bound's own peak where that is higher: its scale, read off the centre
        // node, bound / shape.
        const double p0 = 2.0 * mu * fz / (M_PI * a * b), alpha = 1.0 + 0.5 * s;
        double peak = p0;
        if (scale > 1.0) {
          const int i = nx / 2, j = mesh.ny() / 2, n = mesh.index(i, j);
          const double ka = mesh.a() / a, kb = mesh.b() / b, yn = mesh.yNorm(j) * kb,
                       xn = mesh.xNorms()[n] * ka;
          peak = std::max(p0, f.bound[n] / (1.0 - yn * yn - xn * xn));
        }
        const double beta = 0.75 * s / peak, c = sum1 / (alpha * sum1 - beta * sum2);
        for (int n = 0; n < mesh.size(); ++n) {
          const double q = f.bound[n], expected = q * (c * alpha - c * beta * q);
          EXPECT_NEAR(g.bound[n], expected, 1e-13 * p0) << nx << " " << scale << " " << n;
        }
        EXPECT_EQ(g.entry.size(), f.entry.size());
        for (size_t j = 0; j < f.entry.size(); ++j) EXPECT_EQ(g.entry[j].first, f.entry[j].first);
      }
}

TEST(CalibrationTable, ShippedTableKeepsLinearTheory) {
  // Ratio 1 at zero creepage: Kalker's coefficients hold exactly in the linear limit. Near it
  // (e = 0.01, where the force is 1 % of mu fz) every ratio is within 1 % of 1.
  const CalibrationTable shipped = CalibrationTable::shipped();
  // One table per FastSim mesh of the chi table's (identify_calibration --nx 5,10,20,30,40).
  EXPECT_EQ(shipped.meshes(), (std::vector<int>{5, 10, 20, 30, 40}));
  for (int nx : shipped.meshes()) {
    const CalibrationTable t = shipped.forMesh(nx);
    for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) {
      const PatchCalibration c = t.at(ab);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(c.ratio(k, 0.0), 1.0);
        EXPECT_NEAR(c.ratio(k, 0.01), 1.0, 0.01) << nx << " " << ab << " " << k;
      }
    }
  }
}

TEST(FastSimParameter, CalibratedForNssAndAutoClassicForTheBaselinesUnlessNamed) {
  ContactParameters p;
  for (const char* m : {"steady", "shen-li", "nss", "auto"}) {
    p.model = m;
    p.fastsim.reset();
    const bool recommended = p.model == "nss" || p.model == "auto";
    EXPECT_EQ(resolvedFastSim(p) == FastSimVariant::kCalibrated, recommended) << m;
    EXPECT_STREQ(fastsimVariantName(p), recommended ? "calibrated FastSim" : "classic FastSim");
    setParameter(&p, "fastsim", "calibrated");
    EXPECT_EQ(resolvedFastSim(p), FastSimVariant::kCalibrated) << m;
    setParameter(&p, "fastsim", "classic");
    EXPECT_EQ(resolvedFastSim(p), FastSimVariant::kClassic) << m;
    EXPECT_STREQ(fastsimVariantName(p), "classic FastSim");
  }
  p.model = "exact";
  EXPECT_STREQ(fastsimVariantName(p), "no FastSim");
  // A value that is not a variant, the empty one included (it used to mean the model's own), is
  // refused naming the parameter and its values, and leaves what was set.
  for (const char* bad : {"exact", "", "Calibrated"}) {
    try {
      setParameter(&p, "fastsim", bad);
      FAIL() << "fastsim: '" << bad << "' accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("fastsim: must be calibrated or classic", 0), 0u)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("got '" + std::string(bad) + "'"), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(p.fastsim, FastSimVariant::kClassic);
  }
}

TEST(FastSimParameter, TheModelRunsTheResolvedVariant) {
  // Unset, each model runs its own variant: nss's force is calibrated nss's, steady's classic's.
  auto settled = [](const ContactParameters& p) {  // partial slip, where the variants differ
    const auto m = makeContactModel(p);
    StepOutput o;
    for (int k = 0; k < 100; ++k) o = m->step({1e-4, 20.0, 3e-3, 1e-3, 0.5, p.fz0});
    return o.fx;
  };
  for (const char* m : {"steady", "shen-li", "nss", "auto"}) {
    ContactParameters p;
    p.model = m;
    const double unset = settled(p);
    p.fastsim = resolvedFastSim(p);
    EXPECT_EQ(settled(p), unset) << m;
    p.fastsim = p.fastsim == FastSimVariant::kClassic ? FastSimVariant::kCalibrated
                                                      : FastSimVariant::kClassic;
    EXPECT_NE(settled(p), unset) << m;
  }
}

TEST(FastSimParameter, CalibratedSteadyDiffersFromClassicOnlyBeyondLinearTheory) {
  ContactParameters p;
  p.model = "steady";
  StepInput in;
  in.V = 20.0;
  in.dt = 1e-4;
  in.fz = p.fz0;
  for (double xi : {1e-6, 3e-3}) {  // linear; e = 1, partial slip
    in.xi = xi;
    p.fastsim = FastSimVariant::kClassic;
    const double classic = makeContactModel(p)->step(in).fx;
    p.fastsim = FastSimVariant::kCalibrated;
    const double calibrated = makeContactModel(p)->step(in).fx;
    if (xi < 1e-5)
      EXPECT_NEAR(calibrated, classic, 1e-3 * std::abs(classic));
    else
      EXPECT_GT(std::abs(calibrated - classic), 1e-3 * p.mu * p.fz0);
  }
}
