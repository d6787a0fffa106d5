/// The closed-loop demo's wheelset on real profiles: the wheelset of wheelset_model.hpp (lateral
/// displacement y and yaw psi, tied by its primary suspension to a bogie frame that runs straight
/// at constant speed V) whose wheels run on S1002 on UIC60 1:40 (or any profiles of the track
/// data) through WheelsetContact: each step the wheelset's pose and motion relative to the track
/// go in, each wheel's patches and their forces come out, and their sum in the track frame drives
/// the lateral and yaw equations. ROS-free. Equations and parameters: doc/wheelset_demo.md.
///
/// What the profiles give and how the wheelset follows them:
///  - roll and rise: a rigid wheelset on rigid profiles touches both rails; the roll that makes
///    both wheels touch at the same height, and that height, are tabulated once against the
///    lateral displacement (RigidKinematics) and given to WheelsetContact with their rates (roll
///    rate and vertical velocity from the lateral velocity through the table's slopes);
///  - pitch rate: the wheelset rolls at V over the mean of its two rolling radii at its lateral
///    displacement (its pitch mode, with a time constant of about a millisecond, taken as settled);
///  - loads: each wheel's vertical load is the static wheel load (no load transfer);
///  - forces: each wheel's wrench in the track frame (WheelResult::wrench: its patches' normal and
///    tangential forces); the lateral force (creep forces and the normal forces' lateral
///    components: gravitational stiffness, flange force) and the yaw moment about the wheelset's
///    centre drive the two equations of motion;
///  - inputs: a lateral force on the wheelset (an impact) and an optional lateral alignment y_t(x)
///    of the track, which the contact sees as a track whose frame yaws by y_t' and turns at
///    V y_t'' (both rails follow it).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/profiles/contact_search.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"
#include "wheelset_model.hpp"

namespace wheel_rail_contact {
namespace demo {

/// The rigid wheelset's kinematics on its rails at zero yaw, against its lateral displacement y
/// (REP 103, y to the left): the roll at which both wheels touch their rails together, the height
/// of its centre then (the vertical gap closed), each wheel's rolling radius and the lateral
/// position of its closest contact point. Rigid profiles, as the equivalent conicity's standard
/// definition takes them (EN 15302).
class RigidKinematics {
 public:
  struct Sample {
    double y = 0.0;
    double roll = 0.0;                     ///< [rad], positive raises the left wheel
    double z = 0.0;                        ///< rise of the wheelset's centre [m]
    double r_left = 0.0, r_right = 0.0;    ///< rolling radii at the closest contact points [m]
    double yc_left = 0.0, yc_right = 0.0;  ///< lateral positions of those points, track axes [m]
  };

  /// Tabulates y over [-max_abs_y, max_abs_y] every step with the direct contact search. Throws
  /// std::invalid_argument naming the argument, or std::runtime_error if a pose has no contact.
  RigidKinematics(const WheelsetTrackData& data, double max_abs_y = 0.012, double step = 5e-5) {
    if (!(max_abs_y > 0.0 && max_abs_y <= 0.04))
      throw std::invalid_argument("max_abs_y: must be in (0, 0.04] m");
    if (!(step > 0.0 && step <= max_abs_y / 4.0))
      throw std::invalid_argument("step: must be in (0, max_abs_y / 4]");
    ContactSearch search(data);
    const int n = static_cast<int>(std::lround(max_abs_y / step));
    step_ = max_abs_y / n;
    y0_ = -max_abs_y;
    for (int i = -n; i <= n; ++i) samples_.push_back(solve(search, i * step_));
  }

  /// Linear interpolation at y; false beyond the table (sample untouched).
  bool at(double y, Sample* s, double* droll_dy = nullptr, double* dz_dy = nullptr) const {
    const double u = (y - y0_) / step_;
    if (!(u >= 0.0 && u <= static_cast<double>(samples_.size() - 1))) return false;
    const size_t i = std::min(static_cast<size_t>(u), samples_.size() - 2);
    const double w = u - static_cast<double>(i);
    const Sample &a = samples_[i], &b = samples_[i + 1];
    auto mix = [w](double p, double q) { return p + w * (q - p); };
    s->y = y;
    s->roll = mix(a.roll, b.roll);
    s->z = mix(a.z, b.z);
    s->r_left = mix(a.r_left, b.r_left);
    s->r_right = mix(a.r_right, b.r_right);
    s->yc_left = mix(a.yc_left, b.yc_left);
    s->yc_right = mix(a.yc_right, b.yc_right);
    if (droll_dy) *droll_dy = (b.roll - a.roll) / step_;
    if (dz_dy) *dz_dy = (b.z - a.z) / step_;
    return true;
  }
  double maxAbsY() const { return -y0_; }
  const std::vector<Sample>& samples() const { return samples_; }

