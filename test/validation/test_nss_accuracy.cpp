// Accuracy of NSS-FastSim with the shipped chi table against our exact half-space solver, at
// coarse CI settings (exact grid 20x20; the table was fitted at 30x30, and C^/C_steady moves by
// about 0.5 % between such grids).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"
#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

using namespace wheel_rail_contact;

namespace {

struct CurveErrors {
  double maxNss = 0.0, meanNss = 0.0, meanShenLi = 0.0;
};

// max over lambda/a >= from, and means over all points, of |C^/C_steady - exact| on log-spaced
// lambda/a in [from, 100], FastSim on an n x n mesh with the shipped table's chi for it (or, given
// chiMesh, for that mesh).
CurveErrors errors(CreepageKind kind, double ab, double from, int n = 20, int chiMesh = 0) {
  const ChiTable table = ChiTable::shipped().forMesh(chiMesh > 0 ? chiMesh : n);
  const NonSteadyCoefficients exact(kind, ab, 0.28, 20, 20);
  const double ce = exact.steady(), cf = fastsimSteadyCoefficient(kind, ab, 0.28, n, n);
  CurveErrors e;
  const int points = 10;
  for (int q = 0; q <= points; ++q) {
    const double l = from * std::pow(100.0 / from, double(q) / points);
    const std::complex<double> r = exact.at(l) / ce;
    const auto nss =
        fastsimSecondOrderCoefficient(kind, ab, 0.28, n, n, table.secondOrderAt(kind, ab), l);
    const auto sl = fastsimNonSteadyCoefficient(kind, ab, 0.28, n, n, {}, l);
    e.maxNss = std::max(e.maxNss, std::abs(nss / cf - r));
    e.meanNss += std::abs(nss / cf - r) / (points + 1);
    e.meanShenLi += std::abs(sl / cf - r) / (points + 1);
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
  // The shipped table's kind 23 is second order (doc/method.md#second-order-flexibility): the
  // first-order F missed by 0.08-0.12 between lambda/a = 2 and about 4.5; the second-order one
  // meets the issue target from lambda/a = 2.
  for (double ab : {0.5, 1.0, 2.0}) {
    const CurveErrors e = errors(CreepageKind::kPhi, ab, 2.0);
    EXPECT_LE(e.maxNss, 0.05) << "a/b " << ab;  // issue target
    EXPECT_LT(e.meanNss, 0.2 * e.meanShenLi) << "a/b " << ab;
  }
}

TEST(NssAccuracy, EveryShippedMeshFrom10x10MeetsTheTargetWithItsOwnChi) {
  // chi absorbs the march's discretisation: the 20x20 chi missed C23 by 0.08-0.10 on 10x10 and
  // 0.06-0.07 on 40x40 (exact 30x30, doc/validation.md, "The χ table"). Each mesh's own chi meets
  // the target (5x5 only against the 30x30 exact grid the table was fitted on: C23 0.033-0.048
  // there, 0.072 against this test's 20x20). a/b = 1 here; the three a/b at 20x20 above.
  for (int n : {10, 30, 40})
    for (CreepageKind k : kCreepageKinds) {
      const CurveErrors e = errors(k, 1.0, 2.0, n);
      EXPECT_LE(e.maxNss, 0.05) << toString(k) << " mesh " << n;  // issue target
      EXPECT_LT(e.meanNss, 0.2 * e.meanShenLi) << toString(k) << " mesh " << n;
    }
}

TEST(NssAccuracy, MeshesBetweenTheFittedOnesMeetTheTargetWithChiInterpolated) {
  // On 7x7 and 13x13 the spin coefficient with the nearest fitted mesh's chi (10x10) missed the
  // target (0.090 and 0.066 over lambda/a >= 2 at a/b 1, exact 30x30); chi interpolated in 1/nx
  // between the fitted meshes around them meets it (0.038, 0.019; doc/validation.md, "The χ
  // table").
  for (int n : {7, 13}) {
    EXPECT_GT(errors(CreepageKind::kPhi, 1.0, 2.0, n, 10).maxNss, 0.05) << "mesh " << n;
    const CurveErrors e = errors(CreepageKind::kPhi, 1.0, 2.0, n);
    EXPECT_LE(e.maxNss, 0.05) << "mesh " << n;  // issue target
    EXPECT_LT(e.meanNss, 0.2 * e.meanShenLi) << "mesh " << n;
  }
}
