#include "wheel_rail_contact/profiles/profile.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/profiles/profile_impl.hpp"

namespace wheel_rail_contact {

Profile::Profile() : impl_(std::make_unique<Impl>()) {}
Profile::~Profile() = default;
Profile::Profile(Profile&&) noexcept = default;
Profile& Profile::operator=(Profile&&) noexcept = default;
Profile::Profile(const Profile& o)
    : impl_(std::make_unique<Impl>(*o.impl_)),
      kind_(o.kind_),
      name_(o.name_),
      smoothing_length_(o.smoothing_length_),
      file_sign_y_(o.file_sign_y_),
      file_sign_z_(o.file_sign_z_),
      y_min_(o.y_min_),
      y_max_(o.y_max_),
      points_(o.points_) {}
Profile& Profile::operator=(const Profile& o) {
  if (this != &o) *this = Profile(o);
  return *this;
}

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Segments [a0, a1] and [b0, b1] share a point (touching counts).
bool segmentsMeet(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                  const Eigen::Vector2d& b1) {
  const double d1 = cross2(a1 - a0, b0 - a0), d2 = cross2(a1 - a0, b1 - a0);
  const double d3 = cross2(b1 - b0, a0 - b0), d4 = cross2(b1 - b0, a1 - b0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  auto onSegment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                      const Eigen::Vector2d& r) {
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return (d1 == 0 && onSegment(a0, a1, b0)) || (d2 == 0 && onSegment(a0, a1, b1)) ||
         (d3 == 0 && onSegment(b0, b1, a0)) || (d4 == 0 && onSegment(b0, b1, a1));
}

std::string millimetres(double metres) {
  std::ostringstream os;
  os.precision(6);
  os << metres * 1e3 << " mm";
  return os.str();
}

}  // namespace

Profile ProfileBuilder::build(std::vector<ProfileSourcePoint> pts, ProfileKind kind,
                              const std::string& name, double smoothing_length,
                              double min_point_distance, double max_point_distance,
                              double file_sign_y, double file_sign_z) {
  if (!(smoothing_length >= 0.0) || !std::isfinite(smoothing_length))
    throw std::invalid_argument("smoothing_length must be finite and >= 0 (m)");
  if (!(min_point_distance >= 0.0) || !std::isfinite(min_point_distance))
    throw std::invalid_argument("min_point_distance must be finite and >= 0 (m)");
  if (!(max_point_distance > min_point_distance))
    throw std::invalid_argument("max_point_distance must be larger than min_point_distance (m)");
  const int n = static_cast<int>(pts.size());
  for (const auto& q : pts)
    if (!q.p.allFinite()) refuse(name, q.line, "a coordinate is not a finite number");
  if (n < kMinProfilePoints)
    refuse(name, n > 0 ? pts.back().line : 0,
           std::to_string(n) + " points; a profile needs at least " +
               std::to_string(kMinProfilePoints));
  for (int i = 1; i < n; ++i) {
    const double d = (pts[i].p - pts[i - 1].p).norm();
    if (d < min_point_distance)
      refuse(name, pts[i].line,
             "point " + millimetres(d) + " from the one on line " +
                 std::to_string(pts[i - 1].line) + ": a duplicate (min_point_distance " +
                 millimetres(min_point_distance) + ")");
    if (d > max_point_distance)
      refuse(name, pts[i].line,
             "point " + millimetres(d) + " from the one on line " +
                 std::to_string(pts[i - 1].line) + ": a hole in the profile (max_point_distance " +
                 millimetres(max_point_distance) + ")");
  }
  for (int i = 1; i + 1 < n; ++i) {
    const Eigen::Vector2d a = pts[i].p - pts[i - 1].p, b = pts[i + 1].p - pts[i].p;
    if (a.dot(b) < 0.0)
      refuse(name, pts[i].line,
             "the profile turns back on itself at this point (more than 90 degrees between "
             "the segments to lines " +
                 std::to_string(pts[i - 1].line) + " and " + std::to_string(pts[i + 1].line) +
                 "): points out of order");
  }
  {  // No two segments other than neighbours meet: a sweep over the segments sorted by lowest y.
    std::vector<int> order(n - 1);
    for (int i = 0; i < n - 1; ++i) order[i] = i;
    auto lo = [&](int i) { return std::min(pts[i].p.x(), pts[i + 1].p.x()); };
    auto hi = [&](int i) { return std::max(pts[i].p.x(), pts[i + 1].p.x()); };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return lo(a) < lo(b); });
    for (int a = 0; a < n - 1; ++a) {
      const int i = order[a];
      for (int b = a + 1; b < n - 1 && lo(order[b]) <= hi(i); ++b) {
        const int j = order[b];
        if (std::abs(i - j) <= 1) continue;
        if (segmentsMeet(pts[i].p, pts[i + 1].p, pts[j].p, pts[j + 1].p))
          refuse(name, pts[std::max(i, j)].line,
                 "the profile crosses itself between this line and line " +
                     std::to_string(pts[std::min(i, j) + 1].line) + " (a loop)");
      }
    }
  }
  if (pts.back().p.x() == pts.front().p.x())
    refuse(name, pts.back().line, "the profile ends where it starts laterally");
  // Order toward the track centre, so that the outward normal is a fixed turn of the tangent.
  if (pts.back().p.x() < pts.front().p.x()) std::reverse(pts.begin(), pts.end());

  std::vector<double> t(n), w(n);
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) {
    p[i] = pts[i].p;
    t[i] = i == 0 ? 0.0 : t[i - 1] + (p[i] - p[i - 1]).norm();
  }
  for (int i = 0; i < n; ++i) {  // the arc length each point stands for, times its own weight
    const double left = i > 0 ? t[i] - t[i - 1] : 0.0, right = i + 1 < n ? t[i + 1] - t[i] : 0.0;
    w[i] = 0.5 * (left + right) * pts[i].weight;
  }
  const double L2 = smoothing_length * smoothing_length;

  Profile prof;
  prof.impl_->spline = SmoothingSpline2d(t, p, w, L2 * L2);
  prof.kind_ = kind;
  prof.name_ = name;
  prof.smoothing_length_ = smoothing_length;
  prof.file_sign_y_ = file_sign_y;
  prof.file_sign_z_ = file_sign_z;
  prof.points_ = std::move(p);

  // Monotone pieces of y(s): split every interval at the roots of y'(s).
  const SmoothingSpline2d& sp = prof.impl_->spline;
  Profile::Impl& im = *prof.impl_;
  im.piece_t.push_back(sp.tBegin());
  for (int k = 0; k < sp.intervals(); ++k) {
    const double h = sp.knot(k + 1) - sp.knot(k);
    const double b = sp.coefficient(k, 1).x(), c = sp.coefficient(k, 2).x(),
                 d = sp.coefficient(k, 3).x();
    // y' = b + 2 c u + 3 d u^2
    std::vector<double> roots;
    const double qa = 3.0 * d, qb = 2.0 * c, qc = b;
    if (std::abs(qa) < 1e-300) {
      if (qb != 0.0) roots.push_back(-qc / qb);
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc > 0.0) {
        const double sq = std::sqrt(disc);
        const double q = -0.5 * (qb + (qb >= 0 ? sq : -sq));
        roots.push_back(q / qa);
        if (q != 0.0) roots.push_back(qc / q);
      }
    }
    std::sort(roots.begin(), roots.end());
    for (double u : roots)
      if (u > 0.0 && u < h) im.piece_t.push_back(sp.knot(k) + u);
  }
  im.piece_t.push_back(sp.tEnd());
  prof.y_min_ = 1e300;
  prof.y_max_ = -1e300;
  for (double tt : im.piece_t) {
    const double y = sp(tt).f.x();
    im.piece_y.push_back(y);
    prof.y_min_ = std::min(prof.y_min_, y);
    prof.y_max_ = std::max(prof.y_max_, y);
  }
  return prof;
}

