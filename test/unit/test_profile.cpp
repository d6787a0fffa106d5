// Wheel and rail profiles: reading both formats, refusing bad files, the smoothing spline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/profiles/profile.hpp"

using namespace wheel_rail_contact;

namespace {

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/config/profiles/";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The message of the std::runtime_error parse() throws, "" if it does not.
std::string refusal(const std::string& text, ProfileKind kind = ProfileKind::kRail,
                    const ProfileReadOptions& options = {}) {
  try {
    Profile::parse(text, "bad.txt", kind, options);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

/// A rail-like crown: 30 points on a circle of radius 0.3 m about (0, -0.3), in mm with z down
/// (the default axes), y toward the field side.
std::string crownText(int n = 30, double spacing_mm = 1.0) {
  std::ostringstream os;
  os.precision(12);
  os << "# unit: mm\n";
  for (int i = 0; i < n; ++i) {
    const double y = (i - n / 2) * spacing_mm;
    os << y << ", " << -(std::sqrt(300.0 * 300.0 - y * y) - 300.0) << "\n";
  }
  return os.str();
}

void expectSameCurve(const Profile& a, const Profile& b, double tol) {
  ASSERT_NEAR(a.length(), b.length(), tol);
  for (int i = 0; i <= 1000; ++i) {
    const double s = a.length() * i / 1000;
    const Profile::Point pa = a.at(s), pb = b.at(s);
    EXPECT_NEAR((pa.position - pb.position).norm(), 0.0, tol) << "s = " << s;
    EXPECT_NEAR((pa.normal - pb.normal).norm(), 0.0, 1e-6) << "s = " << s;
    EXPECT_NEAR(pa.curvature, pb.curvature, 1e-6 * (1.0 + std::abs(pa.curvature))) << "s = " << s;
  }
}

}  // namespace

TEST(Profile, SimpackFilesComeOutRightWayUpInTheProfileFrame) {
  const Profile rail = Profile::read(kDataDir + "MBench_UIC60_v3.prr", ProfileKind::kRail);
  const Profile wheel = Profile::read(kDataDir + "MBench_S1002_v3.prw", ProfileKind::kWheel);
  // The rail's top is its highest point, inside the profile; the foot-side ends lie below it.
  double top = -1.0, s_top = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double s = rail.length() * i / 2000;
    if (rail.at(s).position.y() > top) {
      top = rail.at(s).position.y();
      s_top = s;
    }
  }
  EXPECT_GT(s_top, 0.2 * rail.length());
  EXPECT_LT(s_top, 0.8 * rail.length());
  EXPECT_LT(rail.at(0.0).position.y(), top - 0.03);
  EXPECT_LT(rail.at(rail.length()).position.y(), top - 0.03);
  EXPECT_GT(rail.at(s_top).normal.y(), 0.99);  // out of the rail: up
  // The wheel's flange (its lowest point) lies toward the track centre (+y_p) from its taping
  // line, and the flange back (file y = -70 mm) too; the wheel's normal points down.
  double low = 1.0, y_low = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const Profile::Point p = wheel.at(wheel.length() * i / 2000);
    if (p.position.y() < low) {
      low = p.position.y();
      y_low = p.position.x();
    }
  }
  EXPECT_GT(y_low, 0.02);
  EXPECT_LT(low, -0.02);  // the flange is more than 20 mm deep
  EXPECT_NEAR(wheel.fromFile(Eigen::Vector2d(-0.070, 0.0)).x(), 0.070, 1e-15);
  EXPECT_LT(wheel.at(0.5 * wheel.length()).normal.y(), -0.9);
  // The points are ordered toward the track centre and the unit is mm.
  EXPECT_LT(wheel.points().front().x(), wheel.points().back().x());
  EXPECT_NEAR(wheel.yMax() - wheel.yMin(), 0.1296126, 1e-6);  // 69.6126 + 60 mm in the file
}