  /// The rolling-radius difference Delta r(y) = r_left - r_right [m].
  double radiusDifference(double y) const {
    Sample s;
    return at(y, &s) ? s.r_left - s.r_right : std::nan("");
  }

  /// Equivalent conicity at amplitude A by harmonic linearisation of the rolling-radius difference
  /// (the first Fourier coefficient of Delta r over one cycle of y = A sin(tau), the describing
  /// function; EN 15302's Fourier method):
  ///   lambda_e(A) = 1 / (2 pi A) * integral_0^{2 pi} Delta r(A sin tau) sin tau dtau,
  /// which is lambda for a cone (Delta r = 2 lambda y). NaN beyond the table.
  double equivalentConicity(double amplitude) const {
    if (!(amplitude > 0.0 && amplitude <= maxAbsY())) return std::nan("");
    const int n = 720;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const double tau = 2.0 * M_PI * (k + 0.5) / n;
      sum += radiusDifference(amplitude * std::sin(tau)) * std::sin(tau);
    }
    return sum / n / amplitude;  // (1 / (2 pi A)) * sum * (2 pi / n)
  }
  /// Nominal rolling radius and half the distance between the contact points, centred [m].
  double r0() const { return 0.5 * (centre().r_left + centre().r_right); }
  double l0() const { return 0.5 * (centre().yc_left - centre().yc_right); }
  /// Klingel's kinematic wavelength 2 pi sqrt(r0 l0 / lambda_e(A)) [m].
  double klingelWavelength(double amplitude) const {
    return 2.0 * M_PI * std::sqrt(r0() * l0() / equivalentConicity(amplitude));
  }

 private:
  const Sample& centre() const { return samples_[samples_.size() / 2]; }

  static Sample solve(const ContactSearch& search, double y) {
    // Both wheels' closest vertical gaps equal: then lowering the wheelset by that gap makes both
    // touch. The gap difference changes by about the contact points' distance per radian of roll,
    // so Newton with a secant slope converges in a few steps.
    WheelsetPose pose;
    pose.y = y;
    auto gaps = [&](double roll, double* gl, double* gr, ContactCandidate* cl,
                    ContactCandidate* cr) {
      pose.roll = roll;
      const WheelContactGeometry l = search.search(WheelSide::kLeft, pose);
      const WheelContactGeometry r = search.search(WheelSide::kRight, pose);
      if (l.closest < 0 || r.closest < 0)
        throw std::runtime_error("RigidKinematics: no contact at y = " + std::to_string(y) +
                                 " m: " + l.message + r.message);
      *cl = l.candidates[static_cast<size_t>(l.closest)];
      *cr = r.candidates[static_cast<size_t>(r.closest)];
      *gl = cl->vertical_gap;
      *gr = cr->vertical_gap;
    };
    ContactCandidate cl, cr;
    double gl, gr, roll = 0.0;
    gaps(roll, &gl, &gr, &cl, &cr);
    double f = gl - gr, slope = 1.5;
    for (int it = 0; it < 50 && std::fabs(f) > 1e-10; ++it) {
      const double next = roll - f / slope;
      gaps(next, &gl, &gr, &cl, &cr);
      const double fn = gl - gr;
      if (std::fabs(next - roll) > 1e-12 && std::fabs(fn - f) > 1e-14)
        slope = std::clamp((fn - f) / (next - roll), 0.3, 5.0);
      roll = next;
      f = fn;
    }
    if (!(std::fabs(f) <= 1e-8))
      throw std::runtime_error(
          "RigidKinematics: no roll with both wheels touching at y = " + std::to_string(y) + " m");
    Sample s;
    s.y = y;
    s.roll = roll;
    s.z = -0.5 * (gl + gr);
    s.r_left = cl.rolling_radius;
    s.r_right = cr.rolling_radius;
    s.yc_left = cl.point.y();
    s.yc_right = cr.point.y();
    return s;
  }

