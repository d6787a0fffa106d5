// Creepages per patch from the wheelset's motion: rigid-body kinematics against the linearised
// wheelset theory, the symmetries, and the Manchester benchmark's case inputs.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "a22_states.hpp"
#include "contact_search_helpers.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"
#include "wheel_rail_contact/wheelset/creepages.hpp"

using namespace wheel_rail_contact;

namespace {

/// The mirror image of a motion in the track's x-z plane: lateral and rotations about z and x
/// change sign, the forward speed and the pitch rate do not.
WheelsetMotion mirrored(const WheelsetMotion& m) {
  WheelsetMotion r = m;
  r.vy = -m.vy;
  r.yaw_rate = -m.yaw_rate;
  r.roll_rate = -m.roll_rate;
  r.curvature = -m.curvature;
  r.cant = -m.cant;
  return r;
}

double sideSign(WheelSide s) {
  return s == WheelSide::kLeft ? 1.0 : -1.0;
}

/// An exact contact on a coned wheel (cone angle delta against the axle's normal plane, rolling
/// radius r, its circle l0 from the wheelset's centre): the point of the circle whose normal lies
/// in the track's y-z plane, as the contact search finds it, for any yaw and roll.
ContactCandidate coneContact(WheelSide side, const WheelsetPose& pose, double delta, double r,
                             double l0, double nominal_radius) {
  const double t = side == WheelSide::kRight ? 1.0 : -1.0;  // toward the track centre
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  // The wheel's outward normal at angle theta round its circle: -t sin(delta) e_y +
  // cos(delta) (sin theta, 0, -cos theta); its track x-component vanishes at theta.
  const double A = R(0, 0) * std::cos(delta), B = -R(0, 2) * std::cos(delta);
  const double C = t * std::sin(delta) * R(0, 1);
  const double theta = std::asin(C / std::hypot(A, B)) - std::atan2(B, A);
  const Eigen::Vector3d nw(std::cos(delta) * std::sin(theta), -t * std::sin(delta),
                           -std::cos(delta) * std::cos(theta));
  const Eigen::Vector3d nt = R * nw;
  EXPECT_NEAR(nt.x(), 0.0, 1e-14);
  const Eigen::Vector3d centre(0.0, pose.y, nominal_radius + pose.z);
  ContactCandidate c;
  c.point = centre + R * Eigen::Vector3d(r * std::sin(theta), -t * l0, -r * std::cos(theta));
  c.normal = -Eigen::Vector2d(nt.y(), nt.z()).normalized();
  c.contact_angle = std::atan2(t * c.normal.x(), c.normal.y());
  c.rolling_radius = r;
  return c;
}

PatchCreepages ok(const PatchCreepages& c) {
  EXPECT_EQ(c.status, CreepageStatus::kOk) << c.message;
  return c;
}

}  // namespace

TEST(Creepages, PureRollingAtTheRollingRadiusGivesNoLongitudinalCreepage) {
  // Rolling at omega = V / r about a rolled (not yawed) axle, the wheel's material at the contact
  // moves back at exactly V relative to the wheelset: xi = 0 on every patch, both wheels, and the
  // sliding velocity has no component along the normal (the wheel's surface turns in itself).
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  for (double y : {0.0, -0.002, 0.003, -0.008}) {
    WheelsetPose pose;
    pose.y = y;
    pose.roll = 0.002 * y / 0.008;
    for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight}) {
      const WheelContactGeometry g = cs.search(side, pose);
      ASSERT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
      for (const ContactCandidate& c : g.candidates) {
        WheelsetMotion m;
        m.V = 2.0;
        m.omega = m.V / c.rolling_radius;
        const PatchCreepages k = ok(patchCreepages(side, pose, m, c, data));
        EXPECT_NEAR(k.xi, 0.0, 1e-12) << "y = " << y;
        EXPECT_NEAR(k.eta, 0.0, 1e-12);
        EXPECT_NEAR(k.normal_velocity, 0.0, 1e-12);
        // Braking by one per cent: xi = +0.01 (the wheel's surface slides forward).
        m.omega *= 0.99;
        EXPECT_NEAR(ok(patchCreepages(side, pose, m, c, data)).xi, 0.01, 1e-12);
        // The rolling radius, not the point's distance from the axle, sets the wheel's speed (a
        // table's interpolated candidate need not have them agree exactly).
        ContactCandidate larger = c;
        larger.rolling_radius *= 1.002;
        EXPECT_NEAR(ok(patchCreepages(side, pose, m, larger, data)).xi, 1.0 - 0.99 * 1.002, 1e-12);
      }
    }
  }
}

