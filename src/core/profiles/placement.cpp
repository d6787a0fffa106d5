#include "core/profiles/placement.hpp"

#include "core/profiles/profile_impl.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace wheel_rail_contact {

namespace {

/// Samples no more than 0.1 mm apart and at least 1000 of them.
int sampleCount(const Profile& p) {
  return std::max(1000, static_cast<int>(std::ceil(p.length() / 1.0e-4)));
}

}  // namespace

ProfileExtreme profileExtreme(const Profile& p) {
  const double sign = p.kind() == ProfileKind::kRail ? 1.0 : -1.0;  // maximise sign * z
  const int n = sampleCount(p);
  int best = 0;
  double best_v = -1e300;
  for (int i = 0; i <= n; ++i) {
    const double v = sign * p.at(p.length() * i / n).position.y();
    if (v > best_v) {
      best_v = v;
      best = i;
    }
  }
  ProfileExtreme e;
  e.at_end = best == 0 || best == n;
  // Golden-section refinement on the bracket of the best sample.
  double a = p.length() * std::max(0, best - 1) / n, b = p.length() * std::min(n, best + 1) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = sign * p.at(c).position.y(), fd = sign * p.at(d).position.y();
  for (int it = 0; it < 80 && b - a > 1e-12; ++it) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = sign * p.at(c).position.y();
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = sign * p.at(d).position.y();
    }
  }
  e.s = 0.5 * (a + b);
  e.position = p.at(e.s).position;
  return e;
}

bool gaugeSideCrossing(const Profile& p, double z_level, Eigen::Vector2d* point) {
  const int n = sampleCount(p);
  bool found = false;
  double best_y = -1e300;
  double prev_s = 0.0, prev_f = p.at(0.0).position.y() - z_level;
  for (int i = 1; i <= n; ++i) {
    const double s = p.length() * i / n;
    const double f = p.at(s).position.y() - z_level;
    if ((prev_f <= 0.0) != (f <= 0.0)) {
      double a = prev_s, b = s, fa = prev_f;
      for (int it = 0; it < 100 && b - a > 1e-13; ++it) {
        const double m = 0.5 * (a + b);
        const double fm = p.at(m).position.y() - z_level;
        if ((fm <= 0.0) == (fa <= 0.0)) {
          a = m;
          fa = fm;
        } else {
          b = m;
        }
      }
      const Eigen::Vector2d q = p.at(0.5 * (a + b)).position;
      if (q.x() > best_y) {
        best_y = q.x();
        *point = q;
        found = true;
      }
    }
    prev_s = s;
    prev_f = f;
  }
  return found;
}

Profile rotatedProfile(const Profile& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<ProfileSourcePoint> pts(p.points().size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d& q = p.points()[i];
    pts[i].p = Eigen::Vector2d(c * q.x() - s * q.y(), s * q.x() + c * q.y());
    pts[i].line = static_cast<int>(i) + 1;
  }
  // The points passed the profile's own checks: turning them changes no distance.
  return ProfileBuilder::build(std::move(pts), p.kind(), p.name(), p.smoothingLength(), 0.0, 1e300,
                               1.0, 1.0);
}

}  // namespace wheel_rail_contact
