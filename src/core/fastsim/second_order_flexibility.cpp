#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

#include <cmath>
#include <limits>

namespace wheel_rail_contact {

SecondOrderChi SecondOrderChi::fromFirstOrder(const ChiParameters& chi) {
  return {chi.chi1, chi.chi2, chi.chi3, 0.0, 0.0};
}

std::complex<double> SecondOrderChi::at(double k) const {
  const std::complex<double> s(0.0, k);
  return (chi2 + s * (chi1 + s * chi4)) / (1.0 + s * (chi3 + s * chi5));
}

double SecondOrderChi::highFrequencyGain() const {
  if (chi5 > 0.0) return std::abs(chi4) / chi5;
  if (chi4 != 0.0) return std::numeric_limits<double>::infinity();  // improper F
  return chi3 > 0.0 ? std::abs(chi1) / chi3 : std::abs(chi2);
}

bool SecondOrderChi::valid() const {
  for (double c : {chi1, chi2, chi3, chi4, chi5})
    if (!std::isfinite(c)) return false;
  // Hurwitz for every g = h/a > 0: every coefficient of the cubic positive (chi4 = 0: quadratic)
  // and (chi5 + g chi1)(chi3 + g chi2) > g chi4, i.e. chi3 chi5 + g B + g^2 chi1 chi2 > 0 with
  // B = chi1 chi3 + chi2 chi5 - chi4, for all g > 0.
  if (!(chi1 >= 0.0 && chi2 > 0.0 && chi3 > 0.0 && chi4 >= 0.0 && chi5 >= 0.0)) return false;
  if (chi4 > 0.0 && !(chi5 > 0.0)) return false;  // improper: F grows without bound
  const double B = chi1 * chi3 + chi2 * chi5 - chi4;
  return B >= 0.0 || B * B < 4.0 * chi1 * chi2 * chi3 * chi5;
}

}  // namespace wheel_rail_contact
