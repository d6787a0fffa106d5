// The normal problem per patch (normal/patch_normal.hpp) against Hertz and against the exact
// half-space solver on the same gap, on the Manchester benchmark's case.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/exact/halfspace_normal.hpp"
#include "core/normal/hertz_approach.hpp"
#include "core/normal/merge_candidates.hpp"
#include "validation/manchester_a22.hpp"
#include "validation/patch_exact.hpp"
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

ExactPatch exactPatch(const ContactCandidate& c, double approach, int mx, int my) {
  return exactPatchNormal(c, approach, kG, kNu, mx, my);
}

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/test/data/profiles/";

/// The right wheel's state of case at the benchmark's y [mm], in our axes
/// (validation/manchester_a22.hpp).
WheelsetPose a22Right(double y_mm) {
  for (const A22State& s : readA22States(kDataDir + "a22_cases.csv"))
    if (s.side == WheelSide::kRight && std::abs(s.y_mm - y_mm) <= 1e-9) return a22Pose(s);
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

namespace {

/// The method's wheel solution at the benchmark's state y [mm] under kLoad.
struct BenchmarkState {
  WheelContactGeometry geo;
  WheelNormal wheel;
};

BenchmarkState benchmarkState(double y_mm) {
  BenchmarkState s;
  s.geo = atFirstTouch(WheelSide::kRight, a22Right(y_mm));
  s.wheel = solveWheelLoad(s.geo, kLoad, kG, kNu);
  return s;
}

}  // namespace

// The exact solver's own discretisation: on the patches below a 40 x 40 grid over the undeformed
// interpenetration and a 60 x 60 one differ by under 0.3 % in fn and 0.5 % in pmax
// (PatchNormal.ExactReferenceIsGridConverged), well below the tolerances asserted here.

TEST(PatchNormal, ExactReferenceIsGridConverged) {
  for (double y : {5.0, 6.5}) {
    const BenchmarkState s = benchmarkState(y);
    ASSERT_EQ(s.wheel.status, NormalStatus::kOk) << s.wheel.message;
    for (std::size_t i = 0; i < s.wheel.patches.size(); ++i) {
      const NormalPatch& p = s.wheel.patches[i];
      if (p.fn <= 0.0) continue;
      const ExactPatch e40 = exactPatch(s.geo.candidates[i], p.approach, 40, 40);
      const ExactPatch e60 = exactPatch(s.geo.candidates[i], p.approach, 60, 60);
      ASSERT_TRUE(e40.solution.converged && e60.solution.converged);
      EXPECT_NEAR(e40.fn, e60.fn, 0.003 * e60.fn) << y << " " << i;
      EXPECT_NEAR(e40.pmax, e60.pmax, 0.005 * e60.pmax) << y << " " << i;
    }
  }
}

TEST(PatchNormal, A22AgainstTheExactSolverAtTheSameApproach) {
  // Right wheel of case under 10 kN, each patch at the approach the method found, the exact
  // solver on the same gap: gauge corner (5 mm, two patches with the tread), flange (6.5 mm) and
  // the tread at 2 mm where the gap is elliptic. Tolerances: fn 2 % and pmax 3 % (the assumed
  // pressure shape, semi-elliptic strips under the equivalent ellipse's penetration factor, is
  // what differs from exact: up to 1 % and 1.3 % on A-2.2's convex gaps, doc/normal_problem.md),
  // the lateral edges within 0.15 mm (one exact element is 0.02 to 0.15 mm wide).
  for (double y : {2.0, 5.0, 6.5}) {
    const BenchmarkState s = benchmarkState(y);
    ASSERT_EQ(s.wheel.status, NormalStatus::kOk) << s.wheel.message;
    int loaded = 0;
    for (std::size_t i = 0; i < s.wheel.patches.size(); ++i) {
      const NormalPatch& p = s.wheel.patches[i];
      if (p.fn <= 0.0) continue;
      ++loaded;
      const ExactPatch e = exactPatch(s.geo.candidates[i], p.approach, 40, 40);
      ASSERT_TRUE(e.solution.converged);
      EXPECT_NEAR(p.fn, e.fn, 0.02 * e.fn) << "y " << y << " patch " << i;
      EXPECT_NEAR(p.pmax, e.pmax, 0.03 * e.pmax) << "y " << y << " patch " << i;
      EXPECT_NEAR(p.eta_min, e.eta_min, 1.5e-4) << "y " << y << " patch " << i;
      EXPECT_NEAR(p.eta_max, e.eta_max, 1.5e-4) << "y " << y << " patch " << i;
      EXPECT_TRUE(p.message.empty()) << p.message;  // nothing to flag on these gaps
    }
    EXPECT_EQ(loaded, y == 5.0 ? 2 : 1) << y;
  }
}

TEST(PatchNormal, A22LoadSplitOfTwoPatchesAgreesWithExact) {
  // At 5 mm the wheel touches its rail on the tread and on the gauge corner; the exact solver's
  // split of the same 10 kN (its own vertical approach) against the method's: the tread's share
  // within 1 percentage point (measured: 0.2).
  const BenchmarkState s = benchmarkState(5.0);
  ASSERT_EQ(s.wheel.status, NormalStatus::kOk) << s.wheel.message;
  ASSERT_EQ(s.wheel.patches.size(), 2u);
  const std::vector<double> fe =
      exactWheelLoad(s.geo, kLoad, kG, kNu, 40, s.wheel.vertical_approach);
  const double share = s.wheel.patches[0].fn / (s.wheel.patches[0].fn + s.wheel.patches[1].fn);
  const double exact_share = fe[0] / (fe[0] + fe[1]);
  EXPECT_GT(exact_share, 0.05);  // both patches carry load
  EXPECT_NEAR(share, exact_share, 0.01);
  double fz = 0.0;
  for (std::size_t i = 0; i < 2; ++i) fz += s.wheel.patches[i].fn * s.geo.candidates[i].normal.y();
  EXPECT_NEAR(fz, kLoad, 1e-6 * kLoad);
}

TEST(PatchNormal, A22TreadPlateauIsTheMethodsWeakness) {
  // At 0.5 mm the tread's gap has a plateau some 10 um high over 8 mm beside its minimum: under
  // 10 kN the exact contact spreads over it, the method's strips (penetration factor some 0.4
  // at the centre of the equivalent ellipse) stop short of it. Asserted as measured, so that a
  // change in either direction shows: fn at the same approach 20 to 40 % low, the patch narrower,
  // pmax within 11 % (measured 9.6 % low; 4 % low with continuous_region = false, whose fn
  // jumps in the approach here, doc/normal_problem.md).
  const BenchmarkState s = benchmarkState(0.5);
  ASSERT_EQ(s.wheel.status, NormalStatus::kOk) << s.wheel.message;
  const NormalPatch& p = s.wheel.patches.at(s.geo.closest);
  EXPECT_EQ(p.method, NormalMethod::kNonHertzian);
  EXPECT_EQ(p.status, NormalStatus::kOk);
  EXPECT_NE(p.message.find("concave"), std::string::npos) << p.message;  // the method says so
  const ExactPatch e = exactPatch(s.geo.candidates[s.geo.closest], p.approach, 40, 40);
  ASSERT_TRUE(e.solution.converged);
  EXPECT_GT(p.fn, 0.6 * e.fn);
  EXPECT_LT(p.fn, 0.8 * e.fn);
  EXPECT_LT(p.eta_max - p.eta_min, e.eta_max - e.eta_min);
  EXPECT_NEAR(p.pmax, e.pmax, 0.11 * e.pmax);
}

TEST(PatchNormal, ContinuousRegionMovesSmoothlyOverTheTreadPlateau) {
  // At 0.5 mm, from 0.01 to 60 um of approach in 0.01 um steps. By default the strips' region
  // stops where the penetration dips below zero between the minimum and the plateau and jumps
  // over the plateau when the dip fills, and KPEC's extent at d0/2 runs over the plateau within
  // a fraction of a micrometre: fn falls by some 90 % in one step (measured 0.918 at 21.13 um)
  // and its lower edge jumps by some 11 mm (continuous_region = false, the rule before it became
  // the default). With continuous_region fn grows in every step, no
  // step more than twice the one before (measured 1.46, near first touch), and the lower edge
  // moves at most 0.1 mm a step (measured 0.05 mm).
  const ContactCandidate c = benchmarkState(0.5).geo.candidates.at(0);
  double worst_drop[2] = {}, worst_ratio[2] = {}, worst_edge[2] = {};
  for (int k = 0; k < 2; ++k) {
    NormalOptions o;
    o.continuous_region = k == 1;
    double fn_before = 0.0, step_before = 0.0, edge_before = 0.0;
    for (int i = 1; i <= 6000; ++i) {
      const NormalPatch p = solvePatchNormal(c, 1e-8 * i, kG, kNu, o);
      ASSERT_EQ(p.status, NormalStatus::kOk) << i << " " << p.message;
      const double step = p.fn - fn_before;
      if (i > 2) {
        worst_drop[k] = std::max(worst_drop[k], -step / p.fn);
        if (step_before > 0.0) worst_ratio[k] = std::max(worst_ratio[k], step / step_before);
        worst_edge[k] = std::max(worst_edge[k], std::abs(p.eta_min - edge_before));
      }
      fn_before = p.fn;
      step_before = step;
      edge_before = p.eta_min;
    }
  }
  EXPECT_GT(worst_drop[0], 0.5);
  EXPECT_GT(worst_edge[0], 5e-3);
  EXPECT_EQ(worst_drop[1], 0.0);
  EXPECT_LT(worst_ratio[1], 2.0);
  EXPECT_LT(worst_edge[1], 1e-4);
}

TEST(PatchNormal, ContinuousRegionOnTheTreadPlateauAgainstExact) {
  // The plateau with continuous_region (default), at its own load's approach against the exact
  // solver at the same approach (40 x 40), as measured, within a band so that a change shows: fn
  // 23 % low (30 % with continuous_region = false: the region, though continuous, still stops
  // short of the plateau, where the exact contact covers nearly all the rigid overlap), pmax 9.6 %
  // low (4 % with continuous_region = false), the patch narrower than exact's.
  const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(0.5));
  const WheelNormal w = solveWheelLoad(geo, kLoad, kG, kNu);
  ASSERT_EQ(w.status, NormalStatus::kOk) << w.message;
  EXPECT_TRUE(w.message.empty()) << w.message;  // no jump
  const NormalPatch& p = w.patches.at(geo.closest);
  EXPECT_NEAR(p.fn * geo.candidates[geo.closest].normal.y(), kLoad, 1e-6 * kLoad);
  const ExactPatch e = exactPatch(geo.candidates[geo.closest], p.approach, 40, 40);
  ASSERT_TRUE(e.solution.converged);
  EXPECT_GT(p.fn, 0.7 * e.fn);
  EXPECT_LT(p.fn, 0.85 * e.fn);
  EXPECT_GT(p.pmax, 0.85 * e.pmax);
  EXPECT_LT(p.pmax, 0.95 * e.pmax);
  EXPECT_LT(p.eta_max - p.eta_min, e.eta_max - e.eta_min);
}

