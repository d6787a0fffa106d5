// The normal problem per patch (normal/patch_normal.hpp) against Hertz and against the exact
// half-space solver on the same gap, on the Manchester benchmark's case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/exact/halfspace_normal.hpp"
#include "core/normal/hertz_approach.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"
#include "wheel_rail_contact/normal/patch_normal.hpp"

using namespace wheel_rail_contact;

namespace {

const double kG = 8.2e10, kNu = 0.28, kLoad = 1e4;

/// A candidate whose gap is h = B eta^2 + x^2 / (2 r) (Hertz), with wheel radius r.
ContactCandidate hertzCandidate(double B, double r, double half_width, int samples = 81) {
  ContactCandidate c;
  c.gap = 0.0;
  c.normal = Eigen::Vector2d(0.0, 1.0);
  for (int i = 0; i < samples; ++i) {
    GapSample s;
    s.eta = -half_width + 2.0 * half_width * i / (samples - 1);
    s.gap = B * s.eta * s.eta;
    s.rolling_radius = r;
    s.contact_angle = 0.0;
    c.gap_function.push_back(s);
  }
  return c;
}

/// The exact solution on the patch's own gap: a grid over the region where the bodies
/// interpenetrate undeformed (the contact lies inside it), the gap interpolated linearly between
/// the gap function's samples as the method does, h = g(eta) - g(0) + cos(delta) x^2 / (2 r).
struct ExactPatch {
  NormalSolution s;
  HalfspaceGrid grid;
  double eta_offset = 0.0;
  double fn = 0.0, pmax = 0.0, eta_min = 0.0, eta_max = 0.0;
};

double interp(const ContactCandidate& c, double e, int what) {
  const auto& f = c.gap_function;
  std::size_t i = 0;
  while (i + 2 < f.size() && f[i + 1].eta < e) ++i;
  const double t = std::clamp((e - f[i].eta) / (f[i + 1].eta - f[i].eta), 0.0, 1.0);
  auto v = [&](const GapSample& s) {
    return what == 0 ? s.gap - c.gap : std::cos(s.contact_angle) / (2.0 * s.rolling_radius);
  };
  return v(f[i]) + t * (v(f[i + 1]) - v(f[i]));
}

ExactPatch exactPatch(const ContactCandidate& c, double approach, int mx, int my) {
  double lo = 1e9, hi = -1e9, xmax = 0.0;
  for (const GapSample& s : c.gap_function) {
    const double pen = approach - (s.gap - c.gap);
    if (pen <= 0.0) continue;
    lo = std::min(lo, s.eta);
    hi = std::max(hi, s.eta);
    xmax = std::max(xmax, std::sqrt(pen / interp(c, s.eta, 1)));
  }
  const double de = c.gap_function[1].eta - c.gap_function[0].eta;
  lo -= de;
  hi += de;
  ExactPatch e;
  e.grid.mx = mx;
  e.grid.my = my;
  e.grid.dx = 2.0 * 1.02 * xmax / mx;
  e.grid.dy = (hi - lo) / my;
  e.eta_offset = 0.5 * (lo + hi);
  Eigen::VectorXd h(e.grid.size());
  for (int ix = 0; ix < mx; ++ix)
    for (int iy = 0; iy < my; ++iy) {
      const double x = e.grid.xc(ix), eta = e.eta_offset + e.grid.yc(iy);
      h[e.grid.index(ix, iy)] = interp(c, eta, 0) + interp(c, eta, 1) * x * x;
    }
  e.s = solveNormalGapApproach(e.grid, kG, kNu, h, approach);
  e.fn = e.s.fz;
  e.pmax = e.s.p.maxCoeff();
  e.eta_min = 1e9;
  e.eta_max = -1e9;
  for (int ix = 0; ix < mx; ++ix)
    for (int iy = 0; iy < my; ++iy)
      if (e.s.p[e.grid.index(ix, iy)] > 0.0) {
        e.eta_min = std::min(e.eta_min, e.eta_offset + e.grid.yc(iy) - 0.5 * e.grid.dy);
        e.eta_max = std::max(e.eta_max, e.eta_offset + e.grid.yc(iy) + 0.5 * e.grid.dy);
      }
  return e;
}

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/test/data/profiles/";

/// The right wheel's state of case at the benchmark's y [mm], in our axes (as
/// test_contact_search.cpp reads it; doc/profiles.md: y and yaw change sign, roll does not).
WheelsetPose a22Right(double y_mm) {
  std::ifstream in(kDataDir + "a22_cases.csv");
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    std::istringstream ls(line);
    std::string wheel, field;
    std::getline(ls, wheel, ',');
    std::getline(ls, field, ',');
    std::getline(ls, field, ',');
    const double y = std::stod(field);
    if (wheel != "right" || std::abs(y - y_mm) > 1e-9) continue;
    WheelsetPose p;
    p.y = -y * 1e-3;
    std::getline(ls, field, ',');
    p.yaw = -std::stod(field);
    std::getline(ls, field, ',');
    p.roll = std::stod(field);
    return p;
  }
  ADD_FAILURE() << "no right-wheel case at y = " << y_mm << " mm";
  return {};
}

