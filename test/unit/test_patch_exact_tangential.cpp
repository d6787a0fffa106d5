// The exact tangential solution on a patch's own gap (validation/patch_exact.hpp): on an elliptic
// (Hertz) gap against the exact model on the Hertz ellipse and against Kalker's linear theory
// (FastSim's linear limit); the spin's lever from the candidate's contact point on a patch whose
// centre lies beside it; the left wheel's mirror; the transient's approach to the steady state.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/models/exact_model.hpp"
#include "validation/manchester_a22.hpp"
#include "validation/patch_exact.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

using namespace wheel_rail_contact;

namespace {

const double kG = 8.2e10, kNu = 0.28, kMu = 0.3;
/// The gap B eta^2 + x^2 / (2 r): a wheel of radius 0.46 m, a/b about 1.3; at 20 um of approach
/// about 8.4 kN on a 6.3 x 4.8 mm patch.
const double kR = 0.46, kB = 1.6, kApproach = 2e-5;

/// A candidate whose gap is the Hertz gap about eta = centre (the candidate's point at eta = 0).
ContactCandidate hertzCandidate(double centre = 0.0) {
  ContactCandidate c;
  c.normal = Eigen::Vector2d(0.0, 1.0);
  const int samples = 81;
  const double half_width = 0.012;
  for (int i = 0; i < samples; ++i) {
    GapSample s;
    s.eta = -half_width + 2.0 * half_width * i / (samples - 1);
    s.gap = kB * (s.eta - centre) * (s.eta - centre);
    s.rolling_radius = kR;
    c.gap_function.push_back(s);
  }
  c.gap = kB * centre * centre;
  return c;
}

HertzEllipse ellipseOf(const ExactPatch& e) {
  return hertzFromCurvatures(e.fn, 1.0 / (2.0 * kR), kB, kG, kNu);
}

/// The exact model (transient rolling on the discrete Hertz pressure) rolled 40 a at constant
/// creepages from rest: its steady state (a step beyond 10 grid lengths restarts 10 grid lengths
/// before its end, a start-up decayed by e^-20).
StepOutput exactModelSteady(const HertzEllipse& h, double fn, const Creepages& w, int n) {
  ContactParameters p;
  p.model = "exact";
  p.a0 = h.a;
  p.b0 = h.b;
  p.fz0 = fn;
  p.nx = n;
  p.ny = n;
  p.mu = kMu;
  ExactModel m(p);
  m.step({0.0, 1.0, w.xi, w.eta, w.phi, fn});
  return m.step({40.0 * h.a, 1.0, w.xi, w.eta, w.phi, fn});
}

}  // namespace

TEST(PatchExactTangential, EllipticPatchAgreesWithTheExactModel) {
  // The same continuous problem discretised twice: our grid over the gap's interpenetration region
  // (24 x 24, dx = 0.117 a) with the discrete normal problem on the gap, and the exact model's
  // over [-1.1, 1.1] of its patch at 1.5 fn (24 x 24, dx = 0.105 a) with the discrete Hertz
  // problem. Measured: within 0.35 % of mu fn on fx and fs and 0.1 % of mu fn sqrt(ab) on mz, in
  // partial slip (adhesion 0.25 to 0.7). Each alone against 64 x 64: up to 1.3 % of mu fn (ours).
  const ExactPatch e = exactPatchNormal(hertzCandidate(), kApproach, kG, kNu, 24, 24);
  ASSERT_TRUE(e.solution.converged);
  const HertzEllipse h = ellipseOf(e);
  const double scale = kMu * e.fn, lever = std::sqrt(h.a * h.b);
  ExactPatchTangential exact(e, WheelSide::kRight, kG, kNu);
  for (const Creepages& w : std::vector<Creepages>{
           {1e-3, 0.0, 0.0}, {0.0, 1e-3, 0.0}, {0.0, 0.0, 0.3}, {1e-3, 0.5e-3, 0.3}}) {
    const ExactTangential t = exact.steady(w, kMu);
    const StepOutput o = exactModelSteady(h, e.fn, w, 24);
    ASSERT_TRUE(t.converged);
    ASSERT_EQ(o.status, StepStatus::kOk);
    EXPECT_LT(t.adhesion_fraction, 0.9);  // partial slip
    EXPECT_NEAR(t.fx, o.fx, 0.01 * scale) << w.xi << " " << w.eta << " " << w.phi;
    EXPECT_NEAR(t.fs, o.fy, 0.01 * scale) << w.xi << " " << w.eta << " " << w.phi;
    EXPECT_NEAR(t.mz, o.mz, 0.01 * scale * lever) << w.xi << " " << w.eta << " " << w.phi;
  }
}