TEST(Profile, BothFormatsGiveTheSameSpline) {
  // The S1002 file has mirror.y = 1 and inversion = 1: its numbers written out as a CSV in m
  // with the profile frame's own axes (y toward the centre = the file's numbers as they stand,
  // since mirroring turns the file's field-side y the other way; z up = minus the file's z).
  const Profile simpack = Profile::read(kDataDir + "MBench_S1002_v3.prw", ProfileKind::kWheel);
  std::istringstream in(slurp(kDataDir + "MBench_S1002_v3.prw"));
  std::ostringstream csv;
  csv.precision(17);
  csv << "y_m,z_m\n";
  std::string line;
  bool points = false;
  while (std::getline(in, line)) {
    if (line.find("point.begin") != std::string::npos) {
      points = true;
      continue;
    }
    if (line.find("point.end") != std::string::npos) break;
    if (!points || line.find('!') != std::string::npos) continue;
    double y = 0.0, z = 0.0;
    std::istringstream ls(line);
    ls >> y >> z;
    csv << y * 1e-3 << "," << -z * 1e-3 << "\n";
  }
  ProfileReadOptions o;
  o.lateral = LateralAxis::kTowardGauge;
  o.vertical = VerticalAxis::kUp;
  const Profile text = Profile::parse(csv.str(), "s1002.csv", ProfileKind::kWheel, o);
  expectSameCurve(simpack, text, 1e-12);
  // And the file coordinates of each come back as their own file's.
  const Eigen::Vector2d p = simpack.at(0.3 * simpack.length()).position;
  EXPECT_NEAR((simpack.toFile(p) - Eigen::Vector2d(-p.x(), -p.y())).norm(), 0.0, 1e-18);
  EXPECT_NEAR((text.toFile(p) - p).norm(), 0.0, 1e-18);
}

TEST(Profile, UnitsFromTheCallerTheCommentOrTheHeader) {
  const std::string mm = crownText();
  std::string bare = mm.substr(mm.find('\n') + 1);  // without "# unit: mm"
  ProfileReadOptions o;
  o.length_unit = 1e-3;
  const Profile a = Profile::parse(mm, "a", ProfileKind::kRail);
  const Profile b = Profile::parse(bare, "b", ProfileKind::kRail, o);
  const Profile c = Profile::parse("y [mm]; z [mm]\n" + bare, "c", ProfileKind::kRail);
  expectSameCurve(a, b, 1e-15);
  expectSameCurve(a, c, 1e-15);
  EXPECT_NEAR(a.yMax() - a.yMin(), 0.029, 1e-9);
}

TEST(Profile, MirroredAxesGiveTheMirroredProfile) {
  // The same crown read with the lateral axis the other way is its mirror image in y_p.
  ProfileReadOptions o;
  o.lateral = LateralAxis::kTowardGauge;
  const Profile field = Profile::parse(crownText(), "a", ProfileKind::kRail);
  const Profile gauge = Profile::parse(crownText(), "a", ProfileKind::kRail, o);
  for (int i = 0; i <= 100; ++i) {
    const double s = field.length() * i / 100;
    // gauge runs the other way along the points: its s is field's length - s.
    const Profile::Point p = field.at(s), q = gauge.at(gauge.length() - s);
    EXPECT_NEAR(p.position.x(), -q.position.x(), 1e-12);
    EXPECT_NEAR(p.position.y(), q.position.y(), 1e-12);
    EXPECT_NEAR(p.normal.x(), -q.normal.x(), 1e-9);
    EXPECT_NEAR(p.curvature, q.curvature, 1e-6);
  }
}

TEST(Profile, SplineInterpolatesWithoutSmoothingAndGivesSlopeAndCurvature) {
  // A circle of radius 20 mm sampled every 0.5 mm: its bottom, as a wheel's flange tip.
  std::vector<Eigen::Vector2d> pts;
  const double R = 0.02;
  for (int i = -30; i <= 30; ++i) {
    const double a = i * 0.025;
    pts.emplace_back(R * std::sin(a), R - R * std::cos(a));  // centred at (0, R)
  }
  const Profile wheel = Profile::fromPoints(pts, ProfileKind::kWheel, "circle", 0.0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double s = 0.0;
    for (std::size_t k = 1; k <= i; ++k) s += (pts[k] - pts[k - 1]).norm();
    EXPECT_NEAR((wheel.at(s).position - pts[i]).norm(), 0.0, 1e-15);
  }
  for (int i = 10; i <= 50; ++i) {  // away from the natural ends (zero curvature there)
    const double s = wheel.length() * i / 60.0;
    const Profile::Point p = wheel.at(s);
    const Eigen::Vector2d radial = (p.position - Eigen::Vector2d(0.0, R)).normalized();
    EXPECT_NEAR(p.normal.dot(radial), 1.0, 1e-7);                // out of the disc
    EXPECT_NEAR(p.tangent.dot(radial), 0.0, 1e-4);               // the slope
    EXPECT_NEAR(p.curvature, 1.0 / R, 2e-4 / R) << "s = " << s;  // convex: positive
  }
  // The same points as a rail (material below, the circle's inside is air): concave.
  const Profile groove = Profile::fromPoints(pts, ProfileKind::kRail, "groove", 0.0);
  EXPECT_NEAR(groove.at(0.5 * groove.length()).curvature, -1.0 / R, 2e-4 / R);
  EXPECT_NEAR(groove.at(0.5 * groove.length()).normal.y(), 1.0, 1e-9);
}

