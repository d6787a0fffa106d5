// Model auto on a non-Hertzian patch (StepInput::shape): it runs the patch's strips only where its
// equivalent ellipse would err by more than its share of the tolerance (ellipseDeparture,
// PatchShapeMonitor), checked on every patch of the Manchester benchmark's case against the
// exact half-space solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "../a22_states.hpp"
#include "../patch_step_input.hpp"
#include "core/exact/halfspace_solver.hpp"
#include "core/models/auto_model.hpp"
#include "validation/ellipse_patch.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

using namespace wheel_rail_contact;

namespace {

struct Forces {
  double fx = 0.0, fy = 0.0;
};

// One patch at its case's creepages: our normal problem's strips and the exact steady
// tangential solution on the exact normal solution (fx, fs in the eta frame).
struct Case {
  std::string name;
  PatchShape shape;
  double a = 0.0, b = 0.0, fn = 0.0, exact_fn = 0.0;
  double xi = 0.0, eta = 0.0, phi = 0.0;
  bool hertz = false;
  Forces exact;
  A22Exact solution;
};

Forces exactAt(const Case& c, double xi, double eta, double phi, double mu) {
  HalfspaceSolver exact(c.solution.grid, 82e9, 0.28);
  exact.setPressure(c.solution.p);
  const double e = c.solution.eta_offset;
  const HalfspaceSolution& x =
      exact.solve(RollingMode::kSteady, Creepages{xi - phi * e, eta, phi}, mu);
  return {x.fx, x.fy};
}

std::vector<Case> a22Cases(double mu) {
  const ContactSearch search{WheelsetTrackData{}};
  A22Options o;
  o.exact_mx = 24;
  o.exact_my = 18;
  std::vector<Case> out;
  for (const A22State& s : a22States()) {
    const A22Wheel w = runA22Wheel(search, s, o);
    EXPECT_TRUE(w.message.empty()) << w.message;
    for (const A22Patch& p : w.patches) {
      if (!(p.ours.fn > 0.0) || p.ours.merged_into >= 0 || !p.exact.solved) continue;
      Case c;
      char name[64];
      std::snprintf(name, sizeof name, "%s y=%.1f patch %d",
                    s.side == WheelSide::kLeft ? "left" : "right", s.y_mm, p.index);
      c.name = name;
      // The eta frame (toward the track centre) on both wheels: on the left wheel the contact
      // frame's creepages mirrored.
      const double m = s.side == WheelSide::kLeft ? -1.0 : 1.0;
      c.xi = p.creepages.xi;
      c.eta = m * p.creepages.eta;
      c.phi = m * p.creepages.phi;
      c.shape = patchShapeOf(p.ours);
      c.hertz = p.ours.method == NormalMethod::kHertz && !(p.ours.strip_weight > 0.0);
      c.a = p.ours.a;
      c.b = p.ours.b;
      c.fn = p.ours.fn;
      c.exact_fn = p.exact.fn;
      HalfspaceSolver exact(p.exact.grid, o.G, o.nu);
      exact.setPressure(p.exact.p);
      const double e = p.exact.eta_offset;  // the grid's centre from the candidate's point
      const HalfspaceSolution& x =
          exact.solve(RollingMode::kSteady, Creepages{c.xi - c.phi * e, c.eta, c.phi}, mu);
      c.exact = {x.fx, x.fy};
      c.solution = p.exact;
      out.push_back(std::move(c));
    }
  }
  return out;
}

ContactParameters paramsFor(const std::string& model, const Case& c, double mu, double tol) {
  ContactParameters q;
  q.model = model;
  q.mesh = "adaptive";
  q.mu = mu;
  q.tolerance = tol;
  q.b0 = c.b;
  q.a0 = std::min(std::max(c.a / c.b, kKalkerMinAOverB * (1 + 1e-12)),
                  kKalkerMaxAOverB * (1 - 1e-12)) *
         c.b;
  q.fz0 = c.fn;
  return q;
}

StepInput held(const Case& c, const PatchShape* shape) {
  StepInput in;
  in.V = 2.0;
  in.dt = 0.1 * c.a / in.V;
  in.xi = c.xi;
  in.eta = c.eta;
  in.phi = c.phi;
  in.fz = c.fn;
  in.a = c.a;
  in.b = c.b;
  in.shape = shape;
  return in;
}

// A model's forces at the case's creepages held for 40 steps (auto: steady FastSim).
Forces steadyForces(ContactModel& m, const StepInput& in) {
  StepOutput out;
  for (int k = 0; k < 40; ++k) out = m.step(in);
  EXPECT_EQ(out.status, StepStatus::kOk) << out.message;
  return {out.fx, out.fy};
}

double distance(const Forces& f, const Forces& g) {
  return std::hypot(f.fx - g.fx, f.fy - g.fy);
}

bool inTable(const Case& c) {
  return c.a >= kKalkerMinAOverB * c.b && c.a <= kKalkerMaxAOverB * c.b;
}

// The case's creepages, and xi, eta, spin alone small enough for linear theory (a force of about
// 1e-3 mu fz), on a patch.
std::vector<Case> probes(const Case& c) {
  std::vector<Case> out(4, c);
  const double small = 1e-6;
  out[1].xi = small, out[1].eta = out[1].phi = 0.0;
  out[2].eta = small, out[2].xi = out[2].phi = 0.0;
  out[3].phi = 1e-4, out[3].xi = out[3].eta = 0.0;
  return out;
}

}  // namespace

