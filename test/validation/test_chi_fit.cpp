#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "validation/chi_fit.hpp"
#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

using namespace wheel_rail_contact;

TEST(ChiFit, RecoversTheParametersOfASyntheticCurve) {
  // A "reference" made by the model itself with known chi on a different mesh must be fitted back
  // to nearly the same chi and a tiny error: the optimiser and the measure work.
  const ChiParameters truth{0.35, 1.2, 0.45};
  std::vector<FrequencyPoint> curve;
  const double steady = fastsimSteadyCoefficient(CreepageKind::kEta, 1.5, 0.28, 16, 16);
  for (double l = 1.0; l <= 100.0 * 1.0001; l *= std::pow(100.0, 1.0 / 24))
    curve.push_back(
        {l, fastsimNonSteadyCoefficient(CreepageKind::kEta, 1.5, 0.28, 16, 16, truth, l) / steady});
  const ChiFit fit = fitChi(CreepageKind::kEta, 1.5, 0.28, 16, 16, curve);
  EXPECT_LT(fit.meanErrorLog, 1e-4);
  EXPECT_NEAR(fit.chi.chi1, truth.chi1, 0.02);
  EXPECT_NEAR(fit.chi.chi2, truth.chi2, 0.02);
  EXPECT_NEAR(fit.chi.chi3, truth.chi3, 0.02);
  EXPECT_GT(fit.chi.chi3, 0.0);
  // Shen & Li (chi = {0, 1, 0}) is measurably worse on the same curve.
  EXPECT_GT(evaluateChi(CreepageKind::kEta, 1.5, 0.28, 16, 16, ChiParameters{}, curve).meanErrorLog,
            10 * fit.meanErrorLog);
}
