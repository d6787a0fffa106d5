#include "wheel_rail_contact/nss_filter.hpp"

#include <cmath>

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

FilterZ weightedFilter(const FilterZ& z1, double w1, const FilterZ& z2, double w2) {
  // As z1 + t (z2 - z1): exactly z1 when both kinds share a filter or w2 = 0.
  const double t = w2 / (w1 + w2);
  return {z1.b0 + t * (z2.b0 - z1.b0), z1.b1 + t * (z2.b1 - z1.b1), z1.a1 + t * (z2.a1 - z1.a1)};
}

}  // namespace wheel_rail_contact