TEST(Creepages, CentredYawedWheelsetHasEtaMinusYawAndConicitySpinOfOppositeSigns) {
  // A centred wheelset yawed by psi, rolling at omega = V / r: the wheel's surface moves back
  // along the wheelset's own x, at an angle psi to the track, so eta = -sin(psi) cos(delta) (plus
  // a second-order part from the lead). The spin is the pitch rate's component along the normal,
  // omega cos(psi) sin(delta) toward the track centre: + on the right wheel, - on the left.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  for (double psi : {0.004, -0.004, 0.0}) {
    WheelsetPose pose;
    pose.yaw = psi;
    for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight}) {
      const WheelContactGeometry g = cs.search(side, pose);
      ASSERT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
      for (const ContactCandidate& c : g.candidates) {
        ASSERT_EQ(c.zone, ContactZone::kTread);
        WheelsetMotion m;
        m.V = 2.0;
        m.omega = m.V / c.rolling_radius;
        const PatchCreepages k = ok(patchCreepages(side, pose, m, c, data));
        const double eta = -std::sin(psi) / std::cos(c.contact_angle);
        EXPECT_NEAR(k.eta, eta, 1e-4 * std::abs(psi) + 1e-15) << "psi " << psi;
        EXPECT_NEAR(k.eta, -psi, 3e-3 * std::abs(psi) + 1e-15) << "psi " << psi;
        const double spin = -sideSign(side) * std::sin(c.contact_angle) / c.rolling_radius;
        EXPECT_NEAR(k.phi, spin, 1e-4 * std::abs(spin));
        EXPECT_GT(c.contact_angle, 0.0);
        EXPECT_GT(-sideSign(side) * k.phi, 0.0);
      }
    }
  }
}

TEST(Creepages, LateralVelocityGivesEtaAndOnAFlangeTheRisingWheelMore) {
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  WheelsetMotion m;
  m.V = 2.0;
  m.vy = 0.01;
  // On the tread: eta = vy cos(delta) / V, vy / V to first order.
  {
    const WheelsetPose pose;
    const ContactCandidate c = closest(cs.search(WheelSide::kRight, pose));
    m.omega = m.V / c.rolling_radius;
    const PatchCreepages k = ok(patchCreepages(WheelSide::kRight, pose, m, c, data));
    EXPECT_NEAR(k.eta, m.vy / m.V * std::cos(c.contact_angle), 1e-12);
    EXPECT_NEAR(k.eta, m.vy / m.V, 1e-3 * m.vy / m.V);
    EXPECT_NEAR(k.xi, 0.0, 1e-12);
  }
  // On the right wheel's flange (wheelset 8 mm to the right): with vz = 0 the wheel moves into
  // the flange's normal, part of vy is approach (normal_velocity); rising as the flange makes it,
  // vz = -vy tan(delta), the whole motion is in the contact plane and eta = vy / (V cos(delta)).
  WheelsetPose pose;
  pose.y = -0.008;
  const ContactCandidate c = closest(cs.search(WheelSide::kRight, pose));
  ASSERT_EQ(c.zone, ContactZone::kFlange);
  m.omega = m.V / c.rolling_radius;
  m.vy = -0.01;
  const PatchCreepages flat = ok(patchCreepages(WheelSide::kRight, pose, m, c, data));
  EXPECT_NEAR(flat.eta, m.vy / m.V * std::cos(c.contact_angle), 1e-12);
  EXPECT_NEAR(flat.normal_velocity, m.vy * std::sin(c.contact_angle), 1e-12);
  m.vz = -m.vy * std::tan(c.contact_angle);
  const PatchCreepages rising = ok(patchCreepages(WheelSide::kRight, pose, m, c, data));
  EXPECT_NEAR(rising.normal_velocity, 0.0, 1e-12);
  EXPECT_NEAR(rising.eta, m.vy / (m.V * std::cos(c.contact_angle)), 1e-12);
}

