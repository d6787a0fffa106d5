#include "core/normal/hertz_approach.hpp"

#include <algorithm>
#include <cmath>

#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

namespace {

/// (K - E) / m, K, E at parameter m; the series near m = 0 where K - E cancels.
void ellipticParts(double m, double* KmE_m, double* K, double* E) {
  completeEllipticIntegrals(m, K, E);
  *KmE_m = m < 1e-6 ? 0.25 * M_PI * (1.0 + 0.375 * m) : (*K - *E) / m;
}

/// ln of the curvature ratio hi/lo that the eccentricity m = e^2 gives, as a function of
/// t = -ln(1 - m).
double logRatio(double t) {
  const double m = -std::expm1(-t);
  double KmE_m, K, E;
  ellipticParts(m, &KmE_m, &K, &E);
  // hi/lo = (E/(1-m) - K)/(K - E); near m = 0 both vanish like m: use (E e^t - K)/m over (K-E)/m.
  if (m < 1e-6) return std::log1p(0.75 * m);
  return std::log((E * std::exp(t) - K) / (K - E));
}

}  // namespace

HertzApproach hertzFromApproach(double A, double B, double d, double Estar) {
  const double lo = std::min(A, B), hi = std::max(A, B);
  const double target = std::log(hi / lo);
  double m = 0.0;
  if (target > 1e-12) {
    // Illinois false position in t = -ln(1 - m) on [0, 30] (the ratio grows without bound).
    double t0 = 0.0, t1 = 30.0, f0 = -target, f1 = logRatio(t1) - target;
    int side = 0;
    double t = t1;
    for (int it = 0; it < 100; ++it) {
      t = t1 - f1 * (t1 - t0) / (f1 - f0);
      const double f = logRatio(t) - target;
      if (std::abs(f) < 1e-13 || t1 - t0 < 1e-14) break;
      if (f > 0.0) {
        t1 = t;
        f1 = f;
        if (side == 1) f0 *= 0.5;
        side = 1;
      } else {
        t0 = t;
        f0 = f;
        if (side == -1) f1 *= 0.5;
        side = -1;
      }
    }
    m = -std::expm1(-t);
  }
  double KmE_m, K, E;
  ellipticParts(m, &KmE_m, &K, &E);
  const double major = std::sqrt(d * KmE_m / (lo * K));
  const double minor = major * std::sqrt(1.0 - m);
  HertzApproach h;
  h.a = A <= B ? major : minor;
  h.b = A <= B ? minor : major;
  h.p0 = d * Estar / (minor * K);
  h.fn = 2.0 * M_PI * h.a * h.b * h.p0 / 3.0;
  return h;
}

}  // namespace wheel_rail_contact