TEST(PatchNormal, ContinuousRegionKeepsTheConvexPatches) {
  // Elsewhere on continuous_region (default) changes little: on the right wheel's states
  // with a strips patch beyond the plateau, at the load, against the exact solver at the same
  // approach (40 x 40), fn within 2 % and pmax within 3 % on every loaded patch (measured: fn
  // -1.4 % and pmax -1.3 % at 1 mm, where continuous_region = false has +0.4 % and -4.1 %; within
  // 0.6 % and 1.3 % at the others). Hertz's patches do not depend on it.
  for (double y : {1.0, 4.5, 5.0, 6.0, 6.5}) {
    const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(y));
    const WheelNormal w = solveWheelLoad(geo, kLoad, kG, kNu);
    ASSERT_EQ(w.status, NormalStatus::kOk) << y << " " << w.message;
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      const NormalPatch& p = w.patches[i];
      if (p.fn <= 0.0) continue;
      const ExactPatch e = exactPatch(geo.candidates[i], p.approach, 40, 40);
      ASSERT_TRUE(e.solution.converged) << y;
      EXPECT_NEAR(p.fn, e.fn, 0.02 * e.fn) << y << " patch " << i;
      EXPECT_NEAR(p.pmax, e.pmax, 0.03 * e.pmax) << y << " patch " << i;
    }
  }
}

