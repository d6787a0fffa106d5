/// Hertz's solution for a prescribed approach: curvatures A (along x), B (along y) of the gap
/// h = A x^2 + B y^2 [1/m], rigid approach d [m], contact modulus E* = G / (1 - nu) [Pa].
#pragma once

namespace wheel_rail_contact {

struct HertzApproach {
  double a = 0.0, b = 0.0;  ///< semi-axes along x and y [m]
  double p0 = 0.0;          ///< peak pressure [Pa]
  double fn = 0.0;          ///< load [N]
};

/// With e^2 = 1 - (minor/major)^2 from the curvatures' ratio (Johnson eq. 4.39:
/// hi/lo = (E/(1-e^2) - K) / (K - E)): major^2 = d (K - E) / (lo e^2 K), p0 = d E* / (minor K)
/// (the approach d = p0 minor K(e) / E*, Johnson section 4.2), fn = 2 pi a b p0 / 3. A, B, d > 0.
HertzApproach hertzFromApproach(double A, double B, double d, double Estar);

}  // namespace wheel_rail_contact