const ContactSearch& search() {
  static const ContactSearch s{WheelsetTrackData{}};
  return s;
}

/// The wheel's geometry at the pose's y, yaw, roll with the wheelset lowered (or raised) to first
/// touch: the gap functions describe the profiles about where they touch.
WheelContactGeometry atFirstTouch(WheelSide side, WheelsetPose pose) {
  for (int k = 0; k < 3; ++k) {
    const WheelContactGeometry g = search().search(side, pose);
    if (g.closest < 0) return g;
    const double vg = g.candidates[g.closest].vertical_gap;
    if (std::abs(vg) < 1e-9) return g;
    pose.z -= vg;
  }
  return search().search(side, pose);
}

}  // namespace

TEST(PatchNormal, HertzFromApproachInvertsHertzFromLoad) {
  for (double ratio : {0.1, 0.5, 1.0, 2.0, 20.0}) {
    const double A = 1.1, B = A * ratio, d = 6e-5, Estar = contactModulus(kG, kNu);
    const HertzApproach h = hertzFromApproach(A, B, d, Estar);
    const HertzEllipse e = hertzFromCurvatures(h.fn, A, B, kG, kNu);
    EXPECT_NEAR(h.a, e.a, 1e-9 * e.a) << ratio;
    EXPECT_NEAR(h.b, e.b, 1e-9 * e.b) << ratio;
    EXPECT_NEAR(h.p0, e.p0, 1e-9 * e.p0) << ratio;
  }
}

TEST(PatchNormal, EllipticPatchIsHertz) {
  // h = B eta^2 + x^2 / (2 r): the method must say Hertz and return Hertz's a, b, pmax, fn.
  const double B = 1.6, r = 0.46, d = 5e-5;
  const NormalPatch p = solvePatchNormal(hertzCandidate(B, r, 0.02), d, kG, kNu);
  ASSERT_EQ(p.status, NormalStatus::kOk) << p.message;
  EXPECT_EQ(p.method, NormalMethod::kHertz);
  const HertzEllipse e = hertzFromCurvatures(p.fn, 0.5 / r, B, kG, kNu);
  EXPECT_NEAR(p.a, e.a, 1e-6 * e.a);
  EXPECT_NEAR(p.b, e.b, 1e-6 * e.b);
  EXPECT_NEAR(p.pmax, e.p0, 1e-6 * e.p0);
  double sum = 0.0;
  for (const NormalStrip& s : p.strips) sum += s.force;
  EXPECT_NEAR(sum, p.fn, 0.01 * p.fn);  // midpoint rule over 24 strips
}

