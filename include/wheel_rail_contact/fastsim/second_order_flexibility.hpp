/// A second-order dynamic flexibility, the candidate for the spin kind 23 (whose exact response
/// a first-order F cannot follow at 2 <= lambda/a < 5; doc/validation.md, "Accuracy against our
/// exact solver"):
///   F(k) = (chi2 + s chi1 + s^2 chi4) / (1 + s chi3 + s^2 chi5),  s = i k,  k = 2 pi a / lambda,
/// with s <-> (a/V) d/dt as for the first-order F of nss_filter.hpp, which it contains
/// (chi4 = chi5 = 0). All chi dimensionless. The march discretises it inside
/// the core (Tustin, doc/method.md#second-order-flexibility).
#pragma once

#include <complex>

#include "wheel_rail_contact/fastsim/nss_filter.hpp"

namespace wheel_rail_contact {

struct SecondOrderChi {
  double chi1 = 0.0;
  double chi2 = 1.0;
  double chi3 = 0.0;
  double chi4 = 0.0;
  double chi5 = 0.0;

  /// The first-order F of `chi` (chi4 = chi5 = 0).
  static SecondOrderChi fromFirstOrder(const ChiParameters& chi);
  /// F(k) at spatial frequency k (continuous time).
  std::complex<double> at(double k) const;
  /// |F| as k -> infinity (chi4/chi5; chi1/chi3 for a first-order F): the dynamic flexibility a
  /// very short wave or a jump sees, relative to the static one.
  double highFrequencyGain() const;
  /// True if every node's slip equation is stable for every step h > 0 in continuous time: the
  /// node obeys D(s) tau + (h/a) s N(s) tau = forcing (N, D: numerator, denominator of F), and
  /// chi4 (h/a) s^3 + (chi5 + (h/a) chi1) s^2 + (chi3 + (h/a) chi2) s + 1 is Hurwitz for every
  /// h/a > 0 (Routh). First-order F: the condition of ChiParameters::valid() with chi3 > 0.
  bool valid() const;
};

}  // namespace wheel_rail_contact