TEST(PatchNormal, A22CentredTreadsMergeAcrossTheirRidge) {
  // At 0 mm the search finds two tread candidates behind a ridge some 10 um high; 10 kN takes the
  // wheel some 15 um down, across it: by default the two make one patch, at the lower candidate,
  // each lump by its own strips with the amplitudes coupled. Against the exact solver on the
  // merged gap (one 40 x 40 element is some 0.4 mm wide laterally): at the same approach fn
  // within 8 % and pmax within 4 % (measured +6.2 % and -2.6 %: the lumps' semi-elliptic strips
  // stop at the ridge, where the exact pressure passes over it); at the load pmax within 6 %
  // (measured -4.3 %) and the approach within 5 % (measured -3.5 %); the lateral edges within
  // 0.3 mm at both.
  const BenchmarkState s = benchmarkState(0.0);
  ASSERT_EQ(s.wheel.status, NormalStatus::kOk) << s.wheel.message;
  ASSERT_EQ(s.geo.candidates.size(), 2u);
  const int p = s.geo.closest, q = 1 - p;
  const NormalPatch& patch = s.wheel.patches[p];
  EXPECT_EQ(patch.status, NormalStatus::kOk);
  EXPECT_EQ(patch.merged_into, -1);
  EXPECT_NE(patch.message.find("merged"), std::string::npos) << patch.message;
  EXPECT_EQ(s.wheel.patches[q].merged_into, p);
  EXPECT_EQ(s.wheel.patches[q].fn, 0.0);
  EXPECT_NEAR(patch.fn * s.geo.candidates[p].normal.y(), kLoad, 1e-6 * kLoad);
  // The merged patch spans both candidates: from the lower one's point past the other's.
  const ContactCandidate& other = s.geo.candidates[q];
  const double other_eta = (other.point - s.geo.candidates[p].point).norm();
  EXPECT_GT(patch.eta_max - patch.eta_min, other_eta);

  std::vector<double> ridges;
  const ContactCandidate merged = mergeCandidates(s.geo.candidates, 0, 1, p, &ridges);
  ASSERT_EQ(ridges.size(), 1u);
  const ExactPatch e = exactPatch(merged, patch.approach, 40, 40);
  ASSERT_TRUE(e.solution.converged);
  EXPECT_NEAR(patch.fn, e.fn, 0.08 * e.fn);
  EXPECT_NEAR(patch.pmax, e.pmax, 0.04 * e.pmax);
  EXPECT_NEAR(patch.eta_min, e.eta_min, 3e-4);
  EXPECT_NEAR(patch.eta_max, e.eta_max, 3e-4);
  // One strip patch over both lumps (solvePatchNormal on the merged gap): without
  // continuous_region its region spreads past the ridge and fn is some 30 % high (measured
  // +30.3 %), the lumps must do better; with it (the default) the one patch is as near exact as
  // the lumps (measured fn -5.3 %, pmax -1.0 %, edges 0.09 mm outside and 0.28 mm inside), within
  // the lumps' bounds.
  NormalOptions kpec;
  kpec.continuous_region = false;
  const NormalPatch single_kpec = solvePatchNormal(merged, patch.approach, kG, kNu, kpec);
  EXPECT_GT(std::abs(single_kpec.fn - e.fn), 2.0 * std::abs(patch.fn - e.fn));
  const NormalPatch single = solvePatchNormal(merged, patch.approach, kG, kNu);
  EXPECT_NEAR(single.fn, e.fn, 0.08 * e.fn);
  EXPECT_NEAR(single.pmax, e.pmax, 0.04 * e.pmax);
  EXPECT_NEAR(single.eta_min, e.eta_min, 3e-4);
  EXPECT_NEAR(single.eta_max, e.eta_max, 3e-4);

  // The exact approach that carries the load (secant from the method's).
  const double nz = merged.normal.y();
  double a0 = 0.9 * patch.approach, a1 = patch.approach;
  double r0 = exactPatch(merged, a0, 40, 40).fn * nz - kLoad, r1 = e.fn * nz - kLoad;
  ExactPatch at_load = e;
  for (int it = 0; it < 20 && std::abs(r1) > 1e-4 * kLoad; ++it) {
    const double a2 = a1 - r1 * (a1 - a0) / (r1 - r0);
    a0 = a1;
    r0 = r1;
    a1 = a2;
    at_load = exactPatch(merged, a1, 40, 40);
    r1 = at_load.fn * nz - kLoad;
  }
  ASSERT_LT(std::abs(r1), 1e-4 * kLoad);
  EXPECT_NEAR(patch.approach, a1, 0.05 * a1);
  EXPECT_NEAR(patch.pmax, at_load.pmax, 0.06 * at_load.pmax);
  EXPECT_NEAR(patch.eta_min, at_load.eta_min, 3e-4);
  EXPECT_NEAR(patch.eta_max, at_load.eta_max, 3e-4);
}