// The predictor against what it predicts: steady FastSim (auto's variant, calibrated) on the
// strips against the ellipse placed at their centre, over the strips' force, on every patch
// in Kalker's table at its case's creepages and at xi, eta, spin alone (linear). Classic FastSim
// is linear theory's discretisation: within 0.003 of the prediction where linear (measured
// 0.0013). At the cases' creepages (partial slip) the departure is at most the prediction plus
// 0.008 (measured 0.0051, the left wheel at 0.5 mm: the pressure's shape, which linear theory does
// not see). The calibrated variant's eta and spin drives on strips depart further from the ellipse
// than linear theory (up to 0.16 of the force, eta alone at 6 mm): not counted here, as there the
// ellipse is the nearer of the two to exact (A22ChoiceAgainstExact).
TEST(AutoPatchShape, PredictionOfTheEllipsesDepartureOnA22) {
  const double mu = 0.3;
  const std::vector<Case> cases = a22Cases(mu);
  int checked = 0;
  for (const Case& c0 : cases) {
    if (!inTable(c0)) continue;
    const std::vector<Case> cs = probes(c0);
    for (size_t k = 0; k < cs.size(); ++k) {
      const Case& c = cs[k];
      const ShapeDeparture d = ellipseDeparture(held(c, &c.shape), 82e9, 0.28, mu);
      ASSERT_GT(d.force, 0.0) << c.name;
      const double predicted = d.difference / d.force;
      for (FastSimVariant v : {FastSimVariant::kClassic, FastSimVariant::kCalibrated}) {
        if (v == FastSimVariant::kCalibrated && k > 0) continue;
        ContactParameters q = paramsFor("steady", c, mu, 0.05);
        q.fastsim = v;
        auto st = makeContactModel(q), el = makeContactModel(q);
        const Forces fs = steadyForces(*st, held(c, &c.shape));
        StepInput ein = held(c, nullptr);
        ein.xi -= c.phi * d.centre;
        const Forces fe = steadyForces(*el, ein);
        const double actual = distance(fe, fs) / std::hypot(fs.fx, fs.fy);
        if (k > 0)
          EXPECT_NEAR(actual, predicted, 0.003) << c.name << " probe " << k;
        else
          EXPECT_LT(actual, predicted + 0.008) << c.name << " " << toString(v);
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 100);
}

// Auto's choice on every patch (the shape given, as WheelsetContact gives it) against the
// exact steady solution on the exact normal solution, at tolerances 0.1, 0.05, 0.03:
// - held at the case's creepages, within the tolerance of mu Fn on every patch but the right
//   wheel's at 0.5 mm, where our normal problem misses the tread's plateau (doc/true_patch.md) and
//   the strips err by 23 % of mu Fn: there auto errs no more than they do, plus the tolerance;
// - at the case's creepages and at xi, eta, spin alone (linear), the choice costs at most the
//   tolerance of the exact force: |F_auto - F_exact| <= |F_strips - F_exact| + tol |F_exact|, the
//   strips at auto's mesh and variant;
// - the strips where the ellipse's models cannot run (a/b beyond Kalker's table) and on the centred
//   tread (two lumps, a/b 0.26), the ellipse on every Hertz patch in the table.
TEST(AutoPatchShape, A22ChoiceAgainstExact) {
  const double mu = 0.3;
  const std::vector<Case> cases = a22Cases(mu);
  ASSERT_GE(cases.size(), 40u);
  for (double tol : {0.1, 0.05, 0.03}) {
    int strips = 0, ellipse = 0;
    for (const Case& c0 : cases) {
      const std::vector<Case> cs = probes(c0);
      for (size_t k = 0; k < cs.size(); ++k) {
        const Case& c = cs[k];
        auto a = makeContactModel(paramsFor("auto", c, mu, tol));
        const Forces fa = steadyForces(*a, held(c, &c.shape));
        const auto& am = dynamic_cast<const AutoModel&>(*a);
        ContactParameters q = paramsFor("steady", c, mu, tol);
        q.fastsim = resolvedFastSim(paramsFor("auto", c, mu, tol));
        q.nx = q.ny = am.meshSize();
        auto st = makeContactModel(q);
        const Forces fs = steadyForces(*st, held(c, &c.shape));
        const Forces x = k == 0 ? c.exact : exactAt(c, c.xi, c.eta, c.phi, mu);
        const double fx = std::hypot(x.fx, x.fy);
        EXPECT_LE(distance(fa, x), distance(fs, x) + tol * fx) << c.name << " probe " << k;
        if (k > 0) continue;
        const double scale = mu * c.exact_fn;
        if (c.name == "right y=0.5 patch 0")
          EXPECT_LE(distance(fa, x), distance(fs, x) + tol * scale) << c.name;
        else
          EXPECT_LE(distance(fa, x), tol * scale) << c.name << " tolerance " << tol;
        if (!inTable(c) || c.a < 0.3 * c.b) {
          EXPECT_TRUE(am.onStrips()) << c.name;
        }
        if (c.hertz && inTable(c)) {
          EXPECT_FALSE(am.onStrips()) << c.name;
        }
        (am.onStrips() ? strips : ellipse) += 1;
      }
    }
    std::printf("tolerance %.2f: auto on the strips on %d of A-2.2's %d patches\n", tol, strips,
                strips + ellipse);
  }
}

// On Kalker's strips of an ellipse the predicted departure is the strips' quadrature's (within 2 %
// of the force), so auto runs the ellipse: its forces are those of auto given no shape (within
// 1e-9 of mu fz).
TEST(AutoPatchShape, EllipsesStripsRunAsTheEllipse) {
  const double a = 6e-3, b = 4e-3, fz = 8e4;
  const PatchShape shape = ellipseStrips(a, b, fz, 16);
  ContactParameters p;
  p.model = "auto";
  auto plain = makeContactModel(p), given = makeContactModel(p);
  for (int k = 0; k < 60; ++k) {
    StepInput in;
    in.dt = k == 0 ? 0.0 : 2e-4;
    in.V = 20.0;
    in.xi = 1.5e-3 * std::cos(0.05 * k);
    in.eta = -1e-3 * std::sin(0.07 * k);
    in.phi = 0.6;
    in.fz = fz;
    in.a = a;
    in.b = b;
    const StepOutput e = plain->step(in);
    in.shape = &shape;
    const ShapeDeparture d = ellipseDeparture(in, p.G, p.nu, p.mu);
    EXPECT_LT(d.difference, 0.02 * d.force);
    EXPECT_NEAR(d.centre, 0.0, 1e-12);
    const StepOutput s = given->step(in);
    ASSERT_EQ(s.status, StepStatus::kOk) << s.message;
    EXPECT_FALSE(dynamic_cast<const AutoModel&>(*given).onStrips());
    // The same model on the same ellipse; the strips' centre is zero up to rounding.
    EXPECT_NEAR(s.fx, e.fx, 1e-9 * p.mu * fz);
    EXPECT_NEAR(s.fy, e.fy, 1e-9 * p.mu * fz);
    EXPECT_NEAR(s.mz, e.mz, 1e-9 * p.mu * fz * a);
  }
}

// A shape the models refuse is refused by auto too, whichever geometry it would have chosen.
TEST(AutoPatchShape, BadShapeIsRejected) {
  PatchShape bad;
  bad.strips.push_back(PatchStrip{0.0, 1e-3, 1e-3, -2e-3, 1e9});  // edges not symmetric
  ContactParameters p;
  p.model = "auto";
  auto m = makeContactModel(p);
  StepInput in;
  in.dt = 1e-3;
  in.V = 20.0;
  in.xi = 1e-3;
  in.fz = 5e4;
  in.a = 5e-3;
  in.b = 4e-3;
  in.shape = &bad;
  const StepOutput out = m->step(in);
  EXPECT_EQ(out.status, StepStatus::kRejected);
  EXPECT_STRNE(out.message, "");
  EXPECT_EQ(out.fx, 0.0);
}

// A patch that turns from Hertz's ellipse into a lopsided one and back (each strip's length and
// pressure scaled by 1 + t y / b, t from 0 to 1 and back, rolled over metres at held creepages),
// at tolerances 10, 5 and 3 %, both variants: auto takes the strips once and gives them back once,
// after the predicted departure has stayed below 0.4 of the tolerance for a window, and keeps
// running steady FastSim through both switches (the creepages are held). A switch moves the force
// by the two geometries' difference, within the tolerance of mu fz (measured at most 4.4 %
// of mu fz at 10 %, 2.9 % at 5 %: with the 5x5 mesh, the ellipse's 5 strips against the shape's
// 16). With classic FastSim, whose linear forces the prediction is, by at most half the tolerance
// of the force plus 0.01 (measured 2.9 % at 5 %, 2.0 % at 3 %); the calibrated variant's drives
// on strips depart up to 2.6 times further here.
TEST(AutoPatchShape, LopsidedPatchSwitchesOnceEachWay) {
  const double a = 6e-3, b = 4e-3, fz = 8e4;
  const PatchShape ellipse = ellipseStrips(a, b, fz, 16);
  for (FastSimVariant v : {FastSimVariant::kCalibrated, FastSimVariant::kClassic})
    for (double tol : {0.1, 0.05, 0.03}) {
      ContactParameters p;
      p.model = "auto";
      p.fastsim = v;
      p.tolerance = tol;
      p.a0 = a;
      p.b0 = b;
      p.fz0 = fz;
      auto m = makeContactModel(p);
      const auto& am = dynamic_cast<const AutoModel&>(*m);
      const int ramp = 2000, hold = 500, calm = 1500, n = 2 * ramp + hold + calm;
      PatchShape shape = ellipse;
      std::vector<StepOutput> out;
      std::vector<bool> strips;
      double peakEstimate = 0.0;
      for (int k = 0; k < n; ++k) {
        const double t = k < ramp              ? double(k) / ramp
                         : k < ramp + hold     ? 1.0
                         : k < 2 * ramp + hold ? double(2 * ramp + hold - k) / ramp
                                               : 0.0;
        for (size_t j = 0; j < shape.strips.size(); ++j) {
          const PatchStrip& e = ellipse.strips[j];
          const double f = 1.0 + t * e.eta / b;
          shape.strips[j].x_lead = f * e.x_lead;
          shape.strips[j].x_trail = f * e.x_trail;
          shape.strips[j].pmax = f * e.pmax;
        }
        const StepInput in = combinedCreepageStep(&shape, a, b, fz);
        out.push_back(m->step(in));
        ASSERT_EQ(out.back().status, StepStatus::kOk) << out.back().message;
        EXPECT_FALSE(am.nonSteady()) << k;
        strips.push_back(am.onStrips());
        peakEstimate = std::max(peakEstimate, am.shapeMonitor().estimate());
      }
      const std::string what = std::string(toString(v)) + " at " + std::to_string(tol);
      EXPECT_GT(peakEstimate, 0.5 * tol) << what;  // the scene does need the strips
      const auto change = [&](size_t k) {
        return std::hypot(out[k].fx - out[k - 1].fx, out[k].fy - out[k - 1].fy);
      };
      int switches = 0;
      for (size_t k = 12; k + 12 < out.size(); ++k) {
        if (strips[k] == strips[k - 1]) continue;
        ++switches;
        double around = 0.0;
        for (size_t j = k - 10; j <= k + 10; ++j)
          if (j != k) around = std::max(around, change(j));
        EXPECT_LE(change(k), tol * p.mu * fz + around) << what << ", step " << k;
        if (v == FastSimVariant::kClassic && tol < 0.1) {
          const double force = std::hypot(out[k].fx, out[k].fy);
          EXPECT_LE(change(k), (0.5 * tol + 0.01) * force + around) << what << ", step " << k;
        }
      }
      EXPECT_EQ(switches, 2) << what;
      EXPECT_FALSE(strips.back()) << what;
    }
}
