/// Identification of the dynamic-flexibility parameters chi (paper eq. 8,
/// doc/method.md#chi-identification): minimise the distance between the exact and the NSS-FastSim
/// non-steady creep coefficients over lambda/a in [1, 100], on the ratio to each model's own steady
/// coefficient (so the exact grid's 1-4 % bias in the steady value is not fitted into chi). Measure
/// (choice): d(ln lambda/a), which weighs short and long waves alike; the paper's d(lambda/a) is
/// reported alongside.
#pragma once

#include <complex>
#include <vector>

#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

namespace wheel_rail_contact {

struct FrequencyPoint {
  double lambdaOverA = 0.0;
  std::complex<double> ratio;  ///< C^(lambda/a) / C_steady [-]
};

struct ChiFit {
  ChiParameters chi;
  double meanErrorLog = 0.0;     ///< (1/ln 100) int |r_exact - r_nss| d(ln lambda/a) [-]
  double meanErrorLinear = 0.0;  ///< (1/99) int |r_exact - r_nss| d(lambda/a) [-]
  double maxError = 0.0;         ///< max over the points with lambda/a >= 2 [-]
  int evaluations = 0;
};

/// The error measures of `chi` against `exact` (points sorted by lambda/a) on an nx x ny mesh.
ChiFit evaluateChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                   const ChiParameters& chi, const std::vector<FrequencyPoint>& exact);

/// Best chi (chi1 >= 0, chi2 > 0, chi3 > 0) by Nelder-Mead in log-parameters from several starts,
/// minimising meanErrorLog + maxWeight * maxError.
ChiFit fitChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
              const std::vector<FrequencyPoint>& exact, double maxWeight = 0.0);

/// The same measures for a second-order F (second_order_flexibility.hpp).
struct SecondOrderFit {
  SecondOrderChi chi;
  double meanErrorLog = 0.0;     ///< as ChiFit [-]
  double meanErrorLinear = 0.0;  ///< as ChiFit [-]
  double maxError = 0.0;         ///< max over the points with lambda/a >= 2 [-]
  int evaluations = 0;
};

SecondOrderFit evaluateSecondOrderChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                                      const SecondOrderChi& chi,
                                      const std::vector<FrequencyPoint>& exact);

/// Best stable second-order F (SecondOrderChi::valid) minimising meanErrorLog + maxWeight *
/// maxError + max(0, highFrequencyGain - maxHighFrequencyGain). The gain bound keeps F from
/// buying the fit at lambda/a >= 2 with a huge flexibility at very short waves (unbounded, the
/// fit drives chi5 -> 0, an almost improper F). Starts from fitChi(..., maxWeight).
SecondOrderFit fitSecondOrderChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                                 const std::vector<FrequencyPoint>& exact, double maxWeight = 10.0,
                                 double maxHighFrequencyGain = 5.0);

}  // namespace wheel_rail_contact
