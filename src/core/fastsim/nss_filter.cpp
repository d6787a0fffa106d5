#include "wheel_rail_contact/fastsim/nss_filter.hpp"

#include <cmath>

#include "core/fastsim/discrete_filter.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

namespace wheel_rail_contact {

bool ChiParameters::valid() const {
  if (!std::isfinite(chi1) || !std::isfinite(chi2) || !std::isfinite(chi3)) return false;
  return chi3 > 0.0 || (chi1 == 0.0 && chi3 == 0.0);
}

std::complex<double> transferFunction(const ChiParameters& chi, double k) {
  const std::complex<double> ik(0.0, k);
  return (chi.chi2 + ik * chi.chi1) / (1.0 + ik * chi.chi3);
}

FilterZ discretise(const ChiParameters& chi, double a, double V, double dt) {
  FilterZ z;
  if (chi.chi1 == 0.0 && chi.chi3 == 0.0) {  // static: no dynamics, no cancelled pole at z = -1
    z.b0 = chi.chi2;
    return z;
  }
  // Tustin: (a/V) d/dt -> c (1 - z^-1) / (1 + z^-1), c = 2 a / (V dt).
  const double c = 2.0 * a / (V * dt);
  const double den = 1.0 + chi.chi3 * c;
  z.b0 = (chi.chi2 + chi.chi1 * c) / den;
  z.b1 = (chi.chi2 - chi.chi1 * c) / den;
  z.a1 = (1.0 - chi.chi3 * c) / den;
  return z;
}

FilterZ discretise(const SecondOrderChi& chi, double a, double V, double dt) {
  if (chi.chi4 == 0.0 && chi.chi5 == 0.0)
    return discretise(ChiParameters{chi.chi1, chi.chi2, chi.chi3}, a, V, dt);
  // Tustin as above, numerator and denominator times (1 + z^-1)^2:
  //   N = chi2 (1 + z^-1)^2 + chi1 c (1 - z^-2) + chi4 c^2 (1 - z^-1)^2, D alike with 1, chi3,
  //   chi5.
  const double c = 2.0 * a / (V * dt), c2 = c * c;
  const double den = 1.0 + chi.chi3 * c + chi.chi5 * c2;
  FilterZ z;
  z.b0 = (chi.chi2 + chi.chi1 * c + chi.chi4 * c2) / den;
  z.b1 = 2.0 * (chi.chi2 - chi.chi4 * c2) / den;
  z.b2 = (chi.chi2 - chi.chi1 * c + chi.chi4 * c2) / den;
  z.a1 = 2.0 * (1.0 - chi.chi5 * c2) / den;
  z.a2 = (1.0 - chi.chi3 * c + chi.chi5 * c2) / den;
  return z;
}

FilterZ weightedFilter(const FilterZ& z1, double w1, const FilterZ& z2, double w2) {
  // As z1 + t (z2 - z1): exactly z1 when both kinds share a filter or w2 = 0.
  const double t = w2 / (w1 + w2);
  auto mix = [t](double u, double v) { return u + t * (v - u); };
  return {mix(z1.b0, z2.b0), mix(z1.b1, z2.b1), mix(z1.a1, z2.a1), mix(z1.b2, z2.b2),
          mix(z1.a2, z2.a2)};
}

}  // namespace wheel_rail_contact
