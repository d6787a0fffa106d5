/// Hertz contact of two elastically identical bodies (same G, nu).
/// Units: SI throughout — forces N, lengths m, moduli and pressures Pa, curvatures 1/m.
/// x is the rolling direction (semi-axis a), y lateral (semi-axis b).
#pragma once

namespace wheel_rail_contact {

/// Contact ellipse x^2/a^2 + y^2/b^2 <= 1 with Hertz pressure p0*sqrt(1 - x^2/a^2 - y^2/b^2).
struct HertzEllipse {
  double a = 0.0;   ///< semi-axis along x (rolling) [m]
  double b = 0.0;   ///< semi-axis along y (lateral) [m]
  double p0 = 0.0;  ///< peak pressure 3 Fz / (2 pi a b) [Pa]
};

/// Complete elliptic integrals K(m), E(m) of parameter m = k^2 in [0, 1), by the
/// arithmetic-geometric mean (exact to rounding, not a curve fit).
void completeEllipticIntegrals(double m, double* K, double* E);

/// Contact modulus E* = E / (2 (1 - nu^2)) = G / (1 - nu) for two identical bodies [Pa].
double contactModulus(double G, double nu);

/// Hertz ellipse from the normal load fz [N] and the principal relative curvatures A (along x) and
/// B (along y) of the undeformed gap h = A x^2 + B y^2 [1/m]. Throws std::invalid_argument on fz <=
/// 0, A <= 0, B <= 0, G <= 0 or nu outside [0, 0.5).
HertzEllipse hertzFromCurvatures(double fz, double A, double B, double G, double nu);

/// A reference patch (a0, b0) at load fz0: for fixed curvatures, a and b scale as (fz/fz0)^(1/3).
struct ReferencePatch {
  double a0 = 0.0;   ///< [m]
  double b0 = 0.0;   ///< [m]
  double fz0 = 0.0;  ///< [N]
  /// The ellipse at load fz > 0 (a = a0 (fz/fz0)^(1/3), same for b; p0 from fz).
  HertzEllipse at(double fz) const;
};

}  // namespace wheel_rail_contact
