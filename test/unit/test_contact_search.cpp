// Wheelset and track data and the contact search, on the Manchester benchmark's case.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "a22_states.hpp"
#include "contact_search_helpers.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"

using namespace wheel_rail_contact;

TEST(ContactSearch, PlacesTheRailsByGauge) {
  const WheelsetTrackData d;
  const ContactSearch cs(d);
  for (WheelSide s : {WheelSide::kLeft, WheelSide::kRight}) {
    const double sign = s == WheelSide::kLeft ? 1.0 : -1.0;
    EXPECT_NEAR(cs.railTop(s).y(), 0.0, 1e-15);
    EXPECT_NEAR(cs.gaugePoint(s).y(), -0.014, 1e-9);
    EXPECT_NEAR(cs.gaugePoint(s).x(), sign * 0.7175, 1e-9);
    // The top of each rail lies outside its gauge point, toward the field.
    EXPECT_GT(sign * (cs.railTop(s).x() - cs.gaugePoint(s).x()), 0.02);
  }
}

TEST(ContactSearch, RefusesWhatValidateRefusesAndItsOwnOptionsByName) {
  WheelsetTrackData bad;
  bad.gauge_depth = -1.0;
  EXPECT_THROW(ContactSearch{bad}, std::invalid_argument);
  ContactSearchOptions o;
  o.sample_spacing = 0.0;
  try {
    ContactSearch cs(WheelsetTrackData(), o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample_spacing"), std::string::npos) << e.what();
  }
}

TEST(ContactSearch, A22RegimesTreadGaugeCornerFlange) {
  // The account of case on the right wheel: tread up to about 4.5 mm, the gauge
  // corner from about 5 mm, the flange from about 6.5 mm; the contact angle grows through both
  // jumps, and each jump is more than twice any step on the tread.
  // It prints the table doc/profiles.md shows.
  const ContactSearch cs{WheelsetTrackData()};
  double previous = -1.0, largest_tread_step = 0.0;
  std::printf(
      "  y_mm    zone  candidates  contact_angle  y_rail_mm  y_wheel_mm  radius_mm  lead_mm\n");
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kRight) continue;
    const WheelContactGeometry g = cs.search(WheelSide::kRight, a22Pose(c));
    const ContactCandidate& k = closest(g);
    std::printf("%6.1f  %6s  %10zu  %13.4f  %9.2f  %10.2f  %9.2f  %7.2f\n", c.y_mm,
                k.zone == ContactZone::kTread    ? "tread"
                : k.zone == ContactZone::kFlange ? "flange"
                                                 : "corner",
                g.candidates.size(), k.contact_angle, k.rail_file.x() * 1e3, k.wheel_file.x() * 1e3,
                k.rolling_radius * 1e3, k.lead * 1e3);
    const ContactZone expected = c.y_mm <= 4.5  ? ContactZone::kTread
                                 : c.y_mm < 6.5 ? ContactZone::kGaugeCorner
                                                : ContactZone::kFlange;
    EXPECT_EQ(static_cast<int>(k.zone), static_cast<int>(expected)) << "y = " << c.y_mm << " mm";
    if (c.y_mm <= 6.5) {
      EXPECT_GT(k.contact_angle, previous) << "y = " << c.y_mm << " mm";
      if (c.y_mm > 0.0 && c.y_mm <= 4.5)
        largest_tread_step = std::max(largest_tread_step, k.contact_angle - previous);
      if (c.y_mm == 5.0 || c.y_mm == 6.5) {
        EXPECT_GT(k.contact_angle - previous, 2.0 * largest_tread_step) << c.y_mm;
      }
      previous = k.contact_angle;
    }
    // The contact point on the rail is on its gauge side (the file's y < 0) and moves toward
    // the gauge face as the wheelset moves right; the rolling radius grows with it.
    EXPECT_LT(k.rail_file.x(), 0.0);
    EXPECT_NEAR(k.rolling_radius, 0.46 + k.wheel_file.y(), 1e-12);  // the file's z is down
  }
}