TEST(Creepages, YawRateGivesOppositeXiOnTheTwoWheels) {
  // Turning at yaw_rate about the wheelset's centre moves the left wheel back and the right one
  // forward by yaw_rate times the contact's lateral distance: xi = -+ l yaw_rate / V.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  const WheelsetPose pose;
  WheelsetMotion m;
  m.V = 2.0;
  m.yaw_rate = 0.05;
  double xi[2];
  for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight}) {
    const ContactCandidate c = closest(cs.search(side, pose));
    m.omega = m.V / c.rolling_radius;
    const PatchCreepages k = ok(patchCreepages(side, pose, m, c, data));
    EXPECT_NEAR(k.xi, -m.yaw_rate * c.point.y() / m.V, 1e-12);
    EXPECT_NEAR(k.phi,
                m.yaw_rate * std::cos(c.contact_angle) / m.V +
                    -sideSign(side) * std::sin(c.contact_angle) / c.rolling_radius,
                1e-12);
    xi[side == WheelSide::kLeft ? 0 : 1] = k.xi;
  }
  EXPECT_LT(xi[0], -0.01);
  EXPECT_NEAR(xi[0], -xi[1], 1e-9);
}

TEST(Creepages, LinearisedWheelsetTheoryIsTheFirstOrderLimit) {
  // Every small quantity scaled by eps: yaw, roll, cone angle, vy / V, yaw_rate l0 / V,
  // roll_rate r / V, kappa l0, cant, omega r / V - 1. The exact creepages differ from the
  // textbook's linear forms by O(eps^2): a quarter when eps halves.
  const WheelsetTrackData data;
  const double l0 = 0.75, r0 = data.nominal_radius, V = 3.0;
  for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight}) {
    const double s = sideSign(side);
    for (int dir = 0; dir < 4; ++dir) {
      const double sg = dir % 2 ? -1.0 : 1.0, sg2 = dir / 2 ? -1.0 : 1.0;
      double err[2];
      for (int h = 0; h < 2; ++h) {
        const double eps = 0.02 / (1 << h);
        WheelsetPose pose;
        pose.yaw = 0.7 * eps * sg;
        pose.roll = -0.4 * eps * sg2;
        const double cone = 0.9 * eps;
        const double r = r0 * (1.0 + 0.5 * eps * sg);
        WheelsetMotion m;
        m.cant = 0.5 * eps * sg2;
        m.V = V;
        m.vy = 0.5 * eps * V * sg2;
        m.yaw_rate = 0.8 * eps * V / l0 * sg;
        m.roll_rate = -0.6 * eps * V / r * sg;
        m.curvature = 0.6 * eps / l0 * sg2;
        m.omega = V / r * (1.0 + 0.3 * eps * sg2);
        const ContactCandidate c = coneContact(side, pose, cone, r, l0, r0);
        const PatchCreepages k = ok(patchCreepages(side, pose, m, c, data));
        const double delta = c.contact_angle;
        const double xi = 1.0 - m.omega * r / V - s * l0 * (m.yaw_rate / V + m.curvature);
        const double eta = m.vy / V + m.roll_rate * r / V - pose.yaw;
        const double phi = m.yaw_rate / V + m.curvature + (pose.roll - s * delta) / r;
        err[h] = std::max({std::abs(k.xi - xi), std::abs(k.eta - eta), r * std::abs(k.phi - phi)});
        // The first-order terms themselves are of order eps: the forms are not vacuous.
        EXPECT_GT(std::abs(xi) + std::abs(eta), 0.2 * eps);
        EXPECT_LT(err[h], 3.0 * eps * eps) << "eps " << eps;
      }
      EXPECT_GT(err[0] / err[1], 3.0) << "side " << s << " dir " << dir;
      EXPECT_LT(err[0] / err[1], 5.0) << "side " << s << " dir " << dir;
    }
  }
}

