#include "wheel_rail_contact/geometry/hertz.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wheel_rail_contact {

void completeEllipticIntegrals(double m, double* K, double* E) {
  if (!(m >= 0.0 && m < 1.0)) throw std::invalid_argument("elliptic parameter m must be in [0, 1)");
  // Arithmetic-geometric mean: K = pi / (2 AGM(1, k')), E = K (1 - sum 2^(n-1) c_n^2).
  double an = 1.0, bn = std::sqrt(1.0 - m), cn2 = m, sum = 0.5 * m, pow2 = 0.5;
  for (int n = 0; n < 64 && cn2 > 1e-32; ++n) {
    const double a_next = 0.5 * (an + bn);
    const double c_next = 0.5 * (an - bn);
    bn = std::sqrt(an * bn);
    an = a_next;
    cn2 = c_next * c_next;
    pow2 *= 2.0;
    sum += pow2 * cn2;
  }
  *K = M_PI / (2.0 * an);
  *E = *K * (1.0 - sum);
}

double contactModulus(double G, double nu) {
  return G / (1.0 - nu);
}

namespace {

// Ratio of the larger to the smaller relative curvature as a function of e^2 for a >= b
// (Johnson, Contact Mechanics, eq. 4.39): B/A = ((a/b)^2 E - K) / (K - E).
double curvatureRatio(double e2) {
  double K, E;
  completeEllipticIntegrals(e2, &K, &E);
  return (E / (1.0 - e2) - K) / (K - E);
}

}  // namespace

HertzEllipse hertzFromCurvatures(double fz, double A, double B, double G, double nu) {
  if (!(fz > 0.0)) throw std::invalid_argument("hertz: normal load must be > 0");
  if (!(A > 0.0) || !(B > 0.0)) throw std::invalid_argument("hertz: curvatures must be > 0");
  if (!(G > 0.0)) throw std::invalid_argument("hertz: G must be > 0");
  if (!(nu >= 0.0 && nu < 0.5)) throw std::invalid_argument("hertz: nu must be in [0, 0.5)");
  const double Estar = contactModulus(G, nu);
  const double lo = std::min(A, B), hi = std::max(A, B);
  const double ratio = hi / lo;
  // Eccentricity of the ellipse (major axis along the smaller curvature): bisection on e^2, the
  // ratio grows monotonically from 1 at e^2 = 0.
  double e2 = 0.0;
  if (ratio > 1.0 + 1e-12) {
    double left = 0.0, right = 1.0 - 1e-15;
    for (int it = 0; it < 200 && right - left > 1e-16; ++it) {
      const double mid = 0.5 * (left + right);
      (mid > 0.0 && curvatureRatio(mid) < ratio ? left : right) = mid;
    }
    e2 = 0.5 * (left + right);
  }
  double major;
  if (e2 < 1e-10) {
    major = std::cbrt(3.0 * fz / (8.0 * Estar * lo));  // circle: a^3 = 3 P R / (4 E*), R = 1/(2A)
  } else {
    double K, E;
    completeEllipticIntegrals(e2, &K, &E);
    // A_lo = 3P (K - E) / (2 pi E* a^3 e^2)
    major = std::cbrt(3.0 * fz * (K - E) / (2.0 * M_PI * Estar * lo * e2));
  }
  const double minor = major * std::sqrt(1.0 - e2);
  HertzEllipse h;
  h.a = (A <= B) ? major : minor;
  h.b = (A <= B) ? minor : major;
  h.p0 = 3.0 * fz / (2.0 * M_PI * h.a * h.b);
  return h;
}

HertzEllipse ReferencePatch::at(double fz) const {
  const double s = std::cbrt(fz / fz0);
  HertzEllipse h;
  h.a = a0 * s;
  h.b = b0 * s;
  h.p0 = 3.0 * fz / (2.0 * M_PI * h.a * h.b);
  return h;
}

}  // namespace wheel_rail_contact