  double y0_ = 0.0, step_ = 1.0;
  std::vector<Sample> samples_;
};

/// The wheelset's mechanical data (the profiles, gauge and contact data are the WheelsetContact's).
struct ProfileWheelsetParameters {
  double mass = 1800.0;           ///< wheelset mass [kg]
  double yawInertia = 1100.0;     ///< yaw moment of inertia [kg m^2]
  double lateralStiffness = 2e6;  ///< primary lateral stiffness, both sides [N/m]
  double yawStiffness = 2e6;      ///< primary yaw stiffness to the frame [N m/rad]
  double wheelLoad = 8e4;         ///< vertical load on each wheel [N]
};

/// Throws std::invalid_argument naming the first parameter out of its range.
inline void validate(const ProfileWheelsetParameters& p) {
  auto check = [](const char* name, double v, bool zero_ok) {
    if (!(std::isfinite(v) && (zero_ok ? v >= 0.0 : v > 0.0)))
      throw std::invalid_argument(
          std::string(name) + (zero_ok ? ": must be >= 0 and finite" : ": must be > 0 and finite"));
  };
  check("mass", p.mass, false);
  check("yaw_inertia", p.yawInertia, false);
  check("lateral_stiffness", p.lateralStiffness, true);
  check("yaw_stiffness", p.yawStiffness, true);
  check("wheel_load", p.wheelLoad, false);
}

/// A lateral force on the wheelset's centre, constant over [start, start + duration] (an impact,
/// a gust), 0 elsewhere [N, s].
struct LateralImpulse {
  double force = 0.0, start = 0.0, duration = 0.0;
  double at(double t) const {
    return (force != 0.0 && t >= start && t < start + duration) ? force : 0.0;
  }
};

/// One wheel's force from its rail in the track frame and its moment about the wheelset's centre
/// c: WheelResult::wrench (about the wheel's centre) moved to c.
struct WheelTotals {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

inline WheelTotals wheelTotals(const WheelResult& wheel, const Eigen::Vector3d& centre) {
  WheelTotals t;
  const TrackWrench& w = wheel.wrench;
  t.force = Eigen::Vector3d(w.fx, w.fy, w.fz);
  if (wheel.patches.empty()) return t;  // no patch: no wrench, and no centre either
  t.moment = Eigen::Vector3d(w.mx, w.my, w.mz) + (wheel.centre - centre).cross(t.force);
  return t;
}

/// One step's record.
struct ProfileStep {
  double t = 0.0;
  WheelsetState s;      ///< the state the step's forces were computed at
  double yTrack = 0.0;  ///< the track's lateral alignment there [m]
  double roll = 0.0, z = 0.0;
  double impulse = 0.0;       ///< external lateral force [N]
  double fy = 0.0, mz = 0.0;  ///< contact forces' lateral total and yaw moment, straight axes
  WheelTotals left, right;    ///< each wheel's totals in the track frame
  WheelsetResult contact;     ///< every patch
};

/// The wheelset in the loop: its state, the rigid kinematics, and a WheelsetContact.
class ProfileWheelset {
 public:
  ProfileWheelset(const ProfileWheelsetParameters& p, const WheelsetTrackData& track,
                  std::shared_ptr<const RigidKinematics> kinematics,
                  const ContactParameters& contact, const WheelsetContactOptions& options)
      : p_(p), track_(track), kin_(std::move(kinematics)), contact_(track, contact, options) {
    validate(p_);
    if (!kin_) throw std::invalid_argument("kinematics: required");
  }

  /// Starts a run: contact history cleared, state s.
  void reset(const WheelsetState& s) {
    contact_.reset();
    s_ = s;
    first_ = true;
  }