TEST(Creepages, RadialSteeringInACurveGivesNoLongitudinalCreepage) {
  // In a left curve of radius 600 m the outer (right) rail is longer: a wheelset shifted outward
  // until its rolling radii differ as the rails' lengths do, r_R / r_L = (1 - kappa y_R) /
  // (1 - kappa y_L), rolls through it with xi = 0 on both wheels, yawed radially (relative yaw
  // and yaw rate 0: it turns with the track at V kappa).
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  WheelsetMotion m;
  m.V = 20.0;
  m.curvature = 1.0 / 600.0;
  auto at = [&](double y, ContactCandidate* l, ContactCandidate* r) {
    WheelsetPose p;
    p.y = y;
    *l = closest(cs.search(WheelSide::kLeft, p));
    *r = closest(cs.search(WheelSide::kRight, p));
    return r->rolling_radius / l->rolling_radius -
           (1.0 - m.curvature * r->point.y()) / (1.0 - m.curvature * l->point.y());
  };
  ContactCandidate cl, cr;
  double lo = -0.004, hi = -0.0005;  // the mismatch changes sign between (checked)
  const double f_lo = at(lo, &cl, &cr), f_hi = at(hi, &cl, &cr);
  ASSERT_LT(f_lo * f_hi, 0.0) << f_lo << " " << f_hi;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((at(mid, &cl, &cr) < 0.0) == (f_lo < 0.0))
      lo = mid;
    else
      hi = mid;
  }
  WheelsetPose pose;
  pose.y = 0.5 * (lo + hi);
  EXPECT_LT(std::abs(at(pose.y, &cl, &cr)), 1e-9);
  m.omega = m.V * (1.0 - m.curvature * cl.point.y()) / cl.rolling_radius;
  const PatchCreepages kl = ok(patchCreepages(WheelSide::kLeft, pose, m, cl, data));
  const PatchCreepages kr = ok(patchCreepages(WheelSide::kRight, pose, m, cr, data));
  EXPECT_NEAR(kl.xi, 0.0, 1e-8);
  EXPECT_NEAR(kr.xi, 0.0, 1e-8);
  // Not steered radially (no rolling radius difference): xi = -+ kappa l0 on the two wheels.
  WheelsetPose centred;
  for (WheelSide side : {WheelSide::kLeft, WheelSide::kRight}) {
    const ContactCandidate c = closest(cs.search(side, centred));
    m.omega = m.V / c.rolling_radius;
    const PatchCreepages k = ok(patchCreepages(side, centred, m, c, data));
    EXPECT_NEAR(k.xi, -m.curvature * c.point.y(), 1e-12);
    // The track's turning adds kappa cos(delta) to the spin.
    EXPECT_NEAR(k.phi,
                m.curvature * std::cos(c.contact_angle) -
                    sideSign(side) * std::sin(c.contact_angle) / c.rolling_radius,
                1e-12);
  }
}

TEST(Creepages, CantTurnsTheCurvesRotationInTheCantedTrackAxes) {
  // The step's cant enters only through the track frame's turning Omega = V kappa (0, sin c,
  // cos c): against cant 0, each patch's sliding velocity changes by dOmega x p and its spin by
  // dOmega.n, dOmega = V kappa (0, sin c, cos c - 1), in the patch's contact frame. On tangent
  // track the cant changes nothing. Every zone of the benchmark's states, both wheels.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  int flange = 0, leaning = 0;
  for (const A22State& a : a22States()) {
    const WheelsetPose p = a22Pose(a);
    WheelsetMotion m;
    m.V = 20.0;
    m.omega = 20.0 / 0.46;
    m.vy = 0.02;
    m.yaw_rate = -0.01;
    m.curvature = -1.0 / 250.0;
    for (const ContactCandidate& c : cs.search(a.side, p).candidates) {
      flange += c.zone != ContactZone::kTread;
      const PatchCreepages level = ok(patchCreepages(a.side, p, m, c, data));
      for (double cant : {0.15, -0.2, 0.05}) {
        WheelsetMotion mc = m;
        mc.cant = cant;
        const PatchCreepages k = ok(patchCreepages(a.side, p, mc, c, data));
        const Eigen::Vector3d dOmega =
            m.V * m.curvature * Eigen::Vector3d(0.0, std::sin(cant), std::cos(cant) - 1.0);
        const Eigen::Vector3d dv = dOmega.cross(c.point);
        const Eigen::Vector3d n = k.frame.col(2);
        EXPECT_NEAR(k.xi - level.xi, dv.x() / m.V, 1e-12) << a.y_mm << " " << cant;
        EXPECT_NEAR(k.eta - level.eta, dv.dot(k.frame.col(1)) / m.V, 1e-12);
        EXPECT_NEAR(k.phi - level.phi, dOmega.dot(n) / m.V, 1e-12);
        EXPECT_NEAR(k.normal_velocity - level.normal_velocity, dv.dot(n), 1e-12);
        // Not vacuous: at 0.15 rad in a 250 m curve the spin moves by about kappa sin(c) n_y.
        if (std::abs(cant) > 0.1 && std::abs(n.y()) > 0.3) {
          EXPECT_GT(std::abs(k.phi - level.phi), 1e-4) << a.y_mm;
          ++leaning;
        }
        // On tangent track the cant is no input.
        WheelsetMotion straight = mc;
        straight.curvature = 0.0;
        WheelsetMotion straight_level = m;
        straight_level.curvature = 0.0;
        const PatchCreepages s = ok(patchCreepages(a.side, p, straight, c, data));
        const PatchCreepages s0 = ok(patchCreepages(a.side, p, straight_level, c, data));
        EXPECT_EQ(s.xi, s0.xi);
        EXPECT_EQ(s.eta, s0.eta);
        EXPECT_EQ(s.phi, s0.phi);
      }
    }
  }
  EXPECT_GT(flange, 0) << "no gauge corner or flange patch among the states";
  EXPECT_GT(leaning, 0) << "no patch whose normal leans enough to show the cant";
}