TEST(ContactSearch, A22TwoPatchesAtTheJumpToTheGaugeCorner) {
  // At 5 mm the tread and the gauge corner are both minima of the gap, so close in height that
  // a 10 kN wheel's elastic approach (some 0.05 mm) closes both: two patches at once.
  const ContactSearch cs{WheelsetTrackData()};
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kRight || c.y_mm != 5.0) continue;
    const WheelContactGeometry g = cs.search(WheelSide::kRight, a22Pose(c));
    ASSERT_EQ(g.candidates.size(), 2u);
    EXPECT_EQ(g.candidates[0].zone, ContactZone::kTread);  // field side first
    EXPECT_EQ(g.candidates[1].zone, ContactZone::kGaugeCorner);
    EXPECT_LT(std::abs(g.candidates[0].vertical_gap - g.candidates[1].vertical_gap), 0.05e-3);
    // With the wheelset lowered until the closer one overlaps by 0.05 mm, both overlap.
    WheelsetPose lowered = a22Pose(c);
    lowered.z -= closest(g).vertical_gap + 0.05e-3;
    const WheelContactGeometry h = cs.search(WheelSide::kRight, lowered);
    ASSERT_EQ(h.candidates.size(), 2u);
    EXPECT_LT(h.candidates[0].gap, 0.0);
    EXPECT_LT(h.candidates[1].gap, 0.0);
  }
}

TEST(ContactSearch, A22BenchmarksRollPutsBothWheelsOnTheirRails) {
  // The benchmark's roll angles come from its equilibrium with both wheels loaded: with them
  // both wheels must touch at the same height, to within the difference of their elastic
  // approaches (a tenth of a millimetre). The opposite roll does not: a check that the track,
  // the wheelset's placement and the axes' signs are the benchmark's.
  const ContactSearch cs{WheelsetTrackData()};
  double worst_flipped = 0.0;
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kRight) continue;
    const WheelsetPose p = a22Pose(c);
    const double right = closest(cs.search(WheelSide::kRight, p)).vertical_gap;
    const double left = closest(cs.search(WheelSide::kLeft, p)).vertical_gap;
    EXPECT_LT(std::abs(right - left), 0.1e-3) << "y = " << c.y_mm << " mm";
    WheelsetPose q = p;
    q.roll = -p.roll;
    const double right_q = closest(cs.search(WheelSide::kRight, q)).vertical_gap;
    const double left_q = closest(cs.search(WheelSide::kLeft, q)).vertical_gap;
    worst_flipped = std::max(worst_flipped, std::abs(right_q - left_q));
  }
  EXPECT_GT(worst_flipped, 1e-3);
}

TEST(ContactSearch, LeftWheelIsTheRightMirrored) {
  // Left profiles default to the right ones mirrored: the left wheel in the mirrored pose gives
  // the right wheel's contact, point for point. (The benchmark's "left" rows are not this: they
  // are the left wheel of the same wheelset state as the right rows.)
  const ContactSearch cs{WheelsetTrackData()};
  WheelsetTrackData given;
  given.wheel_left = Profile::standardWheel();
  given.rail_left = Profile::standardRail();
  const ContactSearch cs_given(given);
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kLeft) continue;
    const WheelsetPose p = a22Pose(c);
    const WheelContactGeometry r = cs.search(WheelSide::kRight, p);
    const WheelContactGeometry l = cs.search(WheelSide::kLeft, mirrored(p));
    const WheelContactGeometry lg = cs_given.search(WheelSide::kLeft, mirrored(p));
    ASSERT_EQ(r.candidates.size(), l.candidates.size()) << c.y_mm;
    ASSERT_EQ(lg.candidates.size(), l.candidates.size()) << c.y_mm;
    for (std::size_t k = 0; k < r.candidates.size(); ++k) {
      const ContactCandidate &a = r.candidates[k], &b = l.candidates[k], &bg = lg.candidates[k];
      EXPECT_NEAR(a.contact_angle, b.contact_angle, 1e-9);
      EXPECT_NEAR(a.vertical_gap, b.vertical_gap, 1e-9);
      EXPECT_NEAR(a.gap, b.gap, 1e-9);
      EXPECT_NEAR(a.rolling_radius, b.rolling_radius, 1e-9);
      EXPECT_NEAR(a.point.x(), b.point.x(), 1e-9);
      EXPECT_NEAR(a.point.y(), -b.point.y(), 1e-9);
      EXPECT_NEAR(a.point.z(), b.point.z(), 1e-9);
      EXPECT_NEAR((a.rail_file - b.rail_file).norm(), 0.0, 1e-9);
      EXPECT_NEAR((a.wheel_file - b.wheel_file).norm(), 0.0, 1e-9);
      EXPECT_NEAR(b.contact_angle, bg.contact_angle, 1e-12);
      EXPECT_NEAR(b.gap, bg.gap, 1e-12);
    }
  }
  // A left profile given apart is used: a left rail shifted 2 mm toward the field side moves
  // the left contact on the rail's file coordinates, not the right's.
  std::vector<Eigen::Vector2d> pts = Profile::standardRail()->points();
  for (auto& q : pts) q.x() -= 0.002;
  WheelsetTrackData shifted;
  shifted.rail_left = std::make_shared<const Profile>(
      Profile::fromPoints(pts, ProfileKind::kRail, "shifted UIC60"));
  const ContactSearch cs_shifted(shifted);
  const WheelsetPose centred;
  EXPECT_NEAR(closest(cs_shifted.search(WheelSide::kRight, centred)).contact_angle,
              closest(cs.search(WheelSide::kRight, centred)).contact_angle, 1e-12);
  // The gauge point moved with the profile, so the contact lies 2 mm further along the shifted
  // profile's y (its file coordinates are the profile frame's; the standard file's y is minus).
  EXPECT_NEAR(closest(cs_shifted.search(WheelSide::kLeft, centred)).rail_file.x() +
                  closest(cs.search(WheelSide::kLeft, centred)).rail_file.x(),
              -0.002, 1e-6);
}

