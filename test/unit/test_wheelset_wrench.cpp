// WheelsetContact's forces in track axes: each patch's wrench (PatchResult::wrench) and each
// wheel's (WheelResult::wrench) about the wheel's centre, on the Manchester benchmark's case
// (S1002 on UIC60 1:40, the built-in profiles).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

using namespace wheel_rail_contact;

namespace {

/// The benchmark's right-wheel states (test_wheelset_contact.cpp): lateral shift y_mm in CONTACT's
/// axes (to the right), turned into REP 103 (y and yaw change sign, omega = -vpitch).
WheelsetState a22(double y_mm, double yaw, double roll, double vpitch) {
  WheelsetState s;
  s.pose.y = -y_mm * 1e-3;
  s.pose.yaw = -yaw;
  s.pose.roll = roll;
  s.motion.V = 2.0;
  s.motion.omega = -vpitch;
  s.fz_left = s.fz_right = 1e4;
  return s;
}
std::vector<WheelsetState> a22States() {
  return {a22(0.5, 0.0012, -2.304e-05, -4.34741), a22(5.0, 0.012, -0.0003554, -4.33536),
          a22(5.5, 0.0132, -0.0004777, -4.33189), a22(6.5, 0.0156, -0.004376, -4.27488)};
}

/// The mirror image in the track's x-z plane: the left wheel then sees what the right one saw.
WheelsetState mirrored(WheelsetState s) {
  s.pose.y = -s.pose.y;
  s.pose.yaw = -s.pose.yaw;
  s.pose.roll = -s.pose.roll;
  s.motion.vy = -s.motion.vy;
  s.motion.yaw_rate = -s.motion.yaw_rate;
  s.motion.curvature = -s.motion.curvature;
  std::swap(s.fz_left, s.fz_right);
  return s;
}

ContactParameters steady() {
  ContactParameters p;
  p.model = "steady";
  return p;
}

std::vector<double> values(const TrackWrench& w) {
  return {w.fx, w.fy, w.fz, w.mx, w.my, w.mz};
}

/// The wheelset's axle in track axes (creepages.hpp: R = Rz(yaw) Rx(roll)).
Eigen::Vector3d axle(const WheelsetPose& pose) {
  return (Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pose.roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix()
      .col(1);
}

}  // namespace

TEST(WheelsetWrench, TheWheelsIsThePatchesSumAndItsVerticalForceTheLoadPlusTheTangentialShare) {
  // The normal forces' vertical components add up to the load (solveWheelLoad, within its load
  // tolerance); the wrench's vertical force adds the tangential forces' own, -fs n_y per patch
  // (fx lies along the track's x). Not 0: on the gauge corner at 5.5 mm it is some 1 kN.
  const double tolerance = NormalOptions{}.load_tolerance;
  bool tangential_share = false;
  for (const WheelsetState& s : a22States()) {
    WheelsetContact c(WheelsetTrackData{}, steady());
    const WheelsetResult r = c.step(s, 0.0);
    for (const WheelResult* w : {&r.left, &r.right}) {
      ASSERT_EQ(w->status, WheelStatus::kOk) << w->message;
      TrackWrench sum;
      double share = 0.0;
      for (const PatchResult& p : w->patches) {
        const std::vector<double> v = values(p.wrench);
        const std::vector<double> t = values(sum);
        sum = {t[0] + v[0], t[1] + v[1], t[2] + v[2], t[3] + v[3], t[4] + v[4], t[5] + v[5]};
        share -= p.fs * p.geometry.normal.x();
      }
      const std::vector<double> total = values(w->wrench), expected = values(sum);
      for (int k = 0; k < 6; ++k) {
        EXPECT_TRUE(std::isfinite(total[k]));
        EXPECT_NEAR(total[k], expected[k], 1e-9 * (1.0 + std::abs(expected[k]))) << k;
      }
      EXPECT_NEAR(w->wrench.fz - share, 1e4, 2.0 * tolerance * 1e4) << s.pose.y;
      tangential_share |= std::abs(share) > 100.0;
    }
  }
  EXPECT_TRUE(tangential_share);  // the test above checks something
}

TEST(WheelsetWrench, EachPatchsForceIsItsContactFrameTurnedByTheContactAngle) {
  // The contact frame turned into track axes by the contact angle delta: on the right wheel
  // n = (0, sin, cos)(delta), e_y = (0, cos, -sin)(delta); on the left n = (0, -sin, cos)(delta),
  // e_y = (0, cos, sin)(delta); e_x the track's x on both.
  int checked = 0;
  for (const WheelsetState& s : a22States()) {
    WheelsetContact c(WheelsetTrackData{}, steady());
    const WheelsetResult r = c.step(s, 0.0);
    for (const WheelResult* w : {&r.left, &r.right}) {
      const double sigma = w->side == WheelSide::kRight ? 1.0 : -1.0;
      for (const PatchResult& p : w->patches) {
        const double d = p.geometry.contact_angle, fn = p.normal.fn;
        const double tol = 1e-9 * fn;
        EXPECT_NEAR(p.wrench.fx, p.fx, tol);
        EXPECT_NEAR(p.wrench.fy, sigma * fn * std::sin(d) + p.fs * std::cos(d), tol) << p.slot;
        EXPECT_NEAR(p.wrench.fz, fn * std::cos(d) - sigma * p.fs * std::sin(d), tol) << p.slot;
        checked += p.fs != 0.0 && d > 0.2;  // a gauge corner's patch with its lateral force
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(WheelsetWrench, TheNormalForceHasNoMomentAboutTheAxleAndTheCentreSitsOnIt) {
  // A wheel's normals cross its axle, so a normal force has no moment about it, whatever the yaw
  // and roll: with the tangential forces off, M . e_axle = 0 up to the lever's offset between the
  // rail's contact point and the loaded wheel (the approach, some 0.1 mm, times the small yaw). A
  // contact point off its wheel's circle (a lead under yaw wrong by 1 mm gives 1e-3 fn n_y m) or a
  // normal turned by 1 mrad (0.46e-3 fn m) would show.
  // The flange at 6.5 mm is the strong case: its normal is 66 degrees from the vertical.
  // The wheel's centre is on the axle, 0.75 m (flange_back_distance / 2 + 70 mm) from the
  // wheelset's centre, at the loaded height.
  WheelsetContactOptions o;
  o.tangential = false;
  for (const WheelsetState& s : a22States()) {
    WheelsetContact c(WheelsetTrackData{}, steady(), o);
    const WheelsetResult r = c.step(s, 0.0);
    const Eigen::Vector3d e = axle(s.pose);
    for (const WheelResult* w : {&r.left, &r.right}) {
      ASSERT_EQ(w->status, WheelStatus::kOk) << w->message;
      const Eigen::Vector3d m(w->wrench.mx, w->wrench.my, w->wrench.mz);
      const double fn = std::hypot(w->wrench.fy, w->wrench.fz);
      EXPECT_LT(std::abs(m.dot(e)), 1e-5 * fn) << s.pose.y;
      const double sigma = w->side == WheelSide::kRight ? -1.0 : 1.0;  // the wheel's side of y
      const Eigen::Vector3d from_axle = w->centre - 0.75 * sigma * e;  // the wheelset's centre
      EXPECT_NEAR(from_axle.x(), 0.0, 1e-12);
      EXPECT_NEAR(from_axle.y(), s.pose.y, 1e-12);
      EXPECT_NEAR(from_axle.z(), 0.46, 1e-2);  // the touching height, within 10 mm of nominal
      // A tread contact lies about a wheel radius below the centre.
      for (const PatchResult& p : w->patches)
        EXPECT_NEAR((p.geometry.point - w->centre).z(), -p.geometry.rolling_radius, 2e-3) << p.slot;
    }
  }
}

TEST(WheelsetWrench, TheLeftWheelInTheMirroredStateIsTheRightOneMirrored) {
  // The mirror in the track's x-z plane keeps fx, fz and my, and turns fy, mx and mz over.
  for (const WheelsetState& s : a22States()) {
    WheelsetContact c(WheelsetTrackData{}, steady());
    const WheelResult right = c.step(s, 0.0).right;
    const WheelResult left = c.step(mirrored(s), 0.0).left;
    ASSERT_EQ(right.status, WheelStatus::kOk);
    ASSERT_EQ(left.status, WheelStatus::kOk);
    const TrackWrench &r = right.wrench, &l = left.wrench;
    const double f = 1e-4 * 1e4, m = f * 1.0;  // as the patches' forces agree (1e-4 fn), 1 m lever
    EXPECT_NEAR(l.fx, r.fx, f);
    EXPECT_NEAR(l.fy, -r.fy, f);
    EXPECT_NEAR(l.fz, r.fz, f);
    EXPECT_NEAR(l.mx, -r.mx, m);
    EXPECT_NEAR(l.my, r.my, m);
    EXPECT_NEAR(l.mz, -r.mz, m);
    EXPECT_NEAR(left.centre.x(), right.centre.x(), 1e-9);
    EXPECT_NEAR(left.centre.y(), -right.centre.y(), 1e-9);
    EXPECT_NEAR(left.centre.z(), right.centre.z(), 1e-9);
    EXPECT_GT(std::abs(r.mx), 100.0);  // nonzero, so the signs are checked
  }
}

TEST(WheelsetWrench, AWheelWithNoPatchHasZeroWrench) {
  WheelsetContact c(WheelsetTrackData{}, steady());
  WheelsetState s = a22States().front();
  s.fz_left = 0.0;
  WheelsetResult r = c.step(s, 0.0);
  EXPECT_EQ(r.left.status, WheelStatus::kNoLoad);
  for (double v : values(r.left.wrench)) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(r.left.centre, Eigen::Vector3d::Zero());
  ASSERT_EQ(r.right.status, WheelStatus::kOk);
  EXPECT_GT(r.right.wrench.fz, 0.0);
  // Invalid input: zero as well, never NaN.
  s.pose.yaw = std::numeric_limits<double>::quiet_NaN();
  r = c.step(s, 0.0);
  EXPECT_EQ(r.right.status, WheelStatus::kInvalidInput);
  for (double v : values(r.right.wrench)) EXPECT_EQ(v, 0.0);
}
