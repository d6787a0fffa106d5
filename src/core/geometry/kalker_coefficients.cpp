#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

constexpr int kRows = 19;
// Kalker 1990, Table E.3. Rows: a/b = 0.1 .. 1.0, then b/a = 0.9 .. 0.1 (a/b = 1.11 .. 10).
// Columns: C11, C22, C23, each at nu = 0, 0.25, 0.5. (CONTACT's copy reads 1.15 for C23 at
// a/b = 0.8, nu = 0.25; the table's own row-to-row steps of 0.11 give 1.25, which we keep.)
constexpr double kTable[kRows][9] = {
    {2.51, 3.31, 4.85, 2.51, 2.52, 2.53, 0.334, 0.473, 0.731},  // a/b = 0.1
    {2.59, 3.37, 4.81, 2.59, 2.63, 2.66, 0.483, 0.603, 0.809},  // 0.2
    {2.68, 3.44, 4.80, 2.68, 2.75, 2.81, 0.607, 0.715, 0.889},  // 0.3
    {2.78, 3.53, 4.82, 2.78, 2.88, 2.98, 0.720, 0.823, 0.977},  // 0.4
    {2.88, 3.62, 4.83, 2.88, 3.01, 3.14, 0.827, 0.929, 1.07},   // 0.5
    {2.98, 3.72, 4.91, 2.98, 3.14, 3.31, 0.930, 1.03, 1.18},    // 0.6
    {3.09, 3.81, 4.97, 3.09, 3.28, 3.48, 1.03, 1.14, 1.29},     // 0.7
    {3.19, 3.91, 5.05, 3.19, 3.41, 3.65, 1.13, 1.25, 1.40},     // 0.8
    {3.29, 4.01, 5.12, 3.29, 3.54, 3.82, 1.23, 1.36, 1.51},     // 0.9
    {3.40, 4.12, 5.20, 3.40, 3.67, 3.98, 1.33, 1.47, 1.63},     // 1.0
    {3.51, 4.22, 5.30, 3.51, 3.81, 4.16, 1.44, 1.59, 1.77},     // b/a = 0.9
    {3.65, 4.36, 5.42, 3.65, 3.99, 4.39, 1.58, 1.75, 1.94},     // 0.8
    {3.82, 4.54, 5.58, 3.82, 4.21, 4.67, 1.76, 1.95, 2.18},     // 0.7
    {4.06, 4.78, 5.80, 4.06, 4.50, 5.04, 2.01, 2.23, 2.50},     // 0.6
    {4.37, 5.10, 6.11, 4.37, 4.90, 5.56, 2.35, 2.62, 2.96},     // 0.5
    {4.84, 5.57, 6.57, 4.84, 5.48, 6.31, 2.88, 3.24, 3.70},     // 0.4
    {5.57, 6.34, 7.34, 5.57, 6.40, 7.51, 3.79, 4.32, 5.01},     // 0.3
    {6.96, 7.78, 8.82, 6.96, 8.14, 9.79, 5.72, 6.63, 7.89},     // 0.2
    {10.7, 11.7, 12.9, 10.7, 12.8, 16.0, 12.2, 14.6, 18.0},     // 0.1
};

// Position of a/b on the table's own axis: rows 0..9 are linear in a/b, rows 9..18 linear in b/a.
double rowCoordinate(double a_over_b) {
  if (a_over_b <= 1.0) return a_over_b * 10.0 - 1.0;
  return 9.0 + (1.0 - 1.0 / a_over_b) * 10.0;
}

// Parabola through 1/C at nu = 0, 0.25, 0.5 (Lagrange form), evaluated at nu.
double inNu(const double* c, double nu) {
  const double l0 = (nu - 0.25) * (nu - 0.5) / 0.125;
  const double l1 = nu * (nu - 0.5) / -0.0625;
  const double l2 = nu * (nu - 0.25) / 0.125;
  return 1.0 / (l0 / c[0] + l1 / c[1] + l2 / c[2]);
}

}  // namespace

double kalkerTableAOverB(int row) {
  return row <= 9 ? 0.1 * (row + 1) : 1.0 / (0.1 * (19 - row));
}

CreepCoefficients kalkerTableEntry(int row, int nu_index) {
  if (row < 0 || row >= kRows || nu_index < 0 || nu_index > 2)
    throw std::out_of_range("kalkerTableEntry: index out of range");
  return {kTable[row][nu_index], kTable[row][3 + nu_index], kTable[row][6 + nu_index]};
}

CreepCoefficients kalkerCoefficients(double a_over_b, double nu) {
  if (!(a_over_b >= kKalkerMinAOverB * (1 - 1e-12) && a_over_b <= kKalkerMaxAOverB * (1 + 1e-12))) {
    std::ostringstream s;
    s << "a/b = " << a_over_b << " is outside Kalker's table [0.1, 10]";
    throw std::domain_error(s.str());
  }
  if (!(nu >= 0.0 && nu <= 0.5)) {
    std::ostringstream s;
    s << "nu = " << nu << " is outside Kalker's table [0, 0.5]";
    throw std::domain_error(s.str());
  }
  const double r = std::min(std::max(rowCoordinate(a_over_b), 0.0), kRows - 1.0);
  const int r0 = std::min(static_cast<int>(r), kRows - 2);
  const double w = r - r0;
  double out[3];
  for (int k = 0; k < 3; ++k) {  // linear in g first, then the parabola in nu, as CONTACT does
    double c[3];
    for (int n = 0; n < 3; ++n)
      c[n] = (1.0 - w) * kTable[r0][3 * k + n] + w * kTable[r0 + 1][3 * k + n];
    out[k] = inNu(c, nu);
  }
  return {out[0], out[1], out[2]};
}

}  // namespace wheel_rail_contact