TEST(ContactSearch, YawMovesTheContactAlongTheTrackAsFirstOrderTheorySays) {
  // The exact locus against the first-order shift -r tan(delta) sin(yaw) (right wheel): within a
  // few per cent on the tread and the flange, and ahead of the axle on the flange that the yaw
  // steers into the rail.
  const ContactSearch cs{WheelsetTrackData()};
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kRight || c.y_mm == 0.0) continue;
    const WheelsetPose p = a22Pose(c);
    const ContactCandidate k = closest(cs.search(WheelSide::kRight, p));
    const double first_order = -k.rolling_radius * std::tan(k.contact_angle) * std::sin(p.yaw);
    EXPECT_NEAR(k.lead, first_order, 0.05 * std::abs(first_order)) << "y = " << c.y_mm;
    if (k.zone == ContactZone::kFlange) {
      EXPECT_GT(k.lead, 0.0);
    }
  }
  // Without yaw there is no lead.
  EXPECT_EQ(closest(cs.search(WheelSide::kRight, WheelsetPose())).lead, 0.0);
}

TEST(ContactSearch, GapFunctionCurvesAsTheProfilesDo) {
  // Near its minimum the gap across a patch is a parabola whose curvature is the two profiles'
  // curvatures added (the Hertzian relative curvature in the lateral direction), taken from the
  // splines on their own: the gap function and the profiles' curvatures agree.
  ContactSearchOptions local;
  local.gap_window = 1e-8;  // with an overlap of 0.1 um: samples where the gap is below 0.1 um
  local.gap_reach = 1e-8;   // (not the default reach the normal problem needs)
  const ContactSearch cs(WheelsetTrackData(), local);
  for (const double y : {0.0, -2e-3, -5.5e-3}) {
    WheelsetPose p;
    p.y = y;
    const WheelContactGeometry g0 = cs.search(WheelSide::kRight, p);
    p.z = -closest(g0).vertical_gap - 1e-7;  // just touching: the gap function stays local
    const WheelContactGeometry g = cs.search(WheelSide::kRight, p);
    const ContactCandidate& k = closest(g);
    ASSERT_GE(k.gap_function.size(), 5u);
    const double kr = Profile::standardRail()->at(k.s_rail).curvature;
    const double kw = Profile::standardWheel()->at(k.s_wheel).curvature;
    // Least-squares parabola through the samples.
    Eigen::MatrixXd A(k.gap_function.size(), 3);
    Eigen::VectorXd b(k.gap_function.size());
    for (std::size_t i = 0; i < k.gap_function.size(); ++i) {
      const double e = k.gap_function[i].eta;
      A.row(i) << 1.0, e, e * e;
      b[i] = k.gap_function[i].gap;
    }
    const Eigen::Vector3d fit = A.colPivHouseholderQr().solve(b);
    EXPECT_NEAR(2.0 * fit[2], kr + kw, 0.05 * std::abs(kr + kw)) << "y = " << y;
    EXPECT_NEAR(fit[0], k.gap, 1e-9);
    EXPECT_GT(k.gap_function.front().gap, k.gap);
    EXPECT_GT(k.gap_function.back().gap, k.gap);
    EXPECT_LT(k.gap_function.front().eta, 0.0);
    EXPECT_GT(k.gap_function.back().eta, 0.0);
  }
}

