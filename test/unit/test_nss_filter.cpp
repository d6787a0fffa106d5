#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/fastsim/discrete_filter.hpp"
#include "wheel_rail_contact/fastsim/nss_filter.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

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

namespace {
// H(z) of the discrete filter at z = exp(i omega dt), with all five coefficients.
std::complex<double> zResponse(const FilterZ& z, double omegaDt) {
  const std::complex<double> q = std::exp(std::complex<double>(0.0, -omegaDt));  // z^-1
  return (z.b0 + q * (z.b1 + q * z.b2)) / (1.0 + q * (z.a1 + q * z.a2));
}
}  // namespace

// The fitted kind-23 F at a/b = 1 (doc/data/spin_second_order_chi.csv).
const SecondOrderChi kSpinChi{0.744200, 1.776235, 0.511910, 0.107313, 0.021463};

TEST(NssFilter, SecondOrderDiscretisationTendsToF) {
  // Tustin's error is the frequency warping, relative (omega dt)^2 / 12 at small omega dt: a
  // tenfold smaller step must bring H within 1e-3 of F, and shrink the error about 100 times.
  const double a = 0.006, V = 20.0;
  for (double k : {0.3, 1.3, 3.0}) {
    const double omega = V * k / a;
    const std::complex<double> F = kSpinChi.at(k);
    double previous = 0.0;
    for (double dt : {a / V / 20, a / V / 200}) {
      const FilterZ z = discretise(kSpinChi, a, V, dt);
      ASSERT_TRUE(z.secondOrder());
      const double err = std::abs(zResponse(z, omega * dt) - F) / std::abs(F);
      if (previous > 0.0) {
        EXPECT_LT(err, 1e-3) << k;
        EXPECT_LT(err, 0.02 * previous) << k;
      }
      previous = err;
    }
  }
}

TEST(NssFilter, SecondOrderWithoutChi4Chi5IsTheFirstOrderFilterBitForBit) {
  const ChiParameters first{0.4, 1.1, 0.6};
  for (double dt : {1e-6, 1e-4, 1e-2}) {
    const FilterZ z1 = discretise(first, 0.006, 20.0, dt),
                  z2 = discretise(SecondOrderChi::fromFirstOrder(first), 0.006, 20.0, dt);
    EXPECT_FALSE(z2.secondOrder());
    EXPECT_EQ(z1.b0, z2.b0);
    EXPECT_EQ(z1.b1, z2.b1);
    EXPECT_EQ(z1.a1, z2.a1);
    EXPECT_EQ(z2.b2, 0.0);
    EXPECT_EQ(z2.a2, 0.0);
  }
}

TEST(NssFilter, WeightedSecondOrderFilterMixesAllFiveAndStaysStable) {
  const FilterZ first = discretise(ChiParameters{0.4, 1.1, 0.6}, 0.006, 20.0, 1e-5);
  for (double dt : {1e-7, 1e-5, 1e-3, 1e-1}) {
    const FilterZ second = discretise(kSpinChi, 0.006, 20.0, dt);
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const FilterZ z = weightedFilter(first, 1.0 - t, second, t);
      EXPECT_NEAR(z.b2, t * second.b2, 1e-15 + 1e-12 * std::abs(second.b2));
      EXPECT_NEAR(z.a2, t * second.a2, 1e-15);
      // Schur stability of 1 + a1 z^-1 + a2 z^-2 (the triangle |a2| < 1, |a1| < 1 + a2).
      EXPECT_LT(std::abs(z.a2), 1.0) << dt << " " << t;
      EXPECT_LT(std::abs(z.a1), 1.0 + z.a2) << dt << " " << t;
    }
  }
}
