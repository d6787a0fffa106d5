// WheelsetContact's forces in track axes: each patch's wrench (PatchResult::wrench) and each
// wheel's (WheelResult::wrench) about the wheel's centre, on the Manchester benchmark's case
// (S1002 on UIC60 1:40, the built-in profiles).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../a22_wheelset_states.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

using namespace wheel_rail_contact;

namespace {

using a22_wheelset::a22;
using a22_wheelset::mirrored;

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
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
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
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
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
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
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
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
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
  WheelsetState s = a22_wheelset::fourStates().front();
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

// ---- the load balance with the tangential forces' vertical components ----

TEST(WheelLoadTangential, TheWholeForcesVerticalComponentsCarryTheLoad) {
  // solveWheelLoad's tangential_vertical t_i: sum_i fn_i (n_z,i + t_i) = load.
  const ContactSearch search{WheelsetTrackData{}};
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
    WheelsetPose pose = s.pose;
    WheelContactGeometry g = search.search(WheelSide::kRight, pose);
    ASSERT_EQ(g.status, ContactSearchStatus::kOk);
    pose.z -= g.candidates[g.closest].vertical_gap;  // at first touch
    g = search.search(WheelSide::kRight, pose);
    const ContactParameters p;
    const NormalOptions o;
    const WheelNormal plain = solveWheelLoad(g, 1e4, p.G, p.nu, o);
    ASSERT_EQ(plain.status, NormalStatus::kOk) << plain.message;
    // Each patch in lateral full slip toward the field side: the friction holds the wheel up.
    std::vector<double> t;
    for (const ContactCandidate& c : g.candidates) t.push_back(p.mu * std::abs(c.normal.x()));
    const WheelNormal lifted = solveWheelLoad(g, 1e4, p.G, p.nu, o, t);
    ASSERT_EQ(lifted.status, NormalStatus::kOk) << lifted.message;
    double sum = 0.0, fn_plain = 0.0, fn_lifted = 0.0;
    for (size_t i = 0; i < g.candidates.size(); ++i) {
      sum += lifted.patches[i].fn * (g.candidates[i].normal.y() + t[i]);
      fn_plain += plain.patches[i].fn;
      fn_lifted += lifted.patches[i].fn;
    }
    EXPECT_NEAR(sum, 1e4, 2.0 * o.load_tolerance * 1e4) << s.pose.y;
    EXPECT_LT(fn_lifted, fn_plain);  // less normal force for the same load
    EXPECT_LT(lifted.vertical_approach, plain.vertical_approach);
    // An empty vector and zeros are the normal forces' balance itself.
    const WheelNormal zero =
        solveWheelLoad(g, 1e4, p.G, p.nu, o, std::vector<double>(g.candidates.size(), 0.0));
    EXPECT_EQ(zero.vertical_approach, plain.vertical_approach);

    // No balance: a patch whose whole force has no upward component; wrong sizes, NaN.
    for (int k = 0; k < 3; ++k) {
      std::vector<double> bad = t;
      if (k == 0) bad.back() = -g.candidates.back().normal.y();
      if (k == 1) bad.push_back(0.0);
      if (k == 2) bad.front() = std::numeric_limits<double>::quiet_NaN();
      const WheelNormal n = solveWheelLoad(g, 1e4, p.G, p.nu, o, bad);
      EXPECT_EQ(n.status, NormalStatus::kInvalidInput) << k;
      EXPECT_NE(n.message.find("tangential_vertical"), std::string::npos) << n.message;
      for (const NormalPatch& q : n.patches) EXPECT_EQ(q.fn, 0.0);
    }
  }
}

namespace {

WheelsetContactOptions wholeForce() {
  WheelsetContactOptions o;
  o.whole_force_balance = true;
  return o;
}

}  // namespace

TEST(WheelsetBalance, EachStepTakesItsSlotsPreviousTractionRatio) {
  // The first step of a patch has no previous ratio: the normal forces' balance. Each later step
  // balances sum_i fn_i (n_z,i - r_i n_y,i) = load with r_i the slot's previous fs / fn.
  // At y = 0 the two tread candidates merge into the first one's patch; 0.3 mm to the right into
  // the second's, which takes the slot "tread" although it is the second tread candidate.
  const double tolerance = NormalOptions{}.load_tolerance;
  std::vector<WheelsetState> states = a22_wheelset::fourStates();
  states.push_back(a22(0.0, 0.0, 0.0, -4.34812));
  states.push_back(a22(0.3, 0.0, 0.0, -4.34812));
  for (const WheelsetState& s : states) {
    WheelsetContact plain(WheelsetTrackData{}, steady());
    WheelsetContact whole(WheelsetTrackData{}, steady(), wholeForce());
    const WheelsetResult p0 = plain.step(s, 0.0);
    WheelsetResult before = whole.step(s, 0.0);
    for (const WheelResult* w : {&before.left, &before.right}) {
      const WheelResult& q = w->side == WheelSide::kLeft ? p0.left : p0.right;
      ASSERT_EQ(w->patches.size(), q.patches.size());
      for (size_t i = 0; i < q.patches.size(); ++i)
        EXPECT_EQ(w->patches[i].normal.fn, q.patches[i].normal.fn);
    }
    for (int k = 0; k < 2; ++k) {
      const WheelsetResult r = whole.step(s, 0.0);
      for (const WheelResult* w : {&r.left, &r.right}) {
        const WheelResult& b = w->side == WheelSide::kLeft ? before.left : before.right;
        ASSERT_EQ(w->status, WheelStatus::kOk) << w->message;
        ASSERT_EQ(w->patches.size(), b.patches.size());
        double sum = 0.0;
        for (size_t i = 0; i < w->patches.size(); ++i) {
          const PatchResult& p = w->patches[i];
          const double ratio = b.patches[i].fs / b.patches[i].normal.fn;
          sum += p.normal.fn * (p.geometry.normal.y() - ratio * p.geometry.normal.x());
        }
        EXPECT_NEAR(sum, 1e4, 2.0 * tolerance * 1e4) << s.pose.y << " step " << k;
      }
      before = r;
    }
  }
}