Profile Profile::fromPoints(const std::vector<Eigen::Vector2d>& points, ProfileKind kind,
                            const std::string& name, double smoothing_length) {
  std::vector<ProfileSourcePoint> pts(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    pts[i].p = points[i];
    pts[i].line = static_cast<int>(i) + 1;
  }
  const ProfileReadOptions defaults;
  return ProfileBuilder::build(std::move(pts), kind, name, smoothing_length,
                               defaults.min_point_distance, defaults.max_point_distance, 1.0, 1.0);
}

double Profile::length() const {
  return impl_->spline.tEnd();
}

Profile::Point Profile::at(double s) const {
  const SmoothingSpline2d& sp = impl_->spline;
  s = std::clamp(s, sp.tBegin(), sp.tEnd());
  const SmoothingSpline2d::Value v = sp(s);
  Point pt;
  pt.position = v.f;
  const double speed = v.df.norm();
  pt.tangent = v.df / speed;
  // Increasing s runs toward the track centre (+y_p): a rail's material lies to the tangent's
  // right, a wheel's to its left.
  const Eigen::Vector2d left(-pt.tangent.y(), pt.tangent.x());
  pt.normal = kind_ == ProfileKind::kRail ? left : Eigen::Vector2d(-left);
  const double kappa_ccw = cross2(v.df, v.d2f) / (speed * speed * speed);
  pt.curvature = kind_ == ProfileKind::kRail ? -kappa_ccw : kappa_ccw;
  return pt;
}