TEST(PatchNormal, OverlappingNeighboursAreCutWhereTheyCrossAndMerge) {
  // Two tread candidates in one plane whose gap functions overlap by 1.5 mm (a contact table's
  // interpolated function runs on past the ridge): a's gap e^2 / (1 m), b's 1 um + (e - 6 mm)^2 /
  // (1 m), crossing at e = 3.083 mm where the gap is 9.51 um. They are cut there (the lower
  // envelope's highest sample), so that they meet at a ridge and merge as the search's do.
  auto candidate = [](double y, double g0, double from, double to) {
    ContactCandidate c;
    c.point = Eigen::Vector3d(0.0, y, 0.0);
    c.normal = Eigen::Vector2d(0.0, 1.0);
    c.gap = c.vertical_gap = g0;
    for (double e = from; e <= to + 1e-12; e += 1e-4) {
      GapSample s;
      s.eta = e;
      s.gap = g0 + e * e;
      s.rolling_radius = 0.46;
      c.gap_function.push_back(s);
    }
    return c;
  };
  const std::vector<ContactCandidate> cs = {candidate(-0.75, 0.0, -6e-3, 4.5e-3),
                                            candidate(-0.744, 1e-6, -3e-3, 6e-3)};
  const double ridge = ridgeApproach(cs[0], cs[1]);
  ASSERT_TRUE(std::isfinite(ridge));
  // The lower of the two cut ends: within a sample's step (0.1 mm, some 0.6 um here) below it.
  EXPECT_LE(ridge, 9.51e-6);
  EXPECT_GT(ridge, 8.8e-6);
  std::vector<double> ridges;
  const ContactCandidate merged = mergeCandidates(cs, 0, 1, 0, &ridges);
  ASSERT_EQ(ridges.size(), 1u);
  EXPECT_NEAR(ridges[0], 3.083e-3, 1e-4);
  // Past the crossing the merged function is b's (the lower), not a's running on.
  for (const GapSample& s : merged.gap_function) {
    const double b = 1e-6 + (s.eta - 6e-3) * (s.eta - 6e-3);
    if (s.eta > ridges[0] + 1e-4 && s.eta < 6e-3) {
      EXPECT_NEAR(s.gap, b, 1e-9) << s.eta;
    }
  }
  // At an approach past the ridge the two make one patch across it.
  WheelContactGeometry geo;
  geo.candidates = cs;
  geo.closest = 0;
  const WheelNormal w = solveWheelLoad(geo, 2e4, kG, kNu);
  ASSERT_EQ(w.status, NormalStatus::kOk) << w.message;
  EXPECT_GT(w.vertical_approach, ridge);
  EXPECT_EQ(w.patches[1].merged_into, 0);
  EXPECT_LT(w.patches[0].eta_min, 0.0);
  EXPECT_GT(w.patches[0].eta_max, ridges[0]);
}