TEST(PatchExactTangential, LinearLimitIsKalkersAsEllipticFastSimGivesIt) {
  // Full adhesion (mu large: the linear limit of small creepages): fx, fs against classic steady
  // FastSim on the Hertz ellipse at tiny creepages, whose flexibilities give Kalker's C11, C22,
  // C23 exactly; the spin moment from eta against C23 by reciprocity, Mz = G (ab)^(3/2) C23 eta.
  // The discrete exact coefficients exceed Kalker's by O(dx): measured at 32 x 32 (dx = 0.087 a)
  // +3.3 % (C11), +3.8 % (C22), +4.1 % (C23), +0.3 % (the moment); at 64 x 64 about +1.5 % each.
  // Asserted within 5 % at 32 x 32.
  const ExactPatch e = exactPatchNormal(hertzCandidate(), kApproach, kG, kNu, 32, 32);
  const HertzEllipse h = ellipseOf(e);
  ContactParameters p;
  p.model = "steady";
  p.fastsim = FastSimVariant::kClassic;
  p.a0 = h.a;
  p.b0 = h.b;
  p.fz0 = e.fn;
  ExactPatchTangential exact(e, WheelSide::kRight, kG, kNu);
  const double mu = 1e6;
  const double xi = 1e-6, eta = 1e-6, phi = 1e-4;
  const auto fastsim = [&](const Creepages& w) {
    return makeContactModel(p)->step({0.0, 1.0, w.xi, w.eta, w.phi, e.fn});
  };
  const ExactTangential tx = exact.steady({xi, 0.0, 0.0}, mu);
  const ExactTangential ty = exact.steady({0.0, eta, 0.0}, mu);
  const ExactTangential ts = exact.steady({0.0, 0.0, phi}, mu);
  EXPECT_DOUBLE_EQ(tx.adhesion_fraction, 1.0);
  const StepOutput fx = fastsim({xi, 0.0, 0.0}), fy = fastsim({0.0, eta, 0.0}),
                   fs = fastsim({0.0, 0.0, phi});
  EXPECT_LT(fx.fx, 0.0);
  EXPECT_NEAR(tx.fx, fx.fx, 0.05 * std::abs(fx.fx));
  EXPECT_NEAR(ty.fs, fy.fy, 0.05 * std::abs(fy.fy));
  EXPECT_NEAR(ts.fs, fs.fy, 0.05 * std::abs(fs.fy));
  const double g23 = -fs.fy / phi;  // G (ab)^(3/2) C23
  EXPECT_GT(g23, 0.0);
  EXPECT_NEAR(ty.mz, g23 * eta, 0.05 * g23 * eta);
  EXPECT_NEAR(tx.fs, 0.0, 1e-9 * std::abs(tx.fx));
  EXPECT_NEAR(ty.fx, 0.0, 1e-9 * std::abs(ty.fs));
}

