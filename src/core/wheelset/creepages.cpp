#include "wheel_rail_contact/wheelset/creepages.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

namespace wheel_rail_contact {

namespace {

// Inputs beyond this magnitude are refused, as every model's step does (doc/conventions.md).
constexpr double kMaxInput = 1e12;

}  // namespace

PatchCreepages patchCreepages(WheelSide side, const WheelsetPose& pose,
                              const WheelsetMotion& motion, const ContactCandidate& candidate,
                              const WheelsetTrackData& data) {
  PatchCreepages out;
  std::ostringstream msg;
  auto refuse = [&](const std::string& what) {
    if (msg.tellp() > 0) msg << "; ";
    msg << what;
  };
  auto finite = [&](const char* name, double v, double limit) {
    if (!std::isfinite(v) || std::abs(v) > limit) {
      std::ostringstream m;
      m << name << " = " << v << " is not finite or beyond +-" << limit;
      refuse(m.str());
    }
  };
  // The pose as far as this function needs it: the search refuses tighter limits.
  finite("pose y", pose.y, 1.0);
  finite("pose z", pose.z, 1.0);
  finite("pose yaw", pose.yaw, 0.5);
  finite("pose roll", pose.roll, 0.5);
  finite("motion V", motion.V, kMaxInput);
  finite("motion omega", motion.omega, kMaxInput);
  finite("motion vy", motion.vy, kMaxInput);
  finite("motion yaw_rate", motion.yaw_rate, kMaxInput);
  finite("motion vz", motion.vz, kMaxInput);
  finite("motion roll_rate", motion.roll_rate, kMaxInput);
  // A track radius below 1 m is not a railway: the rails would not be prisms over a patch.
  finite("motion curvature", motion.curvature, 1.0);
  finite("motion cant", motion.cant, kMaxCant);
  if (!(data.nominal_radius > 0.0) || !std::isfinite(data.nominal_radius))
    refuse("track nominal_radius must be finite and > 0");
  if (!(candidate.rolling_radius > 0.0 && candidate.rolling_radius <= 10.0))
    refuse("candidate rolling_radius must be in (0, 10] m");
  if (!candidate.point.allFinite() || !std::isfinite(candidate.vertical_gap) ||
      std::abs(candidate.vertical_gap) > 1.0)
    refuse("candidate point or vertical_gap is not finite");
  const double nnorm = candidate.normal.norm();
  if (!candidate.normal.allFinite() || !(nnorm > 0.5 && nnorm < 2.0) ||
      !(candidate.normal.y() > 0.0))
    refuse("candidate normal must be a finite unit vector pointing up, from rail into wheel");
  if (msg.tellp() > 0) {
    out.message = msg.str();
    return out;
  }

  // The contact frame: z the normal, x the track's x (the normal has no x-component), y = z x x.
  const Eigen::Vector3d n =
      Eigen::Vector3d(0.0, candidate.normal.x(), candidate.normal.y()) / nnorm;
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d ey = n.cross(ex);
  // The contact angle is measured toward the track centre: +y on the right wheel, -y on the left.
  const double sigma = side == WheelSide::kRight ? 1.0 : -1.0;
  const double angle = std::atan2(sigma * n.y(), n.z());
  if (!std::isfinite(candidate.contact_angle) || std::abs(angle - candidate.contact_angle) > 0.01)
    refuse(
        "candidate contact_angle does not match its normal on this side (a candidate of the "
        "other wheel?)");

  const Eigen::Matrix3d R = (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d axle = R.col(1);
  const Eigen::Vector3d centre(0.0, pose.y, data.nominal_radius + pose.z);
  const Eigen::Vector3d& p = candidate.point;
  // The wheel's point facing p: vertical_gap above it (the search's locus point).
  const Eigen::Vector3d d = p + candidate.vertical_gap * Eigen::Vector3d::UnitZ() - centre;
  const double axial = d.dot(axle);
  const Eigen::Vector3d radial = d - axial * axle;
  const double rho = radial.norm();
  const double r = candidate.rolling_radius;
  if (sigma * axial > 0.0)
    refuse(std::string("candidate point lies on the ") + (sigma > 0 ? "left" : "right") +
           " half of the axle, not on the " + (sigma > 0 ? "right" : "left") + " wheel");
  // The wheel's circle through that point has the rolling radius: far from it, the pose or the
  // track data is not the one searched (a table's interpolation stays well within 1 %).
  if (!(std::abs(rho - r) <= 0.01 * r)) {
    std::ostringstream m;
    m << "candidate point is " << rho << " m from the axle, its rolling radius " << r
      << " m: not this pose's or track data's candidate";
    refuse(m.str());
  }
  if (msg.tellp() > 0) {
    out.message = msg.str();
    return out;
  }

  // The wheel's material on its circle of the rolling radius, in the direction of the point.
  const Eigen::Vector3d q = centre + axial * axle + (r / rho) * radial;
  const double V = motion.V;
  // The wheelset's angular velocity relative to the track frame: yaw about the track's z, roll
  // about the yawed x, pitch about the axle (the rates of R = Rz(yaw) Rx(roll) Ry(pitch)).
  const Eigen::Vector3d roll_axis(std::cos(pose.yaw), std::sin(pose.yaw), 0.0);
  const Eigen::Vector3d omega_w = motion.yaw_rate * Eigen::Vector3d::UnitZ() +
                                  motion.roll_rate * roll_axis + motion.omega * axle;
  // The track frame's own rotation, V kappa about the vertical, which is (0, sin, cos)(cant) in
  // the canted track axes. The rail, fixed on the ground, turns at -Omega in the frame.
  const Eigen::Vector3d Omega =
      V * motion.curvature * Eigen::Vector3d(0.0, std::sin(motion.cant), std::cos(motion.cant));
  const Eigen::Vector3d v_wheel =
      Eigen::Vector3d(0.0, motion.vy, motion.vz) + omega_w.cross(q - centre);
  const Eigen::Vector3d v_rail = -(V * ex + Omega.cross(p));
  const Eigen::Vector3d dv = v_wheel - v_rail;
  const Eigen::Vector3d dw = omega_w + Omega;

  out.slip_x = dv.dot(ex);
  out.slip_y = dv.dot(ey);
  out.normal_velocity = dv.dot(n);
  out.spin_rate = dw.dot(n);
  out.frame.col(0) = ex;
  out.frame.col(1) = ey;
  out.frame.col(2) = n;
  if (V == 0.0) {
    out.status = CreepageStatus::kNoRollingSpeed;
    out.message = "V = 0: no rolling, the creepages are undefined (given as 0)";
    return out;
  }
  const double xi = out.slip_x / V, eta = out.slip_y / V, phi = out.spin_rate / V;
  if (!std::isfinite(xi) || !std::isfinite(eta) || !std::isfinite(phi)) {
    out.status = CreepageStatus::kNoRollingSpeed;
    out.message = "V is too small for finite creepages (given as 0)";
    return out;
  }
  out.xi = xi;
  out.eta = eta;
  out.phi = phi;
  out.status = CreepageStatus::kOk;
  return out;
}

}  // namespace wheel_rail_contact
