// The contact table against the direct contact search it tabulates: the same candidates and, to
// within bounds that follow from the table's steps, the same geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/profiles/contact_table.hpp"

using namespace wheel_rail_contact;

namespace {

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/test/data/profiles/";

/// The benchmark's right-wheel states in our axes (doc/profiles.md: y and yaw change sign,
/// roll does not): y [m], yaw, roll.
struct State {
  double y, yaw, roll;
};
std::vector<State> a22() {
  std::ifstream in(kDataDir + "a22_cases.csv");
  std::vector<State> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("right,", 0) != 0) continue;
    std::istringstream ls(line);
    std::string f[5];
    for (auto& s : f) std::getline(ls, s, ',');
    out.push_back({-std::stod(f[2]) * 1e-3, -std::stod(f[3]), std::stod(f[4])});
  }
  EXPECT_EQ(out.size(), 21u);
  return out;
}

/// The benchmark's roll at our lateral displacement y (its equilibrium, both wheels on their
/// rails), linear between its cases and beyond 10 mm, odd in y.
double benchmarkRoll(const std::vector<State>& s, double y) {
  const double a = std::abs(y);
  std::size_t k = 0;
  while (k + 2 < s.size() && -s[k + 1].y < a) ++k;
  const double t = (a - (-s[k].y)) / (-s[k + 1].y - (-s[k].y));
  const double r = s[k].roll + t * (s[k + 1].roll - s[k].roll);
  return y < 0.0 ? r : -r;
}

/// The default table, built once for the tests that use it.
const ContactTable& defaultTable() {
  static const ContactTable table{ContactSearch{WheelsetTrackData()}};
  return table;
}

/// The pose lowered until its wheel's closest candidate overlaps by `overlap`: a loaded wheel.
WheelsetPose loaded(const ContactSearch& cs, WheelSide side, WheelsetPose p, double overlap) {
  const WheelContactGeometry g = cs.search(side, p);
  if (g.status == ContactSearchStatus::kOk) p.z -= g.candidates[g.closest].vertical_gap + overlap;
  return p;
}

/// Largest difference of two gap functions where both are sampled: the table's, linear between
/// its samples, at the search's.
double gapFunctionError(const std::vector<GapSample>& direct, const std::vector<GapSample>& table) {
  if (direct.size() < 2 || table.size() < 2) return 0.0;
  double worst = 0.0;
  const double e0 = table.front().eta, e1 = table.back().eta;
  for (const GapSample& s : direct) {
    if (s.eta < e0 || s.eta > e1) continue;
    double u = (s.eta - e0) / (e1 - e0) * (table.size() - 1);
    const std::size_t j = std::min<std::size_t>(static_cast<std::size_t>(u), table.size() - 2);
    u -= j;
    worst =
        std::max(worst, std::abs(s.gap - (table[j].gap + u * (table[j + 1].gap - table[j].gap))));
  }
  return worst;
}

/// Bounds by the zone of the closest candidate (tread; gauge corner and flange).
struct Bounds {
  double point_y, point_z, angle, radius, gap, vertical_gap, gap_function, lead;
};