TEST(PatchExactTangential, SpinLeverIsMeasuredFromTheContactPoint) {
  // The same Hertz gap with its centre 3 mm from the candidate's point (toward the track centre,
  // +eta): on the right wheel the patch's centre is at contact y0 = +3 mm, and the rigid slip
  // xi - phi y = (xi - phi y0) - phi (y - y0). Creepages at the contact point must give the
  // centred patch's forces for xi - phi y0, and its moment carried to the contact point,
  // mz = mz_centre - y0 fx. The two grids differ a little (each over its own samples):
  // within 0.3 % of mu fn, against a difference of phi y0 C11 (some 40 % of mu fn) had the lever
  // been taken from the grid's centre.
  const double y0 = 3e-3;
  const ExactPatch centred = exactPatchNormal(hertzCandidate(), kApproach, kG, kNu, 20, 20);
  const ExactPatch beside =
      exactPatchNormal(hertzCandidate(y0), kApproach - kB * y0 * y0, kG, kNu, 20, 20);
  ASSERT_NEAR(beside.eta_offset, y0, 0.5e-3);
  ASSERT_NEAR(beside.fn, centred.fn, 0.01 * centred.fn);
  const double scale = kMu * centred.fn;
  const Creepages w{2e-4, 3e-4, 0.3};
  const ExactTangential c = exactPatchTangential(centred, WheelSide::kRight, kG, kNu,
                                                 {w.xi - w.phi * y0, w.eta, w.phi}, kMu, beside.fn);
  const ExactTangential b = exactPatchTangential(beside, WheelSide::kRight, kG, kNu, w, kMu);
  EXPECT_GT(std::abs(w.phi * y0 * c.fx / (w.xi - w.phi * y0)), 0.3 * scale);
  EXPECT_NEAR(b.fx, c.fx, 0.003 * scale);
  EXPECT_NEAR(b.fs, c.fs, 0.003 * scale);
  EXPECT_NEAR(b.mz, c.mz - y0 * c.fx, 0.003 * scale * y0);
}

TEST(PatchExactTangential, LeftWheelIsTheRightWheelsMirror) {
  // On the left wheel the contact frame's y is -eta: the same candidate there is the right
  // wheel's mirrored across x, so (xi, eta, phi) on the left gives (fx, -fs, -mz) of
  // (xi, -eta, -phi) on the right (the half-spaces are isotropic). A patch beside its point makes
  // the mirror matter.
  const double y0 = 3e-3;
  const ExactPatch e =
      exactPatchNormal(hertzCandidate(y0), kApproach - kB * y0 * y0, kG, kNu, 20, 20);
  const double scale = kMu * e.fn;
  const Creepages w{2e-4, 3e-4, 0.3};
  ExactPatchTangential left(e, WheelSide::kLeft, kG, kNu);
  EXPECT_NEAR(left.lateralOffset(), -e.eta_offset, 1e-15);
  const ExactTangential l = left.steady(w, kMu);
  const ExactTangential r =
      exactPatchTangential(e, WheelSide::kRight, kG, kNu, {w.xi, -w.eta, -w.phi}, kMu);
  EXPECT_NEAR(l.fx, r.fx, 1e-6 * scale);
  EXPECT_NEAR(l.fs, -r.fs, 1e-6 * scale);
  EXPECT_NEAR(l.mz, -r.mz, 1e-6 * scale * y0);
  // and it is not the unmirrored answer: the spin's lever changes side
  const ExactTangential same = exactPatchTangential(e, WheelSide::kRight, kG, kNu, w, kMu);
  EXPECT_GT(std::abs(l.fx - same.fx), 0.1 * scale);
}

TEST(PatchExactTangential, TransientFromRestSettlesOnTheSteadySolution) {
  // Constant creepages from rest, one element dx per step: the first step carries one element's
  // worth of strain (small), the force grows to the steady one; after 6 grid lengths (about 8 a)
  // it is the steady solution within 0.1 % of mu fn. clearHistory restarts from rest.
  const ExactPatch e = exactPatchNormal(hertzCandidate(), kApproach, kG, kNu, 20, 20);
  const double scale = kMu * e.fn;
  const Creepages w{1e-3, 0.5e-3, 0.3};
  ExactPatchTangential exact(e, WheelSide::kRight, kG, kNu);
  const ExactTangential steady = exact.steady(w, kMu);
  EXPECT_NEAR(exact.dx(), e.grid.dx, 0.0);
  const ExactTangential first = exact.step(w, kMu);
  EXPECT_LT(std::hypot(first.fx, first.fs), 0.3 * std::hypot(steady.fx, steady.fs));
  ExactTangential t = first;
  for (int k = 1; k < 6 * e.grid.mx; ++k) t = exact.step(w, kMu);
  EXPECT_TRUE(t.converged);
  EXPECT_NEAR(t.fx, steady.fx, 1e-3 * scale);
  EXPECT_NEAR(t.fs, steady.fs, 1e-3 * scale);
  exact.clearHistory();
  const ExactTangential again = exact.step(w, kMu);
  EXPECT_NEAR(again.fx, first.fx, 1e-9 * scale);
  EXPECT_NEAR(again.fs, first.fs, 1e-9 * scale);
}

