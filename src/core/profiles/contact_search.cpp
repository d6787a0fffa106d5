#include "wheel_rail_contact/profiles/contact_search.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/profiles/placement.hpp"

namespace wheel_rail_contact {

/// One wheel and its rail, placed: the rail's profile frame (turned by the inclination) maps to
/// the track by y_T = sigma y + rail_offset, z_T = z - rail_top; the wheel's to the wheelset's
/// axle coordinate by y_W = sigma (y - flange_back) - sigma flange_back_distance / 2, its radius
/// being nominal_radius - z. sigma = +1 on the right (the profile's y is the track's y), -1 on
/// the left (mirrored).
struct ContactSearch::Side {
  double sigma = 1.0;
  std::shared_ptr<const Profile> wheel, rail_file, rail;
  double rail_angle = 0.0;
  double rail_offset = 0.0, rail_top = 0.0;
  double flange_back = 0.0;
  Eigen::Vector2d top = Eigen::Vector2d::Zero(), gauge = Eigen::Vector2d::Zero();

  Eigen::Vector2d railToTrack(const Eigen::Vector2d& p) const {
    return {sigma * p.x() + rail_offset, p.y() - rail_top};
  }
  Eigen::Vector2d railDirToTrack(const Eigen::Vector2d& v) const { return {sigma * v.x(), v.y()}; }
  double trackToRailY(double y) const { return sigma * (y - rail_offset); }
};

namespace {

/// The wheelset's pose as a rotation and the centre of the axle, track axes.
struct Frame {
  Eigen::Matrix3d R;
  Eigen::Vector3d centre;
};

/// The point of one wheel circle (profile parameter s) whose normal lies in the track's y-z plane.
struct LocusPoint {
  bool ok = false;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< track axes
  Eigen::Vector2d n = Eigen::Vector2d::Zero();  ///< outward normal of the wheel, (y, z)
  double radius = 0.0;
  double axial = 0.0;  ///< the circle's position along the axle from the wheelset's centre
};

double goldenMin(const std::function<double(double)>& f, double a, double b, double tol) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int it = 0; it < 200 && b - a > tol; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

const char* sideName(WheelSide s) {
  return s == WheelSide::kLeft ? "left" : "right";
}

}  // namespace

ContactSearch::ContactSearch(const WheelsetTrackData& data, const ContactSearchOptions& options)
    : data_(data), options_(options) {
  data_.validate();
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("ContactSearchOptions: ") + name +
                                  " must be finite and > 0");
  };
  positive("sample_spacing", options_.sample_spacing);
  positive("min_ridge", options_.min_ridge);
  positive("candidate_window", options_.candidate_window);
  positive("gap_window", options_.gap_window);
  positive("gap_reach", options_.gap_reach);
  positive("max_gap_extent", options_.max_gap_extent);
  positive("max_abs_y", options_.max_abs_y);
  positive("max_abs_z", options_.max_abs_z);
  positive("max_abs_yaw", options_.max_abs_yaw);
  positive("max_abs_roll", options_.max_abs_roll);
  if (options_.sample_spacing > 1e-3)
    throw std::invalid_argument("ContactSearchOptions: sample_spacing must be <= 1 mm");
  if (options_.gap_samples < 3 || options_.gap_samples > 10000)
    throw std::invalid_argument("ContactSearchOptions: gap_samples must be in [3, 10000]");
  if (!(options_.tread_max_angle < options_.flange_min_angle) ||
      !std::isfinite(options_.tread_max_angle) || !std::isfinite(options_.flange_min_angle))
    throw std::invalid_argument(
        "ContactSearchOptions: tread_max_angle must be below flange_min_angle");
  if (options_.max_abs_yaw > 0.5 || options_.max_abs_roll > 0.5)
    throw std::invalid_argument(
        "ContactSearchOptions: max_abs_yaw and max_abs_roll must be <= 0.5 rad");

  if (!data_.wheel_right) data_.wheel_right = Profile::standardWheel();
  if (!data_.rail_right) data_.rail_right = Profile::standardRail();
  sides_.resize(2);
  for (int k = 0; k < 2; ++k) {
    Side& s = sides_[k];
    const bool left = k == 0;
    s.sigma = left ? -1.0 : 1.0;
    s.wheel = left && data_.wheel_left ? data_.wheel_left : data_.wheel_right;
    s.rail_file = left && data_.rail_left ? data_.rail_left : data_.rail_right;
    s.rail_angle = -std::atan(data_.rail_inclination);  // the top tilts toward the centre, +y_p
    s.rail = s.rail_angle == 0.0
                 ? s.rail_file
                 : std::make_shared<const Profile>(rotatedProfile(*s.rail_file, s.rail_angle));
    const ProfileExtreme top = profileExtreme(*s.rail);
    Eigen::Vector2d g;
    gaugeSideCrossing(*s.rail, top.position.y() - data_.gauge_depth, &g);  // validate() saw it
    s.rail_top = top.position.y();
    // The gauge point goes to y_T = -sigma gauge / 2.
    s.rail_offset = -s.sigma * 0.5 * data_.gauge - s.sigma * g.x();
    s.top = s.railToTrack(top.position);
    s.gauge = s.railToTrack(g);
    s.flange_back = s.wheel->fromFile(Eigen::Vector2d(data_.flange_back_position, 0.0)).x();
  }
}