struct Errors {
  double e[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int n = 0;
  /// Adds one pose's errors; false, naming them, where one exceeds its bound.
  std::string add(const ContactCandidate& d, const ContactCandidate& t, const Bounds& b) {
    const double v[8] = {d.point.y() - t.point.y(),
                         d.point.z() - t.point.z(),
                         d.contact_angle - t.contact_angle,
                         d.rolling_radius - t.rolling_radius,
                         d.gap - t.gap,
                         d.vertical_gap - t.vertical_gap,
                         gapFunctionError(d.gap_function, t.gap_function),
                         d.lead - t.lead};
    const double bound[8] = {b.point_y, b.point_z,      b.angle,        b.radius,
                             b.gap,     b.vertical_gap, b.gap_function, b.lead};
    const char* names[8] = {"point y", "point z",      "contact angle", "rolling radius",
                            "gap",     "vertical gap", "gap function",  "lead"};
    std::string beyond;
    for (int k = 0; k < 8; ++k) {
      e[k] = std::max(e[k], std::abs(v[k]));
      if (std::abs(v[k]) > bound[k])
        beyond += std::string(names[k]) + " " + std::to_string(v[k]) + "; ";
    }
    ++n;
    return beyond;
  }
  void print(const char* what) const {
    std::printf(
        "  %-12s %4d poses: point y %.4f mm, z %.4f mm, angle %.2f mrad, radius %.4f mm, gap %.2f "
        "um, vertical gap %.2f um, gap function %.2f um, lead %.3f mm\n",
        what, n, e[0] * 1e3, e[1] * 1e3, e[2] * 1e3, e[3] * 1e3, e[4] * 1e6, e[5] * 1e6, e[6] * 1e6,
        e[7] * 1e3);
  }
};

// What the default steps give (0.2 mm of the wheel's lateral displacement, four yaw nodes evenly
// spaced in yaw^2 up to 30 mrad, 2.5 mrad of roll; doc/profiles.md). Linear interpolation over a
// step h errs by up to h^2 / 8 times the quantity's second derivative, so the bounds follow the
// profiles: on the tread the contact moves smoothly, and the bounds are about twice the errors
// these poses show. On the gauge corner and the flange the contact angle changes fast near the
// flank's steepest point, and the vertical gap follows the flange's slope (tan(delta) ~ 2.5) and
// the yaw's lift of the contact point (the lead squared over the wheel's diameter, a millimetre
// at 25 mrad): the same steps leave tens of times more there.
const Bounds kTread{0.05e-3, 0.005e-3, 0.5e-3, 0.005e-3, 1e-6, 1e-6, 1.5e-6, 0.005e-3};
const Bounds kFlange{0.05e-3, 0.03e-3, 4e-3, 0.05e-3, 3e-6, 8e-6, 6e-6, 0.2e-3};

/// A pose is at a jump of the closest candidate when the direct search, a lateral step to either
/// side, finds it on another part of the profile or with a contact angle 0.05 rad apart.
bool atJump(const ContactSearch& cs, WheelSide side, const WheelsetPose& p, double step,
            double match) {
  const WheelContactGeometry g = cs.search(side, p);
  for (double d : {-step, step}) {
    WheelsetPose q = p;
    q.y += d;
    const WheelContactGeometry h = cs.search(side, q);
    if (h.status != ContactSearchStatus::kOk) return true;
    const ContactCandidate &a = g.candidates[g.closest], &b = h.candidates[h.closest];
    if (std::abs(a.s_wheel - b.s_wheel) > match ||
        std::abs(a.contact_angle - b.contact_angle) > 0.05)
      return true;
  }
  return false;
}

/// Compares table and search on `poses` (each wheel, lowered to overlap by `overlap`):
/// away from jumps the closest candidate is the same one, every direct candidate within 0.1 mm
/// of the closest (those a load can bring into contact) is in the table's set, and the errors
/// are within the bounds; at a jump the table's closest candidate is the direct search's a
/// lateral step to one side or the other.
void compare(const std::vector<WheelsetPose>& poses, const char* what, double overlap = 50e-6,
             double gap_function_bound = 0.0) {
  const ContactTable& table = defaultTable();
  const ContactSearch& cs = table.contactSearch();
  const double step = table.options().lateral_step, match = table.options().match_distance;
  Errors tread, flange;
  int jumps = 0;
  for (const WheelsetPose& p0 : poses)
    for (WheelSide side : {WheelSide::kRight, WheelSide::kLeft}) {
      const WheelsetPose p = loaded(cs, side, p0, overlap);
      const WheelContactGeometry d = cs.search(side, p);
      const WheelContactGeometry t = table.search(side, p);
      ASSERT_EQ(d.status, ContactSearchStatus::kOk) << d.message;
      ASSERT_EQ(t.status, ContactSearchStatus::kOk) << t.message;
      const ContactCandidate &dc = d.candidates[d.closest], &tc = t.candidates[t.closest];
      if (atJump(cs, side, p, step, match)) {
        ++jumps;
        bool one_side = false;
        for (double dy : {-step, step}) {
          WheelsetPose q = p;
          q.y += dy;
          const WheelContactGeometry h = cs.search(side, q);
          one_side = one_side || std::abs(h.candidates[h.closest].s_wheel - tc.s_wheel) < match;
        }
        EXPECT_TRUE(one_side) << what << " y " << p.y << " yaw " << p.yaw << " roll " << p.roll;
        continue;
      }
      ASSERT_LT(std::abs(dc.s_wheel - tc.s_wheel), match)
          << what << " y " << p.y << " yaw " << p.yaw << " roll " << p.roll;
      EXPECT_EQ(dc.zone, tc.zone) << what << " y " << p.y;
      for (const ContactCandidate& k : d.candidates) {
        if (k.vertical_gap > dc.vertical_gap + 0.1e-3) continue;
        bool found = false;
        for (const ContactCandidate& l : t.candidates)
          found = found || std::abs(k.s_wheel - l.s_wheel) < match;
        EXPECT_TRUE(found) << what << " y " << p.y << " yaw " << p.yaw << " roll " << p.roll;
      }
      const bool on_tread = dc.zone == ContactZone::kTread;
      const std::string beyond =
          (on_tread ? tread : flange).add(dc, tc, on_tread ? kTread : kFlange);
      EXPECT_TRUE(beyond.empty()) << what << " y " << p.y << " yaw " << p.yaw << " roll " << p.roll
                                  << " z " << p.z << (side == WheelSide::kLeft ? " left" : " right")
                                  << ": " << beyond << " angle " << dc.contact_angle;
    }
  std::printf("  %s: %d wheel poses at a jump\n", what, jumps);
  tread.print("tread");
  flange.print("corner/flange");
}

}  // namespace