TEST(PatchNormal, A22CentredStateSolvesAtEveryLoad) {
  // Light loads keep the two tread candidates apart, heavier ones merge them: the load iteration
  // needs the force continuous across the merge (a patch that jumped to the ridge would leave
  // loads no approach carries). Every load from 0.5 to 25 kN is carried.
  const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(0.0));
  ASSERT_EQ(geo.candidates.size(), 2u);
  int merged = 0, apart = 0;
  for (double load = 500.0; load < 2.5e4; load *= 1.03) {
    const WheelNormal w = solveWheelLoad(geo, load, kG, kNu);
    ASSERT_EQ(w.status, NormalStatus::kOk) << load << " " << w.message;
    double fz = 0.0;
    for (std::size_t i = 0; i < 2; ++i) fz += w.patches[i].fn * geo.candidates[i].normal.y();
    EXPECT_NEAR(fz, load, 1e-6 * load);
    (w.patches[0].merged_into >= 0 || w.patches[1].merged_into >= 0 ? merged : apart) += 1;
  }
  EXPECT_GT(merged, 0);
  EXPECT_GT(apart, 0);
}

TEST(PatchNormal, BadInputGivesAStatusAndZeroForces) {
  const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(2.0));
  for (double load : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const WheelNormal w = solveWheelLoad(geo, load, kG, kNu);
    EXPECT_EQ(w.status, NormalStatus::kInvalidInput) << load;
    EXPECT_FALSE(w.message.empty());
    for (const NormalPatch& p : w.patches) EXPECT_EQ(p.fn, 0.0);
  }
  const WheelNormal none = solveWheelLoad(WheelContactGeometry{}, kLoad, kG, kNu);
  EXPECT_EQ(none.status, NormalStatus::kNoContact);
  // A load the sampled gap cannot carry: the patch outgrows its gap function.
  const WheelNormal deep = solveWheelLoad(geo, 1e8, kG, kNu);
  EXPECT_EQ(deep.status, NormalStatus::kBeyondGapFunction) << deep.message;
  for (const NormalPatch& p : deep.patches) {
    EXPECT_EQ(p.fn, 0.0);
    EXPECT_FALSE(std::isnan(p.pmax));
  }
  ContactCandidate bare = geo.candidates.at(0);
  bare.gap_function.clear();
  EXPECT_EQ(solvePatchNormal(bare, 1e-5, kG, kNu).status, NormalStatus::kNoGapFunction);
  EXPECT_EQ(solvePatchNormal(geo.candidates[0], std::nan(""), kG, kNu).status,
            NormalStatus::kInvalidInput);
  EXPECT_EQ(solvePatchNormal(geo.candidates[0], 1e-5, -1.0, kNu).status,
            NormalStatus::kInvalidInput);
  const NormalPatch apart = solvePatchNormal(geo.candidates[0], -1e-5, kG, kNu);
  EXPECT_EQ(apart.status, NormalStatus::kOk);
  EXPECT_EQ(apart.fn, 0.0);
}

