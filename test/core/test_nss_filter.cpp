#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "wheel_rail_contact/nss_filter.hpp"

using namespace wheel_rail_contact;

namespace {
// Response of the discrete filter (transposed direct form II) to a sampled harmonic, measured by
// running it to periodic steady state.
std::complex<double> discreteGain(const FilterZ& z, double omegaDt) {
  double s = 0.0;
  std::complex<double> acc = 0.0;
  const int n = 20000, keep = 10000;
  for (int k = 0; k < n; ++k) {
    const double g = std::cos(omegaDt * k);
    const double h = z.b0 * g + s;
    s = z.b1 * g - z.a1 * h;
    if (k >= n - keep) acc += h * std::exp(std::complex<double>(0.0, -omegaDt * k));
  }
  return 2.0 * acc / double(keep);
}
}  // namespace

TEST(NssFilter, StaticFilterIsExactlyShenLi) {
  const FilterZ z = discretise(ChiParameters{}, 0.01, 20.0, 1e-4);
  EXPECT_EQ(z.b0, 1.0);
  EXPECT_EQ(z.b1, 0.0);
  EXPECT_EQ(z.a1, 0.0);
  EXPECT_TRUE(ChiParameters{}.valid());
  EXPECT_FALSE((ChiParameters{0.5, 1.0, 0.0}.valid()));
  EXPECT_FALSE((ChiParameters{0.5, 1.0, -0.1}.valid()));
}

TEST(NssFilter, TustinMatchesTheContinuousResponseAtLowFrequency) {
  const ChiParameters chi{0.3, 0.9, 0.5};
  const double a = 0.01, V = 10.0, dt = 2e-5;  // V dt = a / 50
  for (double lambdaOverA : {5.0, 20.0, 100.0}) {
    const double k = 2 * M_PI / lambdaOverA, omegaDt = k * V * dt / a;
    const std::complex<double> d = discreteGain(discretise(chi, a, V, dt), omegaDt);
    EXPECT_NEAR(std::abs(d - transferFunction(chi, k)), 0.0, 2e-3) << lambdaOverA;
  }
}

TEST(NssFilter, PoleInsideUnitCircleForEveryStep) {
  const ChiParameters chi{0.2, 1.1, 0.05};
  for (double dt : {1e-9, 1e-6, 1e-3, 1.0, 1e3}) {
    const FilterZ z = discretise(chi, 0.01, 5.0, dt);
    EXPECT_LT(std::abs(z.a1), 1.0) << dt;
    EXPECT_TRUE(std::isfinite(z.b0) && std::isfinite(z.b1));
  }
}

TEST(NssFilter, WeightsAverageTheCoefficients) {
  const FilterZ z1{1.0, 2.0, 0.5}, z2{3.0, -2.0, -0.5};
  const FilterZ w = weightedFilter(z1, 3.0, z2, 1.0);
  EXPECT_DOUBLE_EQ(w.b0, 1.5);
  EXPECT_DOUBLE_EQ(w.b1, 1.0);
  EXPECT_DOUBLE_EQ(w.a1, 0.25);
  const FilterZ only = weightedFilter(z1, 2.0, z2, 0.0);
  EXPECT_DOUBLE_EQ(only.b0, z1.b0);
}