ContactSearch::ContactSearch(const ContactSearch&) = default;
ContactSearch& ContactSearch::operator=(const ContactSearch&) = default;
ContactSearch::~ContactSearch() = default;

Eigen::Vector2d ContactSearch::railTop(WheelSide side) const {
  return sides_[side == WheelSide::kLeft ? 0 : 1].top;
}
Eigen::Vector2d ContactSearch::gaugePoint(WheelSide side) const {
  return sides_[side == WheelSide::kLeft ? 0 : 1].gauge;
}

WheelContactGeometry ContactSearch::search(WheelSide wheel_side, const WheelsetPose& pose) const {
  WheelContactGeometry out;
  {
    std::ostringstream msg;
    auto check = [&](const char* name, double v, double limit) {
      if (!std::isfinite(v) || std::abs(v) > limit) {
        if (msg.tellp() > 0) msg << "; ";
        msg << "pose " << name << " = " << v << " is not finite or beyond +-" << limit;
      }
    };
    check("y", pose.y, options_.max_abs_y);
    check("z", pose.z, options_.max_abs_z);
    check("yaw", pose.yaw, options_.max_abs_yaw);
    check("roll", pose.roll, options_.max_abs_roll);
    if (msg.tellp() > 0) {
      out.status = ContactSearchStatus::kInvalidInput;
      out.message = msg.str();
      return out;
    }
  }
  const Side& side = sides_[wheel_side == WheelSide::kLeft ? 0 : 1];
  const double sigma = side.sigma;
  const Profile& wheel = *side.wheel;
  const Profile& rail = *side.rail;

  Frame fr;
  fr.R = (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
             .toRotationMatrix();
  fr.centre = Eigen::Vector3d(0.0, pose.y, data_.nominal_radius + pose.z);

  auto locus = [&](double s) {
    LocusPoint lp;
    const Profile::Point w = wheel.at(s);
    const double r = data_.nominal_radius - w.position.y();
    const double yw =
        sigma * (w.position.x() - side.flange_back) - sigma * 0.5 * data_.flange_back_distance;
    const double ny = w.normal.x(), nz = w.normal.y();
    if (!(r > 0.0) || !(nz < 0.0)) return lp;
    // The wheel's normal at angle theta from the bottom of its circle (theta toward +x of the
    // wheelset): n_W = sigma ny e_y - nz u(theta), u = (sin theta, 0, -cos theta) the outward
    // radius. Its x-component in the track vanishes where a sin(theta) + b cos(theta) = c.
    const Eigen::Matrix3d& R = fr.R;
    const double a = -nz * R(0, 0), b = nz * R(0, 2), c = -sigma * ny * R(0, 1);
    const double rho = std::hypot(a, b);
    if (!(rho > 0.0) || std::abs(c) > rho) return lp;
    const double theta = std::asin(c / rho) - std::atan2(b, a);
    const double st = std::sin(theta), ct = std::cos(theta);
    const Eigen::Vector3d pw(r * st, yw, -r * ct);
    const Eigen::Vector3d nw(-nz * st, sigma * ny, nz * ct);
    lp.p = fr.centre + R * pw;
    const Eigen::Vector3d nt = R * nw;
    if (!(nt.z() < 0.0)) return lp;
    lp.n = Eigen::Vector2d(nt.y(), nt.z()).normalized();
    lp.radius = r;
    lp.axial = yw;
    lp.ok = true;
    return lp;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto railZ = [&](double y, double* s_rail) {
    double z = 0.0, s = 0.0;
    if (!rail.surfaceAt(side.trackToRailY(y), &z, &s)) return nan;
    if (s_rail) *s_rail = s;
    return z - side.rail_top;
  };
  auto verticalGap = [&](double s) {
    const LocusPoint lp = locus(s);
    if (!lp.ok) return nan;
    const double zr = railZ(lp.p.y(), nullptr);
    return std::isnan(zr) ? nan : lp.p.z() - zr;
  };

  // ---- sample the vertical gap over the wheel's circles ----
  const int n = std::max(2, static_cast<int>(std::ceil(wheel.length() / options_.sample_spacing)));
  const double ds = wheel.length() / n;
  std::vector<double> g(n + 1);
  for (int i = 0; i <= n; ++i) g[i] = verticalGap(i * ds);
  std::vector<int> minima;
  double gmin = std::numeric_limits<double>::infinity();
  int imin = -1;
  for (int i = 0; i <= n; ++i) {
    if (std::isnan(g[i])) continue;
    if (g[i] < gmin) {
      gmin = g[i];
      imin = i;
    }
    const bool left_ok = i > 0 && !std::isnan(g[i - 1]);
    const bool right_ok = i < n && !std::isnan(g[i + 1]);
    if (left_ok && right_ok && g[i] <= g[i - 1] && g[i] < g[i + 1]) minima.push_back(i);
  }
  if (imin < 0) {
    out.status = ContactSearchStatus::kOutOfRange;
    out.message = std::string("the ") + sideName(wheel_side) + " wheel is not above its rail";
    return out;
  }
  if (std::find(minima.begin(), minima.end(), imin) == minima.end()) {
    out.status = ContactSearchStatus::kOutOfRange;
    out.message = std::string("the ") + sideName(wheel_side) +
                  " wheel's smallest gap is at the end of a profile: the wheelset is beyond "
                  "the profiles' reach";
    return out;
  }
  // The ridge between neighbouring minima: the highest sample between them (infinite across a
  // stretch without gap, where the wheel is not above the rail).
  auto ridge = [&](int i, int j, int* at) {
    double r = -std::numeric_limits<double>::infinity();
    for (int k = i + 1; k < j; ++k) {
      if (std::isnan(g[k])) {
        *at = k;
        return std::numeric_limits<double>::infinity();
      }
      if (g[k] > r) {
        r = g[k];
        *at = k;
      }
    }
    return r;
  };
  for (bool merged = true; merged && minima.size() > 1;) {
    merged = false;
    double worst = options_.min_ridge;
    std::size_t pick = 0;
    for (std::size_t k = 0; k + 1 < minima.size(); ++k) {
      int at = 0;
      const double excess =
          ridge(minima[k], minima[k + 1], &at) - std::max(g[minima[k]], g[minima[k + 1]]);
      if (excess < worst) {
        worst = excess;
        pick = k;
        merged = true;
      }
    }
    if (merged) {  // keep the lower of the two
      if (g[minima[pick]] <= g[minima[pick + 1]])
        minima.erase(minima.begin() + pick + 1);
      else
        minima.erase(minima.begin() + pick);
    }
  }

  // ---- each minimum: refine, then its contact frame and gap function ----
  for (std::size_t k = 0; k < minima.size(); ++k) {
    const int i = minima[k];
    if (g[i] > gmin + options_.candidate_window) continue;
    int lo_at = 0, hi_at = n;
    if (k > 0) ridge(minima[k - 1], i, &lo_at);
    if (k + 1 < minima.size()) ridge(i, minima[k + 1], &hi_at);
    const double s_lo = lo_at * ds, s_hi = hi_at * ds;

    const double sw = goldenMin(
        [&](double s) {
          const double v = verticalGap(s);
          return std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
        },
        (i - 1) * ds, (i + 1) * ds, 1e-12);
    const LocusPoint lp = locus(sw);
    double sr = 0.0;
    const double zr = railZ(lp.p.y(), &sr);
    if (!lp.ok || std::isnan(zr)) continue;

    ContactCandidate c;
    c.s_wheel = sw;
    c.s_rail = sr;
    c.vertical_gap = lp.p.z() - zr;
    c.rolling_radius = lp.radius;
    const Profile::Point rp = rail.at(sr);
    c.normal = side.railDirToTrack(rp.normal).normalized();
    c.point = Eigen::Vector3d(lp.p.x(), lp.p.y(), zr);
    c.lead = lp.p.x() - (fr.centre + fr.R * Eigen::Vector3d(0.0, lp.axial, 0.0)).x();
    c.contact_angle = std::atan2(sigma * c.normal.x(), c.normal.y());
    c.zone = c.contact_angle < options_.tread_max_angle     ? ContactZone::kTread
             : c.contact_angle >= options_.flange_min_angle ? ContactZone::kFlange
                                                            : ContactZone::kGaugeCorner;
    {  // file coordinates: undo the inclination's turn on the rail
      const double ca = std::cos(-side.rail_angle), sa = std::sin(-side.rail_angle);
      const Eigen::Vector2d q = rp.position;
      c.rail_file =
          side.rail_file->toFile(Eigen::Vector2d(ca * q.x() - sa * q.y(), sa * q.x() + ca * q.y()));
      c.wheel_file = wheel.toFile(wheel.at(sw).position);
    }

    // Gap along the normal at lateral coordinate eta of the contact plane (origin o, normal nn,
    // lateral t toward the track centre). Each curve is followed from the contact by Newton steps
    // in its own parameter; false where a curve turns away from the plane or leaves its range.
    const Eigen::Vector2d o(c.point.y(), c.point.z()), nn = c.normal;
    const Eigen::Vector2d t = sigma * Eigen::Vector2d(nn.y(), -nn.x());
    auto wheelYZ = [&](double s, Eigen::Vector2d* q) {
      const LocusPoint l = locus(s);
      if (!l.ok) return false;
      *q = Eigen::Vector2d(l.p.y(), l.p.z());
      return true;
    };
    auto railYZ = [&](double s, Eigen::Vector2d* q) {
      if (s < 0.0 || s > rail.length()) return false;
      *q = side.railToTrack(rail.at(s).position);
      return true;
    };
    auto follow = [&](const auto& curve, double eta, double lo, double hi, double* s,
                      double* lambda) {
      double x = *s;
      for (int it = 0; it < 50; ++it) {
        const double h = 1e-7;
        Eigen::Vector2d q, qm, qp;
        if (x < lo || x > hi || !curve(x, &q) || !curve(x - h, &qm) || !curve(x + h, &qp))
          return false;
        const double f = (q - o).dot(t) - eta;
        const double df = (qp - qm).dot(t) / (2 * h);
        if (!(df > 0.05)) return false;  // the curve turns away from the contact plane
        if (std::abs(f) < 1e-13) {
          *s = x;
          *lambda = (q - o).dot(nn);
          return true;
        }
        x -= f / df;
      }
      return false;
    };
    double sw0 = sw, sr0 = sr;
    auto gapAt = [&](double eta, double* gap_out, GapSample* sample = nullptr) {
      double lw = 0.0, lr = 0.0;
      double a = sw0, b = sr0;
      if (!follow(wheelYZ, eta, s_lo, s_hi, &a, &lw)) return false;
      if (!follow(railYZ, eta, 0.0, rail.length(), &b, &lr)) return false;
      sw0 = a;
      sr0 = b;
      *gap_out = lw - lr;
      if (sample) {
        const LocusPoint l = locus(a);  // ok: follow() evaluated it
        sample->rolling_radius = l.radius;
        sample->contact_angle = std::atan2(-sigma * l.n.x(), -l.n.y());
      }
      return true;
    };
    double g0 = 0.0;
    if (!gapAt(0.0, &g0)) {  // no gap function: the normal gap to first order
      c.gap = c.vertical_gap * std::cos(c.contact_angle);
      out.candidates.push_back(std::move(c));
      continue;
    }
    c.gap = g0;
    const double level =
        g0 + std::max(2.0 * std::max(std::abs(g0), options_.gap_window), options_.gap_reach);
    double edge[2] = {0.0, 0.0};
    // March out to the level in steps growing from 0.1 mm by half each (a few dozen steps reach
    // max_gap_extent), then bisect to where the gap reaches the level or the curves stop.
    for (int dir = 0; dir < 2; ++dir) {
      const double sign = dir == 0 ? -1.0 : 1.0;
      sw0 = sw;
      sr0 = sr;
      double inside = 0.0, outside = 0.0, reach = 0.0;
      bool stopped = false;
      for (double step = 1e-4; reach < options_.max_gap_extent; step *= 1.5) {
        reach = std::min(reach + step, options_.max_gap_extent);
        double gv = 0.0;
        outside = sign * reach;
        if (!gapAt(outside, &gv) || gv >= level) {
          stopped = true;
          break;
        }
        inside = outside;
      }
      if (stopped) {
        for (int it = 0; it < 32; ++it) {
          const double mid = 0.5 * (inside + outside);
          double gv = 0.0;
          if (gapAt(mid, &gv) && gv < level)
            inside = mid;
          else
            outside = mid;
        }
      }
      edge[dir] = inside;
    }
    const int m = options_.gap_samples;
    sw0 = sw;
    sr0 = sr;
    // From the contact outward in each direction, so that every Newton start is close.
    std::vector<GapSample> samples(m);
    const double de = (edge[1] - edge[0]) / (m - 1);
    int first_right = 0;
    while (first_right < m && edge[0] + first_right * de < 0.0) ++first_right;
    bool ok = true;
    for (int j = first_right; j < m && ok; ++j) {
      samples[j].eta = edge[0] + j * de;
      ok = gapAt(samples[j].eta, &samples[j].gap, &samples[j]);
    }
    sw0 = sw;
    sr0 = sr;
    for (int j = first_right - 1; j >= 0 && ok; --j) {
      samples[j].eta = edge[0] + j * de;
      ok = gapAt(samples[j].eta, &samples[j].gap, &samples[j]);
    }
    if (ok) c.gap_function = std::move(samples);
    out.candidates.push_back(std::move(c));
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < out.candidates.size(); ++k)
    if (out.candidates[k].vertical_gap < best) {
      best = out.candidates[k].vertical_gap;
      out.closest = static_cast<int>(k);
    }
  if (out.candidates.empty()) {
    out.status = ContactSearchStatus::kOutOfRange;
    out.message = std::string("no contact candidate on the ") + sideName(wheel_side) + " wheel";
  }
  return out;
}

}  // namespace wheel_rail_contact