TEST(Creepages, LeftWheelInTheMirroredStateHasTheMirroredCreepages) {
  // The contact frame is not mirrored (doc/conventions.md): the left wheel in the mirror image of
  // the right wheel's state has the same xi and the opposite eta and phi.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  for (const A22State& a : a22States()) {
    if (a.side != WheelSide::kRight) continue;
    const WheelsetPose p = a22Pose(a);
    WheelsetMotion m;
    m.V = 2.0;
    m.omega = 4.3;
    m.vy = 0.003;
    m.yaw_rate = -0.02;
    m.roll_rate = 0.004;
    m.vz = -0.001;
    m.curvature = 1.0 / 300.0;
    m.cant = 0.1;
    const WheelContactGeometry r = cs.search(WheelSide::kRight, p);
    const WheelContactGeometry l = cs.search(WheelSide::kLeft, mirrored(p));
    ASSERT_EQ(r.candidates.size(), l.candidates.size());
    for (std::size_t k = 0; k < r.candidates.size(); ++k) {
      const PatchCreepages cr = ok(patchCreepages(WheelSide::kRight, p, m, r.candidates[k], data));
      const PatchCreepages cl =
          ok(patchCreepages(WheelSide::kLeft, mirrored(p), mirrored(m), l.candidates[k], data));
      EXPECT_NEAR(cl.xi, cr.xi, 1e-9) << "y = " << a.y_mm;
      EXPECT_NEAR(cl.eta, -cr.eta, 1e-9) << "y = " << a.y_mm;
      EXPECT_NEAR(cl.phi, -cr.phi, 1e-9) << "y = " << a.y_mm;
      EXPECT_NEAR(cl.normal_velocity, cr.normal_velocity, 1e-9);
      EXPECT_GT(std::abs(cr.eta), 1e-4);
    }
  }
}

TEST(Creepages, RollingBackwardsKeepsTheCreepagesDividedBySignedV) {
  // Every velocity reversed reverses the sliding velocities and V together: the creepages, divided
  // by the signed V (doc/conventions.md), are unchanged; a wheel braked while rolling backwards
  // still has xi > 0.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  WheelsetPose pose;
  pose.y = -0.003;
  pose.yaw = 0.004;
  const ContactCandidate c = closest(cs.search(WheelSide::kRight, pose));
  WheelsetMotion m;
  m.V = 2.0;
  m.omega = 0.99 * m.V / c.rolling_radius;
  m.vy = 0.01;
  m.yaw_rate = 0.03;
  m.roll_rate = -0.002;
  m.vz = 0.001;
  m.curvature = 1.0 / 400.0;
  WheelsetMotion back = m;
  back.V = -m.V;
  back.omega = -m.omega;
  back.vy = -m.vy;
  back.yaw_rate = -m.yaw_rate;
  back.roll_rate = -m.roll_rate;
  back.vz = -m.vz;
  const PatchCreepages f = ok(patchCreepages(WheelSide::kRight, pose, m, c, data));
  const PatchCreepages b = ok(patchCreepages(WheelSide::kRight, pose, back, c, data));
  EXPECT_NEAR(b.xi, f.xi, 1e-15);
  EXPECT_NEAR(b.eta, f.eta, 1e-15);
  EXPECT_NEAR(b.phi, f.phi, 1e-13);
  EXPECT_NEAR(b.slip_x, -f.slip_x, 1e-15);
  EXPECT_GT(f.xi, 0.005);
}