TEST(ContactSearch, RailInclinationTurnsAnUprightRailIntoTheInclinedOne) {
  // The standard UIC60 turned upright again, then inclined by rail_inclination = 1/40, must give
  // the contact the built-in inclined profile gives.
  const double a = std::atan(1.0 / 40.0);
  std::vector<Eigen::Vector2d> pts = Profile::standardRail()->points();
  for (auto& q : pts)
    q = Eigen::Vector2d(std::cos(a) * q.x() - std::sin(a) * q.y(),
                        std::sin(a) * q.x() + std::cos(a) * q.y());
  WheelsetTrackData upright;
  upright.rail_right = std::make_shared<const Profile>(
      Profile::fromPoints(pts, ProfileKind::kRail, "UIC60 upright"));
  upright.rail_inclination = 1.0 / 40.0;
  const ContactSearch built_in{WheelsetTrackData()}, turned(upright);
  for (const A22State& c : a22States()) {
    if (c.side != WheelSide::kRight) continue;
    const ContactCandidate& x = closest(built_in.search(WheelSide::kRight, a22Pose(c)));
    const ContactCandidate& y = closest(turned.search(WheelSide::kRight, a22Pose(c)));
    EXPECT_NEAR(x.contact_angle, y.contact_angle, 1e-6) << c.y_mm;
    EXPECT_NEAR(x.vertical_gap, y.vertical_gap, 1e-8) << c.y_mm;
    EXPECT_NEAR(x.point.y(), y.point.y(), 1e-6) << c.y_mm;
  }
}

TEST(ContactSearch, ThePoseOfAnIsolatedMissFindsWhatPosesANanometreAsideFind) {
  // A pose (right wheel on its flange) where one sample of the vertical gap came out 1.8 mm too
  // low, the rail's crossing of that sample's lateral position not converged: the false sample
  // became the smallest gap and the true minimum, 27 um below the one refined next to the false
  // sample, fell out of the candidate window. Poses 1 and 5 nm aside never saw it.
  const ContactSearch cs{WheelsetTrackData()};
  WheelsetPose p;
  p.y = -0.0079864800592553947;
  p.yaw = 0.024494897427831779;
  p.roll = -0.0075;
  const WheelContactGeometry g = cs.search(WheelSide::kRight, p);
  ASSERT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
  const ContactCandidate& c = g.candidates.at(g.closest);
  EXPECT_FALSE(c.gap_function.empty());
  for (double d : {-5e-9, -1e-9, 1e-9, 5e-9}) {
    WheelsetPose q = p;
    q.y += d;
    const WheelContactGeometry h = cs.search(WheelSide::kRight, q);
    ASSERT_EQ(h.status, ContactSearchStatus::kOk) << h.message;
    ASSERT_EQ(h.candidates.size(), g.candidates.size());
    const ContactCandidate& k = h.candidates.at(h.closest);
    // A nanometre of y moves the flange's vertical gap by about tan(delta) nm.
    EXPECT_NEAR(c.vertical_gap, k.vertical_gap, 2e-8) << d;
    EXPECT_NEAR(c.contact_angle, k.contact_angle, 1e-5) << d;
    EXPECT_NEAR(c.s_wheel, k.s_wheel, 1e-7) << d;
  }
}