  /// One step of dt at speed V: the contact at the current state, then the state advanced with the
  /// forces held over dt (the suspension integrated exactly, as advanceWheelset). Returns false
  /// with *why set when the step cannot go on (beyond the kinematics' range, a wheel's status not
  /// ok, a non-finite force); the state is then not advanced.
  bool step(double V, double dt, const Irregularity& track, const LateralImpulse& impulse, double t,
            ProfileStep* out, std::string* why) {
    const double yt = track.lateral(s_.x), slope = track.slope(s_.x), curv = track.curvature(s_.x);
    const double yr = s_.y - yt, vyr = s_.vy - V * slope;
    RigidKinematics::Sample k;
    double droll = 0.0, dz = 0.0;
    if (!kin_->at(yr, &k, &droll, &dz)) {
      *why = "lateral displacement " + std::to_string(yr * 1e3) +
             " mm beyond the rigid kinematics' table (+-" + std::to_string(kin_->maxAbsY() * 1e3) +
             " mm)";
      return false;
    }
    wheel_rail_contact::WheelsetState cs;
    cs.pose.y = yr;
    cs.pose.yaw = s_.psi - slope;  // relative to the track's local direction
    cs.pose.roll = k.roll;
    cs.pose.z = k.z;
    cs.motion.V = V;
    cs.motion.omega = 2.0 * V / (k.r_left + k.r_right);
    cs.motion.vy = vyr;
    // The alignment y_t(x) is a track whose centre line turns: its frame at the wheelset is yawed
    // by y_t' and turns at V y_t'' (its curvature), relative to which yaw and yaw rate are taken.
    cs.motion.curvature = curv;
    cs.motion.yaw_rate = s_.vpsi - V * curv;
    cs.motion.roll_rate = droll * vyr;
    cs.motion.vz = dz * vyr;
    cs.fz_left = cs.fz_right = p_.wheelLoad;
    out->t = t;
    out->s = s_;
    out->yTrack = yt;
    out->roll = k.roll;
    out->z = k.z;
    out->contact = contact_.step(cs, first_ ? 0.0 : dt);
    first_ = false;
    for (const WheelResult* w : {&out->contact.left, &out->contact.right}) {
      if (w->status != WheelStatus::kOk) {
        *why = std::string(w->side == WheelSide::kLeft ? "left" : "right") +
               " wheel: " + toString(w->status) + " at y " + std::to_string(yr * 1e3) +
               " mm, yaw " + std::to_string(cs.pose.yaw * 1e3) + " mrad, roll " +
               std::to_string(cs.pose.roll * 1e3) + " mrad: " + w->message;
        return false;
      }
    }
    const Eigen::Vector3d centre(0.0, yr, track_.nominal_radius + k.z);
    out->left = wheelTotals(out->contact.left, centre);
    out->right = wheelTotals(out->contact.right, centre);
    // Track frame -> the frame's straight axes: turned by the alignment's slope about z.
    const double fxT = out->left.force.x() + out->right.force.x();
    const double fyT = out->left.force.y() + out->right.force.y();
    out->fy = fyT + slope * fxT;
    out->mz = out->left.moment.z() + out->right.moment.z();
    out->impulse = impulse.at(t);
    if (!(std::isfinite(out->fy) && std::isfinite(out->mz))) {
      *why = "non-finite contact force";
      return false;
    }
    detail::advanceOscillator(p_.mass, p_.lateralStiffness, out->fy + out->impulse, dt, &s_.y,
                              &s_.vy);
    detail::advanceOscillator(p_.yawInertia, p_.yawStiffness, out->mz, dt, &s_.psi, &s_.vpsi);
    s_.x += V * dt;
    return true;
  }

  const WheelsetState& state() const { return s_; }
  const RigidKinematics& kinematics() const { return *kin_; }
  const ProfileWheelsetParameters& parameters() const { return p_; }

 private:
  ProfileWheelsetParameters p_;
  WheelsetTrackData track_;
  std::shared_ptr<const RigidKinematics> kin_;
  WheelsetContact contact_;
  WheelsetState s_;
  bool first_ = true;
};

/// A sustained oscillation read from its extremes after t0: amplitude the mean of (peak - trough)
/// / 2 over successive pairs, frequency from the mean spacing of the positive peaks (parabolic
/// vertex per extreme).
struct CycleFit {
  bool ok = false;
  std::string why;
  size_t peaks = 0;
  double frequency = 0.0;  ///< [Hz]
  double amplitude = 0.0;  ///< [same unit as v]
};

inline CycleFit fitCycle(const std::vector<double>& t, const std::vector<double>& v, double t0) {
  CycleFit fit;
  std::vector<double> pt, pv, tv;
  for (size_t i = 1; i + 1 < v.size(); ++i) {
    if (t[i] < t0) continue;
    const bool peak = v[i] > v[i - 1] && v[i] >= v[i + 1];
    const bool trough = v[i] < v[i - 1] && v[i] <= v[i + 1];
    if (!peak && !trough) continue;
    const double h = t[i + 1] - t[i];
    const double den = v[i - 1] - 2.0 * v[i] + v[i + 1];
    const double off = den != 0.0 ? 0.5 * (v[i - 1] - v[i + 1]) / den : 0.0;
    const double value = v[i] - 0.25 * (v[i - 1] - v[i + 1]) * off;
    if (peak && value > 0.0) pt.push_back(t[i] + off * h), pv.push_back(value);
    if (trough && value < 0.0) tv.push_back(value);
  }
  fit.peaks = pt.size();
  if (pt.size() < 2 || tv.empty()) {
    fit.why = "fewer than 2 positive peaks and a trough after t0";
    return fit;
  }
  fit.frequency = static_cast<double>(pt.size() - 1) / (pt.back() - pt.front());
  double sp = 0.0, st = 0.0;
  for (double p : pv) sp += p;
  for (double q : tv) st += q;
  fit.amplitude = 0.5 * (sp / static_cast<double>(pv.size()) - st / static_cast<double>(tv.size()));
  fit.ok = std::isfinite(fit.frequency) && std::isfinite(fit.amplitude) && fit.frequency > 0.0;
  if (!fit.ok) fit.why = "non-finite fit";
  return fit;
}

}  // namespace demo
}  // namespace wheel_rail_contact