TEST(Profile, SmoothingDampsNoiseButKeepsTheShape) {
  // A crown of radius 0.3 m sampled every 0.1 mm with a profile gauge's noise of +-2 um.
  std::vector<Eigen::Vector2d> pts;
  const double R = 0.3;
  for (int i = -300; i <= 300; ++i) {
    const double y = i * 1e-4;
    const double noise = 2e-6 * std::sin(i * 2.39996322972865332);  // golden-angle sequence
    pts.emplace_back(y, std::sqrt(R * R - y * y) - R + noise);
  }
  auto worst = [&](double L, double* dev) {
    const Profile p = Profile::fromPoints(pts, ProfileKind::kRail, "crown", L);
    double e = 0.0;
    *dev = 0.0;
    for (int i = 100; i <= 500; ++i) {  // the middle two thirds
      const double s = p.length() * i / 600.0;
      const Profile::Point q = p.at(s);
      e = std::max(e, std::abs(q.curvature - 1.0 / R));
      const double exact = std::sqrt(R * R - q.position.x() * q.position.x()) - R;
      *dev = std::max(*dev, std::abs(q.position.y() - exact));
    }
    return e;
  };
  double dev0 = 0.0, dev1 = 0.0;
  const double interpolated = worst(0.0, &dev0);
  const double smoothed = worst(0.5e-3, &dev1);
  EXPECT_GT(interpolated, 10.0 / R);  // the noise's curvature swamps the crown's
  EXPECT_LT(smoothed, 0.1 / R);       // within 10 % once smoothed over 0.5 mm
  EXPECT_LT(dev1, 2e-6);              // and the surface stays within the noise band
}

TEST(Profile, DefaultSmoothingMovesTheBenchmarkProfilesByLessThanATenthOfAMicrometre) {
  // The claim behind kDefaultProfileSmoothingLength, on the benchmark's exact shapes: the largest
  // distance from a point to the spline, along the spline's normal, for a range of smoothing
  // lengths (it prints the table doc/profiles.md shows). The 30 points at either end of the rail,
  // bunched within micrometres of each other, are left out.
  std::printf("  L_mm  rail_um  wheel_um  rail_max_curvature  wheel_max_curvature\n");
  for (const double L : {0.0, 0.05e-3, 0.1e-3, 0.2e-3, 0.5e-3, 1e-3}) {
    ProfileReadOptions o;
    o.smoothing_length = L;
    double dev[2] = {0.0, 0.0}, kmax[2] = {0.0, 0.0};
    for (int w = 0; w < 2; ++w) {
      const Profile p =
          w == 0 ? Profile::read(kDataDir + "MBench_UIC60_v3.prr", ProfileKind::kRail, o)
                 : Profile::read(kDataDir + "MBench_S1002_v3.prw", ProfileKind::kWheel, o);
      const std::vector<Eigen::Vector2d>& pts = p.points();
      double s = 0.0;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (i > 0) s += (pts[i] - pts[i - 1]).norm();
        if (i < 30 || i + 30 >= pts.size()) continue;
        const Profile::Point q = p.at(s);
        dev[w] = std::max(dev[w], std::abs((pts[i] - q.position).dot(q.normal)));
        kmax[w] = std::max(kmax[w], std::abs(q.curvature));
      }
    }
    std::printf("%6.2f  %7.3f  %8.3f  %18.1f  %19.1f\n", L * 1e3, dev[0] * 1e6, dev[1] * 1e6,
                kmax[0], kmax[1]);
    if (L == kDefaultProfileSmoothingLength) {
      EXPECT_LT(dev[0], 1e-7);
      EXPECT_LT(dev[1], 1e-7);
    }
  }
}

