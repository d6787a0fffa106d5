/// Creepages of one contact patch from the wheelset's motion: rigid-body kinematics of the wheel
/// (a body of revolution about its yawed and rolled axle) over the rail (fixed, a prism along the
/// track), on tangent track and in curves.
///
/// Frames (doc/conventions.md, "Wheelset and track frames"). The track frame: REP 103, x forward,
/// y left, z up, origin on the track's centre line in the plane of the rails' tops (turned by the
/// step's cant about x, WheelsetMotion::cant). It follows the centre line at the speed V and, in a
/// curve of curvature kappa, turns at V kappa about the vertical. In it the wheelset's centre sits
/// at (0, pose.y, nominal_radius + pose.z) and moves at (0, vy, vz); the rails move backwards: a
/// rail point p moves at -(V e_x + Omega x p), Omega = V kappa (0, sin(cant), cos(cant)), which is
/// -V (1 - kappa y_h) along x at a horizontal distance y_h from the centre line.
///
/// The patch's contact frame (doc/conventions.md): z = n, the candidate's normal (rail into wheel,
/// no x-component); x = the track's e_x, which lies in the contact plane; y = z x x =
/// (0, n_z, -n_y). The same orientation on both wheels, no mirroring.
///
/// With e_a the axle (the wheelset's y), c the wheelset's centre, omega_w = yaw_rate e_z +
/// roll_rate e_x' + omega e_a the wheelset's angular velocity relative to the track frame (e_x' the
/// yawed x), p the candidate's point on the rail, w = p + vertical_gap e_z the wheel's point above
/// it, q the wheel's material on its circle of rolling_radius through w (q = c + a e_a +
/// r (w - c - a e_a)/|w - c - a e_a|, a = (w - c).e_a):
///
///   dv  = (0, vy, vz) + omega_w x (q - c) + V e_x + Omega x p      (wheel minus rail)
///   xi  = dv.x / V,  eta = dv.y / V,  phi = (omega_w + Omega).n / V  [1/m]
///
/// To first order (tread, small yaw psi, roll theta, contact angle delta, wheel at +-l0 with
/// s = +1 left, -1 right): xi = 1 - omega r / V - s l0 (yaw_rate / V + kappa),
/// eta = vy / V + roll_rate r / V - psi, phi = yaw_rate / V + kappa + (omega / V)(theta - s delta);
/// on a centred, coned wheelset rolling at omega = V / r0 the spin is -sin(delta) / r0 on the left
/// wheel and +sin(delta) / r0 on the right (doc/method.md, "Creepages from the wheelset's motion").
#pragma once

#include <Eigen/Core>
#include <string>

#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

/// The wheelset's motion relative to the track frame (SI, REP 103 axes).
struct WheelsetMotion {
  /// Speed of the track frame along the track's centre line [m/s], signed (< 0 rolling
  /// backwards); the creepages are divided by it.
  double V = 0.0;
  /// Pitch rate about the axle (the wheelset's +y) [rad/s]; about V / r0 > 0 rolling forward.
  double omega = 0.0;
  double vy = 0.0;  ///< lateral velocity of the wheelset's centre, d(pose.y)/dt [m/s]
  double yaw_rate =
      0.0;  ///< d(pose.yaw)/dt [rad/s], relative to the track (which turns at V kappa)
  double curvature = 0.0;  ///< of the track's centre line [1/m], positive for a curve to the left
  /// The track's cant under the wheelset this step [rad]: the angle of the rails' plane about the
  /// track's x, REP 103 sense (positive raises the left rail), |cant| <= kMaxCant. The track
  /// frame's axes are those of the canted plane, and the contact geometry is relative to that
  /// plane, so the cant does not change it: it enters only the track frame's turning in a curve,
  /// Omega = V kappa (0, sin(cant), cos(cant)) (nothing at curvature 0). A cant that changes along
  /// the track (a transition) is taken step by step; its rate does not enter: the track frame's
  /// roll at V dcant/ds moves a rail point p at -V (e_x + dcant/ds e_x x p) in the frame, along
  /// the twisted rail's own tangent as the rolling wheel's material does, so to first order in the
  /// twist it adds no creepage (doc/method.md).
  double cant = 0.0;
  /// Vertical velocity of the wheelset's centre, d(pose.z)/dt [m/s], and roll rate,
  /// d(pose.roll)/dt [rad/s]. A wheelset moving laterally on coned or flanged wheels also rises and
  /// rolls as its profiles make it; without these the motion leaves the rail's surface at the patch
  /// (PatchCreepages::normal_velocity), and on a flange eta is vy cos(delta) / V rather than about
  /// vy / (V cos(delta)).
  double vz = 0.0;
  double roll_rate = 0.0;
};

/// The largest cant a step may give [rad]: about 300 mm of cant over standard gauge's 1.5 m
/// between the rails' centres, beyond any railway's.
inline constexpr double kMaxCant = 0.2;

enum class CreepageStatus {
  kOk,
  /// V = 0 (or so small that the creepages are not finite): no rolling, creepages undefined and
  /// given as 0; the sliding velocities are given.
  kNoRollingSpeed,
  /// A value not finite or out of range, or a candidate that does not belong to this wheel and
  /// pose (message); everything 0.
  kInvalidInput,
};

/// One patch's creepages and the relative velocities they come from, in the patch's contact frame.
struct PatchCreepages {
  double xi = 0.0;   ///< longitudinal creepage: (wheel - rail velocity).x / V
  double eta = 0.0;  ///< lateral creepage: (wheel - rail velocity).y / V
  double phi = 0.0;  ///< spin: (wheel - rail angular velocity).z / V [1/m]
  CreepageStatus status = CreepageStatus::kInvalidInput;
  std::string message;
  /// The relative velocity of the wheel's material over the rail's at the patch, along the contact
  /// frame's x and y [m/s], and the relative angular velocity about its z [rad/s]: the creepages
  /// times V, given also at V = 0 (a wheel spinning at standstill).
  double slip_x = 0.0, slip_y = 0.0, spin_rate = 0.0;
  /// The relative velocity along the normal [m/s], > 0 the wheel leaving the rail. Not part of the
  /// creepages; nonzero where vz and roll_rate do not follow the profiles (see WheelsetMotion).
  double normal_velocity = 0.0;
  /// The contact frame's axes x, y, z (columns) in track axes: a force (Fx, Fy, Fz) of the contact
  /// frame is frame * (Fx, Fy, Fz) in the track's.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

/// The creepages of one contact candidate of one wheel (ContactSearch::search or ContactTable for
/// the same side and pose; the same track data: nominal_radius places the axle). Never throws;
/// bad input (a motion value not finite or beyond its range, |motion.cant| > kMaxCant) gives a
/// status and a message, never NaN.
PatchCreepages patchCreepages(WheelSide side, const WheelsetPose& pose,
                              const WheelsetMotion& motion, const ContactCandidate& candidate,
                              const WheelsetTrackData& data);

}  // namespace wheel_rail_contact