TEST(WheelsetBalance, SettledTheWrenchsVerticalForceIsTheLoad) {
  // A steady evaluation: the whole forces' vertical components add up to the load, and the
  // normal forces' do not (the tangential share, up to 1 kN on the gauge corner at 5.5 mm).
  for (const WheelsetState& s : a22_wheelset::fourStates()) {
    WheelsetContact whole(WheelsetTrackData{}, steady(), wholeForce());
    const WheelsetResult r = whole.settle(s, 0.0, 1e-6);
    WheelsetContact plain(WheelsetTrackData{}, steady());
    const WheelsetResult q = plain.step(s, 0.0);
    for (const WheelResult* w : {&r.left, &r.right}) {
      ASSERT_EQ(w->status, WheelStatus::kOk) << w->message;
      EXPECT_EQ(w->message.find("not settled"), std::string::npos) << w->message;
      EXPECT_NEAR(w->wrench.fz, 1e4, 1e-4 * 1e4) << s.pose.y;
      for (double v : values(w->wrench)) EXPECT_TRUE(std::isfinite(v));
      const WheelResult& n = w->side == WheelSide::kLeft ? q.left : q.right;
      // The plain balance's fz is off by the tangential share wherever there is one.
      double share = 0.0;
      for (const PatchResult& p : n.patches) share -= p.fs * p.geometry.normal.x();
      if (std::abs(share) > 10.0) {
        EXPECT_GT(std::abs(n.wrench.fz - 1e4), 0.5 * std::abs(share)) << s.pose.y;
      }
    }
  }
  // Bad settle arguments: both wheels refused.
  WheelsetContact c(WheelsetTrackData{}, steady(), wholeForce());
  const WheelsetResult bad = c.settle(a22_wheelset::fourStates().front(), 0.0, 0.0);
  EXPECT_EQ(bad.left.status, WheelStatus::kInvalidInput);
  EXPECT_EQ(bad.right.status, WheelStatus::kInvalidInput);
  EXPECT_EQ(bad.left.side, WheelSide::kLeft);
}

TEST(WheelsetBalance, WithNoBalanceTheNormalForcesCarryTheLoadSayingSo) {
  // At mu = 5 a gauge corner (delta 0.34 rad) dragged outwards in full slip has fs = 5 fn, whose
  // vertical component pulls the wheel down by more than fn cos(delta) pushes it up: no balance.
  // The normal forces alone carry the load that step; the wheel says so; nothing NaN.
  ContactParameters p = steady();
  p.mu = 5.0;
  WheelsetState s = a22_wheelset::fourStates()[2];  // 5.5 mm: one patch, the gauge corner
  s.motion.vy = -0.4;                               // eta about -0.2: the wheel slides to the right
  WheelsetContact whole(WheelsetTrackData{}, p, wholeForce());
  WheelsetContact plain(WheelsetTrackData{}, p);
  whole.step(s, 0.0);
  const WheelResult r = whole.step(s, 0.0).right;
  const WheelResult q = plain.step(s, 0.0).right;
  ASSERT_EQ(r.status, WheelStatus::kOk) << r.message;
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].zone, ContactZone::kGaugeCorner);
  EXPECT_GT(
      r.patches[0].fs / r.patches[0].normal.fn * std::tan(r.patches[0].geometry.contact_angle),
      1.0);  // the case is what it says
  EXPECT_NE(r.message.find("no balance"), std::string::npos) << r.message;
  EXPECT_EQ(r.patches[0].normal.fn, q.patches[0].normal.fn);
  for (double v : values(r.wrench)) EXPECT_TRUE(std::isfinite(v));
  // A configuration without tangential forces cannot balance them.
  WheelsetContactOptions o = wholeForce();
  o.tangential = false;
  try {
    WheelsetContact c(WheelsetTrackData{}, p, o);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("whole_force_balance"), std::string::npos);
  }
}