TEST(Profile, SurfaceAtTakesTheOuterCrossing) {
  // A rail head with an overhang: y goes back under the head on the gauge side (points walk
  // down the face and back toward the field side, then down again).
  const std::vector<Eigen::Vector2d> corners = {
      {-0.030, -0.030}, {-0.030, -0.020}, {-0.030, -0.010}, {-0.025, -0.002}, {-0.015, 0.000},
      {-0.005, 0.000},  {0.005, 0.000},   {0.015, 0.000},   {0.025, -0.002},  {0.030, -0.008},
      {0.026, -0.014},  {0.024, -0.020},  {0.027, -0.026},  {0.030, -0.032}};
  std::vector<Eigen::Vector2d> pts;  // four points a side, 2.5 mm apart at most
  for (std::size_t i = 0; i + 1 < corners.size(); ++i)
    for (int k = 0; k < 4; ++k) pts.push_back(corners[i] + (corners[i + 1] - corners[i]) * k / 4.0);
  pts.push_back(corners.back());
  const Profile rail = Profile::fromPoints(pts, ProfileKind::kRail, "overhang", 0.0);
  EXPECT_EQ(rail.crossings(0.0275).size(), 3u);  // the head, the overhang's face, the web
  double z = 0.0, s = 0.0;
  ASSERT_TRUE(rail.surfaceAt(0.0275, &z, &s));
  EXPECT_GT(z, -0.008);  // the head, not the faces below it
  EXPECT_FALSE(rail.surfaceAt(0.05, &z, &s));
}

TEST(Profile, CrossingsConvergeEverywhereOnTheRail) {
  // Every crossing lies on the line it was asked for, including where the gauge face turns
  // vertical (y changing slowly along the profile at one end of a monotone piece, fast at the
  // other), which made plain safeguarded Newton bounce between the piece's ends and stop
  // 1.4 mm off at y = 41.2126 mm (the contact search's isolated miss).
  const Profile& rail = *Profile::standardRail();
  int checked = 0;
  double worst = 0.0;
  for (double y = rail.yMin() + 1e-6; y < rail.yMax() - 1e-6; y += 0.7e-6)
    for (double t : rail.crossings(y)) {
      worst = std::max(worst, std::abs(rail.at(t).position.x() - y));
      ++checked;
    }
  for (double d : {-2e-12, -1e-12, 0.0, 1e-12})
    for (double t : rail.crossings(41.212577441806e-3 + d))
      worst = std::max(worst, std::abs(rail.at(t).position.x() - (41.212577441806e-3 + d)));
  EXPECT_GT(checked, 100000);
  EXPECT_LT(worst, 1e-12);
}

// ---- refusals: each reason, with the file's name and line ------------------------------------

TEST(ProfileRefusals, NotANumberNamesFileLineAndToken) {
  const std::string msg = refusal("# unit: mm\n0, 0\n1, 0.1\n2, abc\n");
  EXPECT_NE(msg.find("bad.txt:4:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'abc' is not a number"), std::string::npos) << msg;
}

