// Accuracy of NSS-FastSim with the shipped chi table against our exact half-space solver, at
// coarse CI settings (exact grid 20x20; the table was fitted at 30x30, and C^/C_steady moves by
// about 0.5 % between such grids).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "wheel_rail_contact/chi_table.hpp"
#include "wheel_rail_contact/fastsim_frequency.hpp"
#include "wheel_rail_contact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

struct CurveErrors {
  double maxNss = 0.0, meanNss = 0.0, meanShenLi = 0.0;
};

// max over lambda/a >= from, and means over all points, of |C^/C_steady - exact| on log-spaced
// lambda/a in [from, 100].
CurveErrors errors(CreepageKind kind, double ab, double from) {
  const ChiTable table = ChiTable::load(ChiTable::defaultPath());
  const NonSteadyCoefficients exact(kind, ab, 0.28, 20, 20);
  const double ce = exact.steady(), cf = fastsimSteadyCoefficient(kind, ab, 0.28, 20, 20);
  CurveErrors e;
  const int n = 10;
  for (int q = 0; q <= n; ++q) {
    const double l = from * std::pow(100.0 / from, double(q) / n);
    const std::complex<double> r = exact.at(l) / ce;
    const auto nss =
        fastsimSecondOrderCoefficient(kind, ab, 0.28, 20, 20, table.secondOrderAt(kind, ab), l);
    const auto sl = fastsimNonSteadyCoefficient(kind, ab, 0.28, 20, 20, {}, l);
    e.maxNss = std::max(e.maxNss, std::abs(nss / cf - r));
    e.meanNss += std::abs(nss / cf - r) / (n + 1);
    e.meanShenLi += std::abs(sl / cf - r) / (n + 1);
  }
  return e;
}

}  // namespace

TEST(NssAccuracy, LongitudinalAndLateralWithinFivePercentFromLambdaOverA2) {
  for (double ab : {0.5, 1.0, 2.0})
    for (CreepageKind k : {CreepageKind::kXi, CreepageKind::kEta}) {
      const CurveErrors e = errors(k, ab, 2.0);
      EXPECT_LE(e.maxNss, 0.05) << toString(k) << " a/b " << ab;  // issue target
      EXPECT_LT(e.meanNss, 0.2 * e.meanShenLi) << toString(k) << " a/b " << ab;
    }
}

TEST(NssAccuracy, SpinCoefficientWithinFivePercentFromLambdaOverA2) {
  // The shipped table's kind 23 is second order (README "Spin: why C23 misses"): the first-order
  // F missed by 0.08-0.12 between lambda/a = 2 and about 4.5; the second-order one meets the
  // issue target from lambda/a = 2.
  for (double ab : {0.5, 1.0, 2.0}) {
    const CurveErrors e = errors(CreepageKind::kPhi, ab, 2.0);
    EXPECT_LE(e.maxNss, 0.05) << "a/b " << ab;  // issue target
    EXPECT_LT(e.meanNss, 0.2 * e.meanShenLi) << "a/b " << ab;
  }
}