TEST(PatchNormal, StripMethodOnAHertzGapApproachesHertz) {
  // Its penetration factors come from the equivalent Hertz problem, so on a Hertz gap the strip
  // method's patch is Hertz's ellipse; what remains is the strips' discretisation of the
  // Boussinesq integral and of the gap (1 % with 24 strips and 81 samples).
  for (double B : {0.3, 1.6, 8.0}) {
    const double r = 0.46, d = 5e-5;
    NormalOptions o;
    o.allow_hertz = false;
    const NormalPatch p =
        solvePatchNormal(hertzCandidate(B, r, std::sqrt(8.0 * d / B)), d, kG, kNu, o);
    ASSERT_EQ(p.status, NormalStatus::kOk) << p.message;
    EXPECT_EQ(p.method, NormalMethod::kNonHertzian);
    const HertzApproach h = hertzFromApproach(0.5 / r, B, d, contactModulus(kG, kNu));
    EXPECT_NEAR(p.fn, h.fn, 0.01 * h.fn) << B;
    EXPECT_NEAR(p.pmax, h.p0, 0.01 * h.p0) << B;
    EXPECT_NEAR(p.b, h.b, 0.01 * h.b) << B;
    EXPECT_NEAR(p.a, h.a, 0.01 * h.a) << B;
  }
}

TEST(PatchNormal, ExploreBenchmark) {
  for (double y : {0.0, 0.5, 2.0, 4.0, 5.0, 5.5, 6.0, 6.5, 7.0, 8.0, 10.0}) {
    const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(y));
    const WheelNormal w = solveWheelLoad(geo, kLoad, kG, kNu);
    std::printf("y %.1f status %d %s dv %.3g um\n", y, int(w.status), w.message.c_str(),
                w.vertical_approach * 1e6);
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      const NormalPatch& p = w.patches[i];
      const ContactCandidate& c = geo.candidates[i];
      std::printf(
          "  cand %zu angle %.3f gap %.3g um samples %zu [%.2f %.2f] mm: method %d fn %.0f "
          "pmax %.3g a %.2f b %.2f ext [%.2f %.2f] appr %.2f um\n",
          i, c.contact_angle, c.gap * 1e6, c.gap_function.size(),
          c.gap_function.empty() ? 0.0 : c.gap_function.front().eta * 1e3,
          c.gap_function.empty() ? 0.0 : c.gap_function.back().eta * 1e3, int(p.method), p.fn,
          p.pmax, p.a * 1e3, p.b * 1e3, p.eta_min * 1e3, p.eta_max * 1e3, p.approach * 1e6);
      if (p.fn > 0.0 && (y == 0.5 || y == 5.0 || y == 6.5 || y == 2.0 || y == 8.0)) {
        for (int m : {40}) {
          const ExactPatch e = exactPatch(c, p.approach, m, m);
          std::printf("    exact %d: conv %d fn %.0f (%.2f%%) pmax %.3g (%.2f%%) ext [%.2f %.2f]\n",
                      m, int(e.s.converged), e.fn, 100 * (p.fn / e.fn - 1), e.pmax,
                      100 * (p.pmax / e.pmax - 1), e.eta_min * 1e3, e.eta_max * 1e3);
        }
      }
    }
  }
}

TEST(PatchNormal, HertzApproachAgreesWithTheExactSolver) {
  // The approach-load relation against the exact solver on the same Hertz gap at the same
  // approach: 2 % (piecewise-constant pressure on a 40 x 40 grid over the ellipse).
  for (double ratio : {0.3, 1.0, 4.0}) {
    const double A = 1.1, B = A * ratio, d = 5e-5;
    const HertzApproach h = hertzFromApproach(A, B, d, contactModulus(kG, kNu));
    const HalfspaceGrid g = HalfspaceGrid::covering(h.a, h.b, 40, 40);
    Eigen::VectorXd gap(g.size());
    for (int ix = 0; ix < g.mx; ++ix)
      for (int iy = 0; iy < g.my; ++iy)
        gap[g.index(ix, iy)] = A * g.xc(ix) * g.xc(ix) + B * g.yc(iy) * g.yc(iy);
    const NormalSolution s = solveNormalGapApproach(g, kG, kNu, gap, d);
    ASSERT_TRUE(s.converged);
    EXPECT_NEAR(s.fz, h.fn, 0.02 * h.fn) << ratio;
  }
}