TEST(Creepages, FrameIsTheContactFrameOfTheConventions) {
  // z the normal (rail into wheel), x the track's x, y = z x x: right-handed, y to the left and
  // down the flank toward the field on a right flange, up it on a left one.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  WheelsetPose p;
  p.y = -0.008;
  const ContactCandidate c = closest(cs.search(WheelSide::kRight, p));
  WheelsetMotion m;
  m.V = 1.0;
  const PatchCreepages k = ok(patchCreepages(WheelSide::kRight, p, m, c, data));
  EXPECT_NEAR((k.frame.transpose() * k.frame - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(k.frame.determinant(), 1.0, 1e-14);
  EXPECT_NEAR(k.frame.col(2).y(), std::sin(c.contact_angle), 1e-12);
  EXPECT_NEAR(k.frame.col(2).z(), std::cos(c.contact_angle), 1e-12);
  EXPECT_GT(k.frame.col(1).y(), 0.0);
  EXPECT_LT(k.frame.col(1).z(), 0.0);
}

TEST(Creepages, BadInputGivesAStatusNeverNaN) {
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  const WheelsetPose pose;
  const ContactCandidate c = closest(cs.search(WheelSide::kRight, pose));
  WheelsetMotion m;
  m.omega = 3.0;
  // Standing still: no creepages, but the wheel spinning on the spot slides back at omega r.
  PatchCreepages k = patchCreepages(WheelSide::kRight, pose, m, c, data);
  EXPECT_EQ(k.status, CreepageStatus::kNoRollingSpeed);
  EXPECT_FALSE(k.message.empty());
  EXPECT_EQ(k.xi, 0.0);
  EXPECT_NEAR(k.slip_x, -3.0 * c.rolling_radius, 1e-12);
  m.V = 1e-320;  // denormal: omega r / V overflows
  k = patchCreepages(WheelSide::kRight, pose, m, c, data);
  EXPECT_EQ(k.status, CreepageStatus::kNoRollingSpeed);
  EXPECT_TRUE(std::isfinite(k.xi));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto refused = [&](const PatchCreepages& r, const char* name) {
    EXPECT_EQ(r.status, CreepageStatus::kInvalidInput) << name;
    EXPECT_NE(r.message.find(name), std::string::npos) << r.message;
    for (double v : {r.xi, r.eta, r.phi, r.slip_x, r.slip_y, r.spin_rate, r.normal_velocity})
      EXPECT_TRUE(std::isfinite(v)) << name;
  };
  m.V = 2.0;
  for (double bad : {nan, inf, 2e12}) {
    const std::pair<double WheelsetMotion::*, const char*> fields[] = {
        {&WheelsetMotion::V, "V"},
        {&WheelsetMotion::omega, "omega"},
        {&WheelsetMotion::vy, "vy"},
        {&WheelsetMotion::yaw_rate, "yaw_rate"},
        {&WheelsetMotion::curvature, "curvature"},
        {&WheelsetMotion::cant, "cant"},
        {&WheelsetMotion::vz, "vz"},
        {&WheelsetMotion::roll_rate, "roll_rate"}};
    for (const auto& [field, name] : fields) {
      WheelsetMotion b = m;
      b.*field = bad;
      refused(patchCreepages(WheelSide::kRight, pose, b, c, data), name);
    }
    WheelsetPose q = pose;
    q.yaw = bad;
    refused(patchCreepages(WheelSide::kRight, q, m, c, data), "yaw");
    ContactCandidate cc = c;
    cc.point.x() = bad;
    refused(patchCreepages(WheelSide::kRight, pose, m, cc, data), "point");
    cc = c;
    cc.normal.y() = bad;
    refused(patchCreepages(WheelSide::kRight, pose, m, cc, data), "normal");
    cc = c;
    cc.rolling_radius = bad;
    refused(patchCreepages(WheelSide::kRight, pose, m, cc, data), "rolling_radius");
  }
  // A cant beyond kMaxCant either way, the largest one taken.
  for (double cant : {-0.21, 0.21}) {
    WheelsetMotion b = m;
    b.cant = cant;
    refused(patchCreepages(WheelSide::kRight, pose, b, c, data), "cant");
    b.cant = cant > 0 ? kMaxCant : -kMaxCant;
    EXPECT_EQ(patchCreepages(WheelSide::kRight, pose, b, c, data).status, CreepageStatus::kOk);
  }
  // A candidate of the other wheel, a default one, another pose's: refused by name.
  refused(patchCreepages(WheelSide::kLeft, pose, m, c, data), "contact_angle");
  refused(patchCreepages(WheelSide::kRight, pose, m, ContactCandidate(), data), "rolling_radius");
  WheelsetPose lifted = pose;
  lifted.z = 0.02;
  refused(patchCreepages(WheelSide::kRight, lifted, m, c, data), "point");
}

TEST(Creepages, A22BenchmarkInputsGiveSmallPlausibleCreepages) {
  // The benchmark's wheelset states with its speed and pitch rate (the sign turned to ours). At
  // y = 0 the longitudinal creepage is (V - omega r) / V; everywhere the creepages are small, the
  // lateral one that of the yaw (eta about -yaw / cos(delta): the benchmark's roll rate and
  // vertical velocity are 0, its states are quasi-static), and the spin that of the contact
  // angle and the roll.
  const WheelsetTrackData data;
  const ContactSearch cs(data);
  std::printf("wheel  y_mm  zone  delta    r_mm      xi         eta        phi_1/m\n");
  for (const A22State& a : a22States()) {
    const WheelSide side = a.side;
    // The benchmark's left rows are the left wheel of the same wheelset state (CONTACT's
    // mbench_a22_left example: the same Y_WS, its left wheel rolling toward its field side).
    const WheelsetPose p = a22Pose(a);
    const WheelsetMotion m = a22Motion(a);
    const WheelContactGeometry g = cs.search(side, p);
    ASSERT_EQ(g.status, ContactSearchStatus::kOk);
    for (const ContactCandidate& c : g.candidates) {
      const PatchCreepages k = ok(patchCreepages(side, p, m, c, data));
      std::printf("%-5s %5.1f  %d  %7.4f  %7.2f  %9.2e  %9.2e  %9.3e\n",
                  side == WheelSide::kRight ? "right" : "left", a.y_mm, static_cast<int>(c.zone),
                  c.contact_angle, c.rolling_radius * 1e3, k.xi, k.eta, k.phi);
      if (a.y_mm == 0.0) {
        EXPECT_NEAR(k.xi, (m.V - m.omega * c.rolling_radius) / m.V, 1e-12);
      }
      const double xi = 1.0 - m.omega * c.rolling_radius / m.V;
      // Off y = 0 the wheel's surface moves back at an angle to the track: yawed by psi, and
      // along the circle by theta = asin(lead / r) on a leading flange: xi differs from
      // 1 - omega r / V by 1 - cos(psi) cos(theta), about (psi^2 + theta^2) / 2.
      const double theta = c.lead / c.rolling_radius;
      EXPECT_NEAR(k.xi, xi, 0.6 * (p.yaw * p.yaw + theta * theta) + 1e-12) << a.y_mm;
      EXPECT_LT(std::abs(k.xi), 0.03);
      // The surface's speed omega r along the yawed wheel, in the contact plane.
      const double eta = -std::sin(p.yaw) * (1.0 - xi) / std::cos(c.contact_angle);
      EXPECT_NEAR(k.eta, eta, 0.02 * std::abs(eta) + 1e-12) << a.y_mm;
      // The pitch rate's component along the normal: the axle is rolled by theta, the normal
      // tilted by delta toward the track centre (the benchmark's roll, up to 11 mrad, is as large
      // as the left wheel's contact angle).
      const double spin = (std::sin(p.roll) * std::cos(c.contact_angle) -
                           sideSign(side) * std::sin(c.contact_angle)) *
                          m.omega / m.V;
      EXPECT_NEAR(k.phi, spin, 0.02 * std::abs(spin)) << a.y_mm;
    }
  }
}