TEST(PatchExactTangential, FullSlidingGivesMuTimesTheGivenNormalForce) {
  const ExactPatch e = exactPatchNormal(hertzCandidate(), kApproach, kG, kNu, 16, 16);
  const double fn = 1.1 * e.fn;
  const ExactTangential t =
      exactPatchTangential(e, WheelSide::kRight, kG, kNu, {0.05, 0.0, 0.0}, kMu, fn);
  EXPECT_NEAR(t.fx, -kMu * fn, 1e-5 * kMu * fn);
  EXPECT_DOUBLE_EQ(t.adhesion_fraction, 0.0);
}

TEST(PatchExactTangential, APatchWithoutLoadIsRefused) {
  EXPECT_THROW(ExactPatchTangential(ExactPatch{}, WheelSide::kRight, kG, kNu),
               std::invalid_argument);
}

TEST(PatchExactTangential, SteadyAndTransientAgreeOnAGaugeCornerPatch) {
  // A general gap: the right wheel's gauge-corner patch of Manchester case at 5.5 mm (a/b
  // about 6, the pressure not Hertz's), its exact pressure at the wheel's 10 kN, with that case's
  // creepages scaled down. The steady solve (the steady system) and the transient march from rest
  // (one element a step) are two routes to the same steady state: within 0.1 % of mu fn after 6
  // grid lengths.
  const ContactSearch search{WheelsetTrackData{}};
  A22State s;
  for (const A22State& t :
       readA22States(std::string(WRC_SOURCE_DIR) + "/test/data/profiles/a22_cases.csv"))
    if (t.side == WheelSide::kRight && t.y_mm == 5.5) s = t;
  ASSERT_EQ(s.y_mm, 5.5);
  A22Options o;
  o.exact_mx = 20;
  o.exact_my = 16;
  const A22Wheel w = runA22Wheel(search, s, o);
  const A22Patch* corner = nullptr;
  for (const A22Patch& p : w.patches)
    if (p.exact.fn > 0.0) corner = &p;
  ASSERT_NE(corner, nullptr);
  ASSERT_EQ(corner->candidate.zone, ContactZone::kGaugeCorner);
  ExactPatch e;
  e.grid = corner->exact.grid;
  e.eta_offset = corner->exact.eta_offset;
  e.solution.p = corner->exact.p;
  e.fn = corner->exact.fn;
  const Creepages w0{corner->creepages.xi, corner->creepages.eta, corner->creepages.phi};
  // A twentieth of the case's creepages (eta 0.014; adhesion 0.69): partial slip, where the routes
  // differ most.
  const Creepages c{0.05 * w0.xi, 0.05 * w0.eta, 0.05 * w0.phi};
  ExactPatchTangential exact(e, WheelSide::kRight, kG, kNu);
  const ExactTangential steady = exact.steady(c, kMu);
  ASSERT_TRUE(steady.converged);
  EXPECT_GT(steady.adhesion_fraction, 0.05);
  EXPECT_LT(steady.adhesion_fraction, 0.95);
  ExactTangential t;
  for (int k = 0; k < 6 * e.grid.mx; ++k) t = exact.step(c, kMu);
  const double scale = kMu * e.fn;
  EXPECT_NEAR(t.fx, steady.fx, 1e-3 * scale);
  EXPECT_NEAR(t.fs, steady.fs, 1e-3 * scale);
  EXPECT_NEAR(t.mz, steady.mz, 1e-3 * scale * 1e-3);
}