std::vector<double> Profile::crossings(double y) const {
  std::vector<double> out;
  const SmoothingSpline2d& sp = impl_->spline;
  const std::vector<double>& pt = impl_->piece_t;
  const std::vector<double>& py = impl_->piece_y;
  for (std::size_t k = 0; k + 1 < pt.size(); ++k) {
    double ya = py[k] - y, yb = py[k + 1] - y;
    if ((ya > 0 && yb > 0) || (ya < 0 && yb < 0)) continue;
    if (ya == 0.0) {
      if (out.empty() || out.back() != pt[k]) out.push_back(pt[k]);
      continue;
    }
    if (yb == 0.0) {
      out.push_back(pt[k + 1]);
      continue;
    }
    // Safeguarded Newton on the monotone piece [a, b]: a Newton step is taken only if it stays
    // inside the bracket and is less than half the step before it, else the bracket is halved.
    // Newton alone can bounce between the two ends of a piece whose slope dy/ds is small at
    // one end (a rail's gauge face turning vertical) and large at the other, shrinking the
    // bracket by next to nothing, and stop far from the crossing.
    double a = pt[k], b = pt[k + 1];
    double t = a + (b - a) * ya / (ya - yb);
    double step_before = b - a;
    for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
      const SmoothingSpline2d::Value v = sp(t);
      const double f = v.f.x() - y;
      if (std::abs(f) < 1e-14) break;
      if ((f > 0) == (ya > 0)) {
        a = t;
        ya = f;
      } else {
        b = t;
      }
      double tn = v.df.x() != 0.0 ? t - f / v.df.x() : 0.5 * (a + b);
      if (!(tn > a && tn < b) || !(2.0 * std::abs(tn - t) < step_before)) tn = 0.5 * (a + b);
      step_before = std::abs(tn - t);
      t = tn;
      if (step_before < 1e-15) break;
    }
    out.push_back(t);
  }
  return out;
}

bool Profile::surfaceAt(double y, double* z, double* s) const {
  const std::vector<double> c = crossings(y);
  if (c.empty()) return false;
  const bool rail = kind_ == ProfileKind::kRail;
  double best_z = rail ? -1e300 : 1e300, best_s = 0.0;
  for (double t : c) {
    const double zt = impl_->spline(t).f.y();
    if (rail ? zt > best_z : zt < best_z) {
      best_z = zt;
      best_s = t;
    }
  }
  if (z) *z = best_z;
  if (s) *s = best_s;
  return true;
}

Eigen::Vector2d Profile::toFile(const Eigen::Vector2d& p) const {
  return {file_sign_y_ * p.x(), file_sign_z_ * p.y()};
}
Eigen::Vector2d Profile::fromFile(const Eigen::Vector2d& q) const {
  return {file_sign_y_ * q.x(), file_sign_z_ * q.y()};
}

}  // namespace wheel_rail_contact
