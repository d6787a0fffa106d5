/// The dynamic flexibility of NSS-FastSim (Alonso & Gimenez 2008): a first-order transfer function
/// F(k) = (chi2 + i k chi1) / (1 + i k chi3), the ratio of dynamic to static flexibility at the
/// dimensionless spatial frequency k = 2 pi a / lambda (i k <-> (a/V) d/dt;
/// doc/method.md#dynamic-flexibility). chi1, chi2, chi3 are dimensionless. F == 1 (chi = {0, 1, 0})
/// is Shen & Li's model.
#pragma once

#include <complex>

namespace wheel_rail_contact {

struct ChiParameters {
  double chi1 = 0.0;
  double chi2 = 1.0;
  double chi3 = 0.0;
  /// True if the discretised filter is stable for every step: chi3 > 0, or the static case
  /// chi1 = chi3 = 0.
  bool valid() const;
};

/// F at spatial frequency k (continuous time).
std::complex<double> transferFunction(const ChiParameters& chi, double k);

}  // namespace wheel_rail_contact
