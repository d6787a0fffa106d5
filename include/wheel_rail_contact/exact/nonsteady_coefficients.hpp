/// Exact non-steady linear creep coefficients C11, C22, C23 as functions of the wavelength of a
/// harmonic creepage (doc/method.md#chi-identification), from the transient half-space scheme of
/// halfspace_solver.hpp (shift dq = dx per step) in full adhesion, at periodic steady state.
/// Convention: creepage = cos(omega t), omega t = 2 pi q / lambda; each step uses the exact mean of
/// the creepage over the step (as CONTACT's reference runs); C = -F^/(norm), F = Re(F^ e^{i omega
/// t}), norm = G a b (xi, eta) or G (ab)^{3/2} (phi); Im C < 0 is a lag. Dimensionless; G cancels.
/// Grid: mx x my elements over [-1.1a, 1.1a] x [-1.1b, 1.1b]; contact = the loaded elements of the
/// discrete Hertz normal problem (halfspace_normal.hpp), as in CONTACT.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "wheel_rail_contact/fastsim/creepage_kind.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

/// Frequency response of the discrete scheme: harmonic unknowns tau^n = tau^ z^n, z = e^{i omega
/// dt}, solve (A - B/z) tau^ = -dx w^ on the contact elements (A: influence at the element, B: at
/// its upstream neighbour), folded by the y-symmetry of the kind (about mx*my/1.6 unknowns).
/// Built once per (kind, a/b, nu, grid): A^-1 B = Q H Q^T (Hessenberg, about 6 n^3 flops), so
/// that every at() is one O(n^2) Hessenberg solve of (I - H/z) y = Q^T A^-1 w.
class NonSteadyCoefficients {
 public:
  NonSteadyCoefficients(CreepageKind kind, double a_over_b, double nu, int mx, int my);
  /// Complex coefficient at wavelength lambda = lambda_over_a * a (> 0).
  std::complex<double> at(double lambda_over_a) const;
  /// The same scheme in steady rolling (lambda -> infinity).
  double steady() const { return steady_; }
  int unknowns() const { return static_cast<int>(g_.size()); }

 private:
  std::complex<double> solve(std::complex<double> zinv, std::complex<double> wmean) const;
  CreepageKind kind_;
  double a_ = 1.0, b_ = 1.0, dx_ = 0.0, steady_ = 0.0;
  Eigen::MatrixXd H_;  // Hessenberg form of A^-1 B
  Eigen::VectorXd g_;  // Q^T A^-1 (rigid slip per unknown for unit creepage)
  Eigen::VectorXd h_;  // Q^T (force weight per unknown: dA times 1 or 2 (mirror), 0 off-axis)
};

/// One coefficient (C11 for kXi, C22 for kEta, C23 for kPhi) at lambda/a.
std::complex<double> exactNonSteadyCoefficient(CreepageKind kind, double a_over_b,
                                               double lambda_over_a, double nu, int mx, int my);

/// A whole curve: builds the matrices once.
std::vector<std::complex<double>> exactNonSteadyCurve(CreepageKind kind, double a_over_b,
                                                      const std::vector<double>& lambda_over_a,
                                                      double nu, int mx, int my);

/// Steady coefficient of the same scheme on the same grid (one LU, no Hessenberg reduction).
double exactSteadyCoefficient(CreepageKind kind, double a_over_b, double nu, int mx, int my);

/// C11, C22 and C23 of the steady scheme on one grid: one normal problem, two LU factorisations.
CreepCoefficients exactSteadyCoefficients(double a_over_b, double nu, int mx, int my);

}  // namespace wheel_rail_contact
