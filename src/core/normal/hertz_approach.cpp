#include "core/normal/hertz_approach.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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

/// t = -ln(1 - e^2) whose curvature ratio is exp(target), by Illinois false position on [0, 30].
double solveT(double target) {
  double t0 = 0.0, t1 = 30.0, f0 = -target, f1 = logRatio(t1) - target;
  int side = 0;
  double t = t1;
  for (int it = 0; it < 200; ++it) {
    t = t1 - f1 * (t1 - t0) / (f1 - f0);
    const double f = logRatio(t) - target;
    if (std::abs(f) < 1e-14 || t1 - t0 < 1e-15) break;
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
  return t;
}

/// t over u = ln(hi/lo) in [0, kUmax], tabulated once (Catmull-Rom): a start within some 1e-7
/// of the root, which two Newton steps make exact to rounding.
class TTable {
 public:
  static constexpr double kUmax = 25.0, kDu = 0.025;
  TTable() {
    const int n = static_cast<int>(std::lround(kUmax / kDu)) + 3;
    v_.resize(n);
    for (int i = 0; i < n; ++i) v_[i] = i == 1 ? 0.0 : solveT(std::abs((i - 1) * kDu));
    v_[0] = -v_[2];  // t is odd in u about 0 to first order
  }
  /// t(u) and dt/du.
  double operator()(double u, double* slope) const {
    const double s = u / kDu;
    const int i = static_cast<int>(s);
    const double x = s - i;
    const double p0 = v_[i], p1 = v_[i + 1], p2 = v_[i + 2], p3 = v_[i + 3];
    const double c1 = 0.5 * (p2 - p0), c2 = p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3,
                 c3 = 0.5 * (p3 - p0) + 1.5 * (p1 - p2);
    *slope = (c1 + x * (2.0 * c2 + 3.0 * x * c3)) / kDu;
    return p1 + x * (c1 + x * (c2 + x * c3));
  }

 private:
  std::vector<double> v_;  // node i at u = (i - 1) kDu
};

}  // namespace

HertzApproach hertzFromApproach(double A, double B, double d, double Estar) {
  const double lo = std::min(A, B), hi = std::max(A, B);
  const double target = std::log(hi / lo);
  double m = 0.0;
  if (target > 1e-12) {
    double t, slope;
    if (target < TTable::kUmax) {
      static const TTable table;
      t = table(target, &slope);
      for (int it = 0; it < 2 && slope > 0.0; ++it) t -= (logRatio(t) - target) * slope;
    } else {
      t = solveT(target);
    }
    m = -std::expm1(-std::clamp(t, 0.0, 30.0));  // m in [0, 1) whatever the iteration did
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