TEST(PatchNormal, GapSamplesCarryTheWheelsRadiusAndAngle) {
  // Interpolated to eta = 0 the samples give the candidate's own point: its radius (to 1 um) and
  // contact angle (to 2 mrad: the flange's angle turns by some 0.1 rad per mm, the samples lie
  // some 0.06 mm apart, linear interpolation errs by a fraction of that).
  for (double y : {2.0, 6.5}) {
    const WheelContactGeometry geo = atFirstTouch(WheelSide::kRight, a22Right(y));
    for (const ContactCandidate& c : geo.candidates) {
      const auto& f = c.gap_function;
      ASSERT_GT(f.size(), 2u);
      std::size_t i = 0;
      while (i + 2 < f.size() && f[i + 1].eta < 0.0) ++i;
      const double t = -f[i].eta / (f[i + 1].eta - f[i].eta);
      ASSERT_GE(t, 0.0);
      ASSERT_LE(t, 1.0);
      EXPECT_NEAR(f[i].rolling_radius + t * (f[i + 1].rolling_radius - f[i].rolling_radius),
                  c.rolling_radius, 1e-6)
          << y;
      EXPECT_NEAR(f[i].contact_angle + t * (f[i + 1].contact_angle - f[i].contact_angle),
                  c.contact_angle, 2e-3)
          << y;
    }
  }
}