TEST(ContactSearch, EveryCandidateOfALoadedFlangeHasAGapFunction) {
  // Flange contact about the flank's steepest point (some 1.22 rad), yawed, each pose lowered
  // until the closest candidate overlaps by 50 um. There the gap function's edge toward the field
  // side lies where the wheel's curve turns away from the contact plane; a sample close to it,
  // reached by Newton from the sample before, could fail and drop the whole gap function (97 of
  // 3950 candidates of a wider sweep), which the normal problem cannot do without.
  const ContactSearch cs{WheelsetTrackData()};
  const double a0 = -0.5 * cs.data().gauge, r0 = cs.data().nominal_radius;
  int candidates = 0;
  for (double Y = -7.4e-3; Y <= -6.0e-3; Y += 0.1e-3)
    for (double yaw : {0.02, 0.0245})
      for (double roll : {-0.005, 0.005}) {
        WheelsetPose p;
        p.yaw = yaw;
        p.roll = roll;
        p.y = Y - a0 * (std::cos(yaw) * std::cos(roll) - 1.0) - r0 * std::sin(roll) * std::cos(yaw);
        WheelContactGeometry g = cs.search(WheelSide::kRight, p);
        ASSERT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
        p.z -= g.candidates[g.closest].vertical_gap + 50e-6;
        g = cs.search(WheelSide::kRight, p);
        ASSERT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
        for (const ContactCandidate& c : g.candidates) {
          ++candidates;
          ASSERT_EQ(static_cast<int>(c.gap_function.size()), cs.options().gap_samples)
              << "Y " << Y << " yaw " << yaw << " roll " << roll << " angle " << c.contact_angle;
          // Uniform samples, the candidate's gap at eta = 0 within the stretch.
          const double de = c.gap_function[1].eta - c.gap_function[0].eta;
          EXPECT_GT(de, 0.0);
          EXPECT_NEAR(c.gap_function.back().eta - c.gap_function.front().eta,
                      de * (c.gap_function.size() - 1), 1e-9);
          EXPECT_LE(c.gap_function.front().eta, 0.0);
          EXPECT_GE(c.gap_function.back().eta, 0.0);
        }
      }
  EXPECT_GT(candidates, 60);
}

TEST(ContactSearch, BadPosesGiveAStatusNeverAThrowOrNaN) {
  const ContactSearch cs{WheelsetTrackData()};
  WheelsetPose p;
  p.yaw = NAN;
  WheelContactGeometry g = cs.search(WheelSide::kLeft, p);
  EXPECT_EQ(g.status, ContactSearchStatus::kInvalidInput);
  EXPECT_NE(g.message.find("yaw"), std::string::npos) << g.message;
  EXPECT_TRUE(g.candidates.empty());
  p = WheelsetPose();
  p.roll = 0.2;
  EXPECT_EQ(cs.search(WheelSide::kLeft, p).status, ContactSearchStatus::kInvalidInput);
  // A rail cut 3 mm below its top: the wheel's smallest gap is where the cut profile ends, not a
  // contact; and a wheelset 200 mm to the left has its right wheel beside its rail.
  std::vector<Eigen::Vector2d> crown;
  for (const Eigen::Vector2d& q : Profile::standardRail()->points())
    if (q.y() > -0.003) crown.push_back(q);
  WheelsetTrackData cut;
  cut.gauge_depth = 0.002;
  cut.rail_right =
      std::make_shared<const Profile>(Profile::fromPoints(crown, ProfileKind::kRail, "crown"));
  ContactSearchOptions wide;
  wide.max_abs_y = 0.3;
  const ContactSearch cs_cut(cut, wide);
  p = WheelsetPose();
  p.y = -0.008;
  g = cs_cut.search(WheelSide::kRight, p);
  EXPECT_EQ(g.status, ContactSearchStatus::kOutOfRange);
  EXPECT_NE(g.message.find("end of a profile"), std::string::npos) << g.message;
  EXPECT_TRUE(g.candidates.empty());
  p.y = 0.2;
  g = cs_cut.search(WheelSide::kRight, p);
  EXPECT_EQ(g.status, ContactSearchStatus::kOutOfRange);
  EXPECT_NE(g.message.find("not above its rail"), std::string::npos) << g.message;
  // Every value of an ordinary search is finite.
  p = WheelsetPose();
  p.y = -0.003;
  p.yaw = 0.01;
  g = cs.search(WheelSide::kRight, p);
  ASSERT_EQ(g.status, ContactSearchStatus::kOk);
  for (const ContactCandidate& k : g.candidates) {
    EXPECT_TRUE(std::isfinite(k.gap) && std::isfinite(k.contact_angle) &&
                std::isfinite(k.rolling_radius) && k.point.allFinite() && std::isfinite(k.lead));
    for (const GapSample& s : k.gap_function)
      EXPECT_TRUE(std::isfinite(s.eta) && std::isfinite(s.gap));
  }
}