TEST(ProfileRefusals, WrongFieldCount) {
  const std::string msg = refusal("# unit: mm\n0, 0\n1, 0.1, 1, 7\n");
  EXPECT_NE(msg.find("bad.txt:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("found 4 fields"), std::string::npos) << msg;
}

TEST(ProfileRefusals, NotFinite) {
  for (const char* v : {"nan", "inf", "1e999"}) {
    const std::string msg = refusal(std::string("# unit: mm\n0, 0\n1, ") + v + "\n");
    EXPECT_NE(msg.find("bad.txt:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a finite number"), std::string::npos) << msg;
  }
}

TEST(ProfileRefusals, TooFewPoints) {
  const std::string msg = refusal(crownText(9));
  EXPECT_NE(msg.find("bad.txt:10:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("9 points; a profile needs at least 10"), std::string::npos) << msg;
  EXPECT_EQ(refusal(crownText(10)), "");
}

TEST(ProfileRefusals, DuplicateOrTooClosePoints) {
  std::string text = crownText();
  // Repeat the 6th point (file line 7) right after itself.
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  for (int ln = 1; std::getline(in, line); ++ln) {
    out << line << "\n";
    if (ln == 7) out << line << "\n";
  }
  const std::string msg = refusal(out.str());
  EXPECT_NE(msg.find("bad.txt:8:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("from the one on line 7: a duplicate"), std::string::npos) << msg;
  // 0.5 um apart is refused once min_point_distance is 1 um.
  ProfileReadOptions o;
  o.min_point_distance = 1e-6;
  const std::string close =
      refusal("# unit: mm\n0, 0\n0.0005, 0\n" + text.substr(11), ProfileKind::kRail, o);
  EXPECT_NE(close.find("bad.txt:3:"), std::string::npos) << close;
  EXPECT_NE(close.find("a duplicate"), std::string::npos) << close;
}

TEST(ProfileRefusals, HoleBetweenPoints) {
  const std::string msg = refusal(crownText(30, 6.0));
  EXPECT_NE(msg.find("bad.txt:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a hole in the profile"), std::string::npos) << msg;
}

TEST(ProfileRefusals, PointsOutOfOrder) {
  // Swap two neighbouring points (file lines 10 and 11): the profile turns back at line 10.
  std::istringstream in(crownText());
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  std::swap(lines[9], lines[10]);
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  const std::string msg = refusal(text);
  EXPECT_NE(msg.find("bad.txt:10:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("turns back on itself"), std::string::npos) << msg;
}

TEST(ProfileRefusals, LoopCrossingItself) {
  // A curl (a prolate cycloid's loop), 0.1 rad a step: no sharp turn, but it crosses itself.
  std::ostringstream os;
  os << "# unit: mm\n";
  for (int i = 0; i <= 63; ++i) {
    const double t = M_PI + 0.1 * i;
    os << 5.0 * (t - 2.0 * std::sin(t)) << " " << -10.0 * std::cos(t) << "\n";
  }
  const std::string msg = refusal(os.str());
  EXPECT_NE(msg.find("crosses itself"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bad.txt:"), std::string::npos) << msg;
}

TEST(ProfileRefusals, UnitMissingOrContradicted) {
  const std::string mm = crownText();
  const std::string bare = mm.substr(mm.find('\n') + 1);
  EXPECT_NE(refusal(bare).find("no length unit"), std::string::npos);
  ProfileReadOptions o;
  o.length_unit = 1.0;
  const std::string msg = refusal(mm, ProfileKind::kRail, o);
  EXPECT_NE(msg.find("bad.txt:1:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("disagrees"), std::string::npos) << msg;
  EXPECT_NE(refusal("# unit: furlong\n" + bare).find("unknown unit"), std::string::npos);
}

TEST(ProfileRefusals, SimpackStructureAndType) {
  const std::string good = slurp(kDataDir + "MBench_UIC60_v3.prr");
  // A rail file asked for as a wheel: the header's type line (11).
  std::string msg = refusal(good, ProfileKind::kWheel);
  EXPECT_NE(msg.find("bad.txt:12:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rail profile, a wheel profile was asked for"), std::string::npos) << msg;
  // No point.end.
  std::string cut = good.substr(0, good.find("    point.end"));
  msg = refusal(cut);
  EXPECT_NE(msg.find("bad.txt:39:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("point.begin without point.end"), std::string::npos) << msg;
  // A processing flag that is not 0 or 1.
  std::string flag = good;
  flag.replace(flag.find("mirror.y       =  0"), 19, "mirror.y       =  2");
  msg = refusal(flag);
  EXPECT_NE(msg.find("bad.txt:32:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mirror.y must be 0 or 1"), std::string::npos) << msg;
  // A value that is not a number.
  std::string value = good;
  value.replace(value.find("+1.000000000000000e+03"), 22, "thousand");
  msg = refusal(value);
  EXPECT_NE(msg.find("bad.txt:37:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("units.len.f"), std::string::npos) << msg;
}

TEST(Profile, SimpackProcessingIsApplied) {
  // shift.y and mirror.z in the file move the profile as Simpack would: shift, then mirror.
  const std::string good = slurp(kDataDir + "MBench_UIC60_v3.prr");
  std::string moved = good;
  moved.replace(moved.find("shift.y        = +0.000000000000000e+00"), 39,
                "shift.y        = +5.000000000000000e+00");
  moved.replace(moved.find("mirror.z       =  0"), 19, "mirror.z       =  1");
  const Profile a = Profile::parse(good, "a", ProfileKind::kRail);
  ProfileReadOptions o;
  o.vertical = VerticalAxis::kUp;  // mirror.z turned the file's z up
  const Profile b = Profile::parse(moved, "b", ProfileKind::kRail, o);
  for (int i = 0; i <= 100; ++i) {
    const double s = a.length() * i / 100;
    EXPECT_NEAR((a.at(s).position - b.at(s).position - Eigen::Vector2d(0.005, 0.0)).norm(), 0.0,
                1e-12);
  }
}

TEST(ProfileRefusals, MissingFile) {
  try {
    Profile::read(kDataDir + "no_such_profile.prr", ProfileKind::kRail);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_profile.prr: cannot open"), std::string::npos)
        << e.what();
  }
}
