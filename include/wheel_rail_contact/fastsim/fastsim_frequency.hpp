/// Frequency response of the FastSim models in full adhesion: the non-steady creep coefficient
/// C^(lambda/a) (complex, dimensionless) for one small harmonic creepage, with the convention of
/// doc/method.md#chi-identification (creepage = amp cos(wt); C = -F^/(norm amp); Im C < 0 is a
/// lag). Computed exactly for the model's space discretisation in the continuous-time limit dt ->
/// 0, by one complex march per strip: tau_i (1/h + (i k / a) F(k)) = tau_up / h - D_i, k = 2 pi
/// a/lambda.
#pragma once

#include <complex>

#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/nss_filter.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

namespace wheel_rail_contact {

/// C^ of a FastSim model on an nx x ny mesh at a/b and nu with dynamic flexibility `chi`
/// ({0, 1, 0} for Shen & Li). lambda_over_a = +infinity gives the steady coefficient.
std::complex<double> fastsimNonSteadyCoefficient(CreepageKind kind, double a_over_b, double nu,
                                                 int nx, int ny, const ChiParameters& chi,
                                                 double lambda_over_a);

/// The same with a second-order dynamic flexibility (second_order_flexibility.hpp).
std::complex<double> fastsimSecondOrderCoefficient(CreepageKind kind, double a_over_b, double nu,
                                                   int nx, int ny, const SecondOrderChi& chi,
                                                   double lambda_over_a);

/// The steady FastSim coefficient on the same mesh (real; equals Kalker's C within the mesh error).
double fastsimSteadyCoefficient(CreepageKind kind, double a_over_b, double nu, int nx, int ny);

}  // namespace wheel_rail_contact