TEST(ContactTable, RefusesBadOptionsByName) {
  const ContactSearch cs{WheelsetTrackData()};
  ContactTableOptions o;
  o.lateral_step = 0.0;
  try {
    ContactTable t(cs, o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lateral_step"), std::string::npos) << e.what();
  }
  o = ContactTableOptions();
  o.max_abs_yaw = 1.0;  // beyond the search's own limit
  EXPECT_THROW(ContactTable(cs, o), std::invalid_argument);
  o = ContactTableOptions();
  o.gap_samples = 1;
  EXPECT_THROW(ContactTable(cs, o), std::invalid_argument);
}

TEST(ContactTable, A22CasesAsTheSearch) {
  // The benchmark's 21 states and their mirror images, both wheels.
  std::vector<WheelsetPose> poses;
  for (const State& s : a22())
    for (double sign : {1.0, -1.0}) {
      WheelsetPose p;
      p.y = sign * s.y;
      p.yaw = sign * s.yaw;
      p.roll = sign * s.roll;
      poses.push_back(p);
    }
  compare(poses, "A-2.2");
  // Touching, and at the table's max_overlap, where the gap function's interpolation in the
  // height has the farthest to go and the bound on it is wider.
  compare(poses, "A-2.2 touching", 0.0);
  compare(poses, "A-2.2 at 0.1 mm", 0.1e-3, 3e-6);
}

TEST(ContactTable, RandomPosesAsTheSearch) {
  // y in [-12, 12] mm, yaw in [-25, 25] mrad, the benchmark's roll for y.
  const std::vector<State> s = a22();
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<WheelsetPose> poses(150);
  for (WheelsetPose& p : poses) {
    p.y = 12e-3 * u(rng);
    p.yaw = 25e-3 * u(rng);
    p.roll = benchmarkRoll(s, p.y);
  }
  compare(poses, "random");
}

TEST(ContactTable, AtItsNodesTheSearchItself) {
  // At a node (the wheel's lateral displacement, yaw and roll on the grid; any height) the table
  // gives the search's numbers but for the rounding of the gap function's samples.
  const ContactTable& table = defaultTable();
  const ContactSearch& cs = table.contactSearch();
  const double a0 = -0.5 * cs.data().gauge, r0 = cs.data().nominal_radius;
  // Nodes of the default table (yaw's evenly spaced in yaw^2).
  const double Y = -6e-3, yaw = table.options().max_abs_yaw * std::sqrt(2.0 / 3.0), roll = -5e-3;
  WheelsetPose p;
  p.yaw = yaw;
  p.roll = roll;
  p.y = Y - a0 * (std::cos(yaw) * std::cos(roll) - 1.0) - r0 * std::sin(roll) * std::cos(yaw);
  p = loaded(cs, WheelSide::kRight, p, 30e-6);
  const WheelContactGeometry d = cs.search(WheelSide::kRight, p);
  const WheelContactGeometry t = table.search(WheelSide::kRight, p);
  ASSERT_EQ(d.candidates.size(), t.candidates.size());
  EXPECT_EQ(d.closest, t.closest);
  for (std::size_t k = 0; k < d.candidates.size(); ++k) {
    const ContactCandidate &a = d.candidates[k], &b = t.candidates[k];
    EXPECT_EQ(a.zone, b.zone);
    EXPECT_NEAR(a.contact_angle, b.contact_angle, 1e-9);
    EXPECT_NEAR((a.point - b.point).norm(), 0.0, 1e-9);
    EXPECT_NEAR(a.lead, b.lead, 1e-9);
    EXPECT_NEAR(a.vertical_gap, b.vertical_gap, 1e-9);
    // The gap at this height from the two tabulated heights, linearly.
    EXPECT_NEAR(a.gap, b.gap, 0.2e-6);
    EXPECT_NEAR((a.normal - b.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR((a.rail_file - b.rail_file).norm(), 0.0, 1e-9);
    EXPECT_NEAR((a.wheel_file - b.wheel_file).norm(), 0.0, 1e-9);
    EXPECT_NEAR(a.rolling_radius, b.rolling_radius, 1e-9);
    ASSERT_EQ(a.gap_function.size(), b.gap_function.size());
    // Where a ridge to the neighbouring candidate ends it, the search's gap function ends on its
    // 0.1 mm march; elsewhere where the gap reaches its level.
    EXPECT_NEAR(a.gap_function.front().eta, b.gap_function.front().eta, 0.15e-3);
    EXPECT_NEAR(a.gap_function.back().eta, b.gap_function.back().eta, 0.15e-3);
    EXPECT_LT(gapFunctionError(a.gap_function, b.gap_function), 0.3e-6);
  }
}

TEST(ContactTable, BeyondItsRangeTheSearchOrAStatus) {
  const ContactSearch cs{WheelsetTrackData()};
  ContactTableOptions o;
  o.max_abs_lateral = 2e-3;
  o.max_abs_yaw = 0.01;
  o.max_abs_roll = 2.5e-3;
  const ContactTable by_search(cs, o);
  o.beyond = ContactTableOptions::Beyond::kRefuse;
  const ContactTable refusing(cs, o);
  WheelsetPose far;
  far.y = -8e-3;
  far.yaw = -0.005;
  const WheelContactGeometry d = cs.search(WheelSide::kRight, far);
  const WheelContactGeometry s = by_search.search(WheelSide::kRight, far);
  ASSERT_EQ(s.status, ContactSearchStatus::kOk);
  ASSERT_EQ(s.candidates.size(), d.candidates.size());
  EXPECT_EQ(s.candidates[s.closest].contact_angle, d.candidates[d.closest].contact_angle);
  const WheelContactGeometry r = refusing.search(WheelSide::kRight, far);
  EXPECT_EQ(r.status, ContactSearchStatus::kOutOfRange);
  EXPECT_NE(r.message.find("contact table"), std::string::npos) << r.message;
  EXPECT_TRUE(r.candidates.empty());
  // A pose the search refuses is refused with its status and message, never a NaN.
  WheelsetPose bad;
  bad.yaw = std::nan("");
  for (const ContactTable* t : {&by_search, &refusing}) {
    const WheelContactGeometry b = t->search(WheelSide::kLeft, bad);
    EXPECT_EQ(b.status, ContactSearchStatus::kInvalidInput);
    EXPECT_NE(b.message.find("yaw"), std::string::npos) << b.message;
  }
}

TEST(ContactTable, LeftWheelSharesTheRightTableWhenMirrored) {
  // Mirrored left profiles: one table serves both wheels. Left profiles given apart (here copies
  // of the right ones): a table of their own, with the same answers.
  ContactTableOptions o;
  o.max_abs_lateral = 3e-3;
  o.max_abs_yaw = 0.01;
  o.max_abs_roll = 2.5e-3;
  const ContactTable mirrored(ContactSearch{WheelsetTrackData()}, o);
  WheelsetTrackData given;
  given.wheel_left = std::make_shared<const Profile>(*Profile::standardWheel());
  given.rail_left = std::make_shared<const Profile>(*Profile::standardRail());
  const ContactTable own(ContactSearch{given}, o);
  EXPECT_EQ(mirrored.tables(), 1);
  EXPECT_EQ(own.tables(), 2);
  EXPECT_GT(own.bytes(), mirrored.bytes());
  WheelsetPose p;
  p.y = 1.3e-3;
  p.yaw = 0.004;
  p.roll = 1e-4;
  const WheelContactGeometry a = mirrored.search(WheelSide::kLeft, p);
  const WheelContactGeometry b = own.search(WheelSide::kLeft, p);
  ASSERT_EQ(a.status, ContactSearchStatus::kOk);
  ASSERT_EQ(a.candidates.size(), b.candidates.size());
  for (std::size_t k = 0; k < a.candidates.size(); ++k) {
    EXPECT_NEAR(a.candidates[k].contact_angle, b.candidates[k].contact_angle, 1e-9);
    EXPECT_NEAR((a.candidates[k].point - b.candidates[k].point).norm(), 0.0, 1e-9);
    // Each table's touching heights follow its own sweep: the gap's linearisation differs.
    EXPECT_NEAR(a.candidates[k].gap, b.candidates[k].gap, 0.2e-6);
    EXPECT_NEAR(a.candidates[k].lead, b.candidates[k].lead, 1e-9);
  }
}

TEST(ContactTable, AnIsolatedMissOfTheSearchDoesNotReachTheTable) {
  // At this node of the default table (right wheel) the search has missed the flange's smallest
  // gap, which poses 5 nm to either side find; the table holds what they find.
  const ContactTable& table = defaultTable();
  const ContactSearch& cs = table.contactSearch();
  const double a0 = -0.5 * cs.data().gauge, r0 = cs.data().nominal_radius;
  const double Y = -0.02 + 44 * 2e-4, yaw = std::sqrt(2 * (0.03 * 0.03 / 3)),
               roll = -0.015 + 3 * 2.5e-3;
  WheelsetPose p;
  p.yaw = yaw;
  p.roll = roll;
  p.y = Y - a0 * (std::cos(yaw) * std::cos(roll) - 1.0) - r0 * std::sin(roll) * std::cos(yaw);
  const WheelContactGeometry t = table.search(WheelSide::kRight, p);
  ASSERT_EQ(t.status, ContactSearchStatus::kOk);
  for (double d : {-5e-9, 5e-9}) {
    WheelsetPose q = p;
    q.y += d;
    const ContactCandidate k = [&] {
      const WheelContactGeometry g = cs.search(WheelSide::kRight, q);
      return g.candidates.at(g.closest);
    }();
    EXPECT_NEAR(t.candidates[t.closest].vertical_gap, k.vertical_gap, 0.1e-6);
    EXPECT_NEAR(t.candidates[t.closest].contact_angle, k.contact_angle, 1e-5);
  }
}
