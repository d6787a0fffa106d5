/// Kalker's linear-theory creep coefficients C11, C22, C23 (dimensionless) for an elliptic contact
/// of two elastically identical bodies. Source: J.J. Kalker, Three-Dimensional Elastic Bodies in
/// Rolling Contact, Kluwer 1990, Table E.3 (nu = 0, 0.25, 0.5; g = a/b from 0.1 to 1 and b/a from 1
/// to 0.1). Interpolated as CONTACT does: linearly in g (a/b for a <= b, b/a for a >= b) and by the
/// parabola through 1/C at the three tabulated nu. Linear theory: Fx = -G a b C11 xi, Fy = -G a b
/// C22 eta - G (ab)^(3/2) C23 phi.
#pragma once

namespace wheel_rail_contact {

struct CreepCoefficients {
  double c11 = 0.0;  ///< longitudinal [-]
  double c22 = 0.0;  ///< lateral [-]
  double c23 = 0.0;  ///< lateral force from spin [-]
};

/// Smallest and largest a/b covered by the table (0.1 and 10).
constexpr double kKalkerMinAOverB = 0.1;
constexpr double kKalkerMaxAOverB = 10.0;

/// Coefficients at a/b in [0.1, 10] and nu in [0, 0.5]. Outside the table throws std::domain_error
/// naming the value: extrapolating Kalker's table is not physics we can vouch for.
CreepCoefficients kalkerCoefficients(double a_over_b, double nu);

/// The raw table entry at row `row` (0..18: a/b = 0.1..1 then b/a = 0.9..0.1) and nu index 0..2.
CreepCoefficients kalkerTableEntry(int row, int nu_index);

/// a/b of table row `row`.
double kalkerTableAOverB(int row);

}  // namespace wheel_rail_contact