TEST(PatchNormal, LeftWheelMirrorsTheRight) {
  // The left wheel in the mirror image of the right's state (y, yaw, roll of the other sign)
  // sees the same geometry, so the same patches (to the search's and the iteration's rounding).
  for (double y : {0.0, 2.0, 5.0, 6.5}) {  // 0: two candidates merged across their ridge
    const WheelsetPose right = a22Right(y);
    WheelsetPose left = right;
    left.y = -right.y;
    left.yaw = -right.yaw;
    left.roll = -right.roll;
    const WheelNormal r = solveWheelLoad(atFirstTouch(WheelSide::kRight, right), kLoad, kG, kNu);
    const WheelNormal l = solveWheelLoad(atFirstTouch(WheelSide::kLeft, left), kLoad, kG, kNu);
    ASSERT_EQ(r.status, NormalStatus::kOk) << r.message;
    ASSERT_EQ(l.status, NormalStatus::kOk) << l.message;
    ASSERT_EQ(l.patches.size(), r.patches.size());
    for (std::size_t i = 0; i < r.patches.size(); ++i) {
      EXPECT_NEAR(l.patches[i].fn, r.patches[i].fn, 1e-4 * kLoad) << y;
      EXPECT_NEAR(l.patches[i].pmax, r.patches[i].pmax, 1e-4 * r.patches[i].pmax) << y;
      EXPECT_NEAR(l.patches[i].b, r.patches[i].b, 1e-4 * r.patches[i].b) << y;
      EXPECT_EQ(l.patches[i].merged_into, r.patches[i].merged_into) << y;
    }
  }
}

TEST(PatchNormal, OddGapsNeverGiveNaN) {
  // Gaps of every shape (noise, flat, hollow, steps, a flange's samples with another wheel
  // radius), approaches from none to deep: a status, finite non-negative forces, never a NaN.
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const ContactCandidate base = atFirstTouch(WheelSide::kRight, a22Right(6.5)).candidates.at(0);
  for (int k = 0; k < 300; ++k) {
    ContactCandidate c = base;
    const int kind = k % 5;
    for (GapSample& s : c.gap_function) {
      if (kind == 0) s.gap += 2e-6 * (u(rng) - 0.5);                // noise
      if (kind == 1) s.gap = c.gap + 1e-6 * u(rng);                 // flat
      if (kind == 2) s.gap = c.gap - 1e3 * s.eta * s.eta * u(rng);  // hollow
      if (kind == 3) s.gap += (s.eta > 0.0 ? 5e-5 : 0.0) * u(rng);  // a step
      if (kind == 4) s.rolling_radius *= 0.05 + 2.0 * u(rng);       // another wheel
    }
    const double approach = std::pow(10.0, -8.0 + 5.0 * u(rng)) * (u(rng) < 0.1 ? -1.0 : 1.0);
    const NormalPatch p = solvePatchNormal(c, approach, kG, kNu);
    ASSERT_TRUE(std::isfinite(p.fn) && p.fn >= 0.0) << k << " " << p.message;
    ASSERT_TRUE(std::isfinite(p.pmax) && p.pmax >= 0.0) << k;
    ASSERT_TRUE(std::isfinite(p.a) && std::isfinite(p.b) && std::isfinite(p.area)) << k;
    for (const NormalStrip& s : p.strips)
      ASSERT_TRUE(std::isfinite(s.force) && std::isfinite(s.x_lead) && std::isfinite(s.pmax)) << k;
    if (p.status != NormalStatus::kOk) {
      EXPECT_EQ(p.fn, 0.0) << k;
    }
  }
}

TEST(PatchNormal, OddMergedGapsNeverGiveNaN) {
  // The two tread candidates of the centred state with gaps of every shape, loads from light to
  // heavy, through solveWheelLoad (which merges them where the approach crosses their ridge): a
  // status, finite non-negative forces; when solved, the load carried; otherwise zero forces.
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const WheelContactGeometry base = atFirstTouch(WheelSide::kRight, a22Right(0.0));
  ASSERT_EQ(base.candidates.size(), 2u);
  for (int k = 0; k < 200; ++k) {
    WheelContactGeometry g = base;
    const int kind = k % 5;
    for (ContactCandidate& c : g.candidates)
      for (GapSample& s : c.gap_function) {
        if (kind == 0) s.gap += 2e-6 * (u(rng) - 0.5);                // noise
        if (kind == 1) s.gap = c.gap + 1e-6 * u(rng);                 // flat
        if (kind == 2) s.gap -= 2e-5 * u(rng);                        // lower, ridge and all
        if (kind == 3) s.gap += (s.eta > 0.0 ? 5e-5 : 0.0) * u(rng);  // a step
        if (kind == 4) s.rolling_radius *= 0.05 + 2.0 * u(rng);       // another wheel
      }
    const double load = std::pow(10.0, 2.0 + 3.0 * u(rng));
    const WheelNormal w = solveWheelLoad(g, load, kG, kNu);
    double fz = 0.0;
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      const NormalPatch& p = w.patches[i];
      ASSERT_TRUE(std::isfinite(p.fn) && p.fn >= 0.0) << k << " " << p.message;
      ASSERT_TRUE(std::isfinite(p.pmax) && p.pmax >= 0.0) << k;
      ASSERT_TRUE(std::isfinite(p.a) && std::isfinite(p.b) && std::isfinite(p.area)) << k;
      for (const NormalStrip& s : p.strips)
        ASSERT_TRUE(std::isfinite(s.force) && std::isfinite(s.x_lead) && std::isfinite(s.pmax))
            << k;
      fz += p.fn * g.candidates[i].normal.y();
    }
    const std::size_t jump = w.message.find("jumps from ");
    if (w.status == NormalStatus::kOk && jump != std::string::npos) {
      // A load inside a jump of the force in the approach: the side nearer the load.
      double below = 0.0, above = 0.0;
      ASSERT_EQ(std::sscanf(w.message.c_str() + jump, "jumps from %lf N to %lf N", &below, &above),
                2)
          << w.message;
      EXPECT_LT(below, load) << k;
      EXPECT_GT(above, load) << k;
      const double nearer = above - load < load - below ? above : below;
      EXPECT_NEAR(fz, nearer, 1e-6 * nearer) << k << " " << w.message;
    } else if (w.status == NormalStatus::kOk) {
      EXPECT_NEAR(fz, load, 1e-5 * load) << k;
    } else {
      EXPECT_EQ(fz, 0.0) << k << " " << w.message;
    }
  }
}
