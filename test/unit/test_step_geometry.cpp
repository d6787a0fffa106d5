// Per-step contact geometry and friction (StepInput::a, b, mu): screening, and every model
// honouring them.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/models/exact_model.hpp"
#include "core/models/nss_model.hpp"
#include "core/models/steady_model.hpp"

using namespace wheel_rail_contact;

namespace {

ContactParameters params(const std::string& model, const std::string& mesh = "fixed") {
  ContactParameters p;
  p.model = model;
  p.mesh = mesh;
  p.nx = p.ny = model == "exact" ? 10 : 12;
  return p;
}

StepInput rolling(double xi, double eta = 0.0, double phi = 0.0, double fz = 8e4) {
  StepInput in;
  in.dt = 1e-4;
  in.V = 20.0;
  in.xi = xi;
  in.eta = eta;
  in.phi = phi;
  in.fz = fz;
  return in;
}

StepInput withPatch(StepInput in, double a, double b, double mu = 0.0) {
  in.a = a;
  in.b = b;
  in.mu = mu;
  return in;
}

const std::vector<std::string> kModels = {"steady", "shen-li", "nss", "auto", "exact"};

}  // namespace

TEST(StepGeometry, BadGeometryIsRejectedWithItsReasonAndLeavesTheStateUntouched) {
  struct Bad {
    double a, b, mu;
    const char* why;
  };
  const double nan = std::nan("");
  const std::vector<Bad> bad = {
      {6e-3, 0.0, 0.0, "a and b must be given together (or both 0)"},
      {0.0, 4e-3, 0.0, "a and b must be given together (or both 0)"},
      {-6e-3, 4e-3, 0.0, "a must be in [1e-6, 1] m (or 0: not given)"},
      {nan, 4e-3, 0.0, "a must be in [1e-6, 1] m (or 0: not given)"},
      {6e-3, 2.0, 0.0, "b must be in [1e-6, 1] m (or 0: not given)"},
      {6e-3, 1e-4, 0.0, "a/b must be in [0.1, 10] (Kalker's table)"},
      {0.0, 0.0, -0.3, "mu must be in [1e-6, 1000] (or 0: not given)"},
      {0.0, 0.0, nan, "mu must be in [1e-6, 1000] (or 0: not given)"},
      {0.0, 0.0, INFINITY, "mu must be in [1e-6, 1000] (or 0: not given)"},
  };
  for (const std::string& model : kModels) {
    auto m = makeContactModel(params(model));
    auto twin = makeContactModel(params(model));
    for (int k = 0; k < 3; ++k) {
      m->step(rolling(2e-3, 1e-3, 0.5));
      twin->step(rolling(2e-3, 1e-3, 0.5));
    }
    for (const Bad& b : bad) {
      const StepOutput out = m->step(withPatch(rolling(2e-3), b.a, b.b, b.mu));
      EXPECT_EQ(out.status, StepStatus::kRejected) << model << " " << b.why;
      EXPECT_STREQ(out.message, b.why) << model;
      EXPECT_EQ(out.fx, 0.0) << model;
      EXPECT_EQ(out.fy, 0.0) << model;
    }
    const StepOutput next = m->step(rolling(2e-3, 1e-3, 0.5)),
                     ref = twin->step(rolling(2e-3, 1e-3, 0.5));
    EXPECT_EQ(next.fx, ref.fx) << model;
    EXPECT_EQ(next.fy, ref.fy) << model;
    EXPECT_EQ(next.mz, ref.mz) << model;
  }
}

TEST(StepGeometry, SteadyWithAStepPatchEqualsAModelBuiltAtThatPatch) {
  const double a = 5e-3, b = 5.5e-3, fz = 6e4;
  ContactParameters at = params("steady");
  at.a0 = a;
  at.b0 = b;
  at.fz0 = fz;
  SteadyModel given(params("steady")), built(at);
  const StepOutput g = given.step(withPatch(rolling(1e-3, -2e-3, 1.5, fz), a, b)),
                   r = built.step(rolling(1e-3, -2e-3, 1.5, fz));
  EXPECT_NEAR(g.fx, r.fx, 1e-9 * std::abs(r.fx));
  EXPECT_NEAR(g.fy, r.fy, 1e-9 * std::abs(r.fy));
  EXPECT_NEAR(g.mz, r.mz, 1e-9 * std::abs(r.mz));
  EXPECT_EQ(g.a, a);
  EXPECT_EQ(g.b, b);
  // Back to the parameters' patch: the reference's a/b and coefficients again.
  SteadyModel fresh(params("steady"));
  const StepOutput back = given.step(rolling(1e-3, -2e-3, 1.5, fz)),
                   want = fresh.step(rolling(1e-3, -2e-3, 1.5, fz));
  EXPECT_EQ(back.fx, want.fx);
  EXPECT_EQ(back.fy, want.fy);
}

TEST(StepGeometry, HalvingMuHalvesTheSaturatedForceInEveryModel) {
  for (const std::string& model : kModels) {
    auto m = makeContactModel(params(model));
    StepOutput full, half;
    for (int k = 0; k < 40; ++k) full = m->step(rolling(0.05));
    for (int k = 0; k < 40; ++k) half = m->step(withPatch(rolling(0.05), 0.0, 0.0, 0.15));
    EXPECT_NEAR(full.fx, -0.3 * 8e4, 1e-3 * 0.3 * 8e4) << model;
    EXPECT_NEAR(half.fx, -0.15 * 8e4, 1e-3 * 0.15 * 8e4) << model;
  }
}

TEST(StepGeometry, NssWithAConstantStepPatchEqualsAModelBuiltAtThatPatch) {
  // On the adaptive mesh (the fixed one is sized from a0, b0): the same mesh, chi and Kalker
  // coefficients, so the same forces but for rounding.
  for (const char* model : {"nss", "shen-li"}) {
    const double a = 4.5e-3, b = 5.5e-3, fz = 7e4;
    ContactParameters at = params(model, "adaptive");
    at.a0 = a;
    at.b0 = b;
    at.fz0 = fz;
    auto given = makeContactModel(params(model, "adaptive")), built = makeContactModel(at);
    for (int k = 0; k < 60; ++k) {
      const StepInput in = rolling(2e-3 * std::cos(0.2 * k), 1e-3, 2.0, fz);
      const StepOutput g = given->step(withPatch(in, a, b)), r = built->step(in);
      ASSERT_NEAR(g.fx, r.fx, 1e-9 * 0.3 * fz) << model << " step " << k;
      ASSERT_NEAR(g.fy, r.fy, 1e-9 * 0.3 * fz) << model << " step " << k;
    }
  }
}

TEST(StepGeometry, NssCarriesItsHistoryAcrossAStepOfAOverB) {
  // Constant creepage until steady, then a/b from 1.4 to 0.7 at the same area: the force moves to
  // the new steady value without a jump to zero (the history is carried, not cleared), and gets
  // there within a few patch lengths.
  const double area = 6e-3 * 4e-3, a1 = std::sqrt(area * 1.4), b1 = std::sqrt(area / 1.4),
               a2 = std::sqrt(area * 0.7), b2 = std::sqrt(area / 0.7);
  for (const char* mesh : {"fixed", "adaptive"}) {
    ContactParameters p = params("nss", mesh);
    p.fz_max = 3.5 * p.fz0;  // the fixed mesh covers both patches (b2 = 1.46 b0)
    NssModel m(p, ChiTable::shipped());
    SteadyModel steady(params("steady"));
    StepOutput before, after, last;
    for (int k = 0; k < 200; ++k) before = m.step(withPatch(rolling(1e-3, 1e-3), a1, b1));
    after = m.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    for (int k = 0; k < 200; ++k) last = m.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    const StepOutput want = steady.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    EXPECT_GT(after.fx / before.fx, 0.8) << mesh;
    EXPECT_GT(after.fy / before.fy, 0.8) << mesh;
    // Nor a jump up: the adaptive mesh's strips kept at fixed y/b stretched the history laterally
    // with the patch's b (Fx +17 % at once here).
    EXPECT_LT(after.fx / before.fx, 1.1) << mesh;
    EXPECT_LT(after.fy / before.fy, 1.1) << mesh;
    EXPECT_NEAR(last.fx, want.fx, 0.03 * std::abs(want.fx)) << mesh;
    EXPECT_NEAR(last.fy, want.fy, 0.03 * std::abs(want.fy)) << mesh;
    EXPECT_STREQ(last.message, "") << mesh;
  }
}

TEST(StepGeometry, AChangeOfMuRescalesTheBoundAndKeepsTheHistory) {
  NssModel m(params("nss"), ChiTable::shipped());
  StepOutput before, after;
  for (int k = 0; k < 200; ++k) before = m.step(rolling(2e-4));  // nearly full adhesion
  after = m.step(withPatch(rolling(2e-4), 0.0, 0.0, 0.6));
  // Twice the friction changes little in near-full adhesion, and nothing was cleared.
  EXPECT_NEAR(after.fx, before.fx, 0.05 * std::abs(before.fx));
  // A lower friction saturates the history at once (but for the leading edge's few nodes): near
  // mu fz, never above it, not zero.
  const StepOutput low = m.step(withPatch(rolling(2e-4), 0.0, 0.0, 0.01));
  EXPECT_LE(std::abs(low.fx), 0.01 * 8e4 * (1 + 1e-9));
  EXPECT_GT(std::abs(low.fx), 0.95 * 0.01 * 8e4);
}

TEST(StepGeometry, APatchBeyondTheDefaultFixedMeshLosesNoForce) {
  // Default parameters (fixed mesh sized for fz_max = 1.5 fz0), linear range, settled: a patch
  // doubled at the same a/b and load gives four times the force (G a b C11 xi), as steady FastSim
  // and the adaptive mesh do; clipped to the mesh it gave 0.75. A patch twice as wide, and a load
  // three times fz0, give what steady FastSim's fitted mesh gives. The step that grows the mesh
  // says so; the next ones have nothing to say.
  struct Change {
    const char* what;
    StepInput before, after;
  };
  const double a0 = ContactParameters().a0, b0 = ContactParameters().b0,
               fz0 = ContactParameters().fz0;
  const std::vector<Change> changes = {
      {"a, b doubled", withPatch(rolling(1e-5), a0, b0), withPatch(rolling(1e-5), 2 * a0, 2 * b0)},
      {"b doubled", withPatch(rolling(0.0, 1e-5), a0, b0),
       withPatch(rolling(0.0, 1e-5), a0, 2 * b0)},
      {"load tripled", rolling(1e-5, 0.0, 0.0, fz0), rolling(1e-5, 0.0, 0.0, 3 * fz0)}};
  for (const char* model : {"nss", "auto"}) {
    for (const Change& c : changes) {
      ContactParameters p;
      p.model = model;
      auto m = makeContactModel(p);
      ContactParameters sp = p;
      sp.model = "steady";
      auto steady = makeContactModel(sp);
      StepOutput before, grown, after;
      for (int k = 0; k < 200; ++k) before = m->step(c.before);
      grown = m->step(c.after);
      for (int k = 0; k < 200; ++k) after = m->step(c.after);
      const StepOutput steadyBefore = steady->step(c.before), steadyAfter = steady->step(c.after);
      const bool alongX = c.before.xi != 0.0;
      const double ratio = alongX ? after.fx / before.fx : after.fy / before.fy,
                   want =
                       alongX ? steadyAfter.fx / steadyBefore.fx : steadyAfter.fy / steadyBefore.fy;
      EXPECT_NEAR(ratio, want, 0.01 * want) << model << ", " << c.what;
      if (c.after.a == 2 * a0) {
        EXPECT_NEAR(ratio, 4.0, 0.04) << model;
      }
      EXPECT_EQ(grown.status, StepStatus::kOk) << model << ", " << c.what;
      EXPECT_NE(std::string(grown.message).find("grew"), std::string::npos)
          << model << ", " << c.what << ": " << grown.message;
      EXPECT_STREQ(after.message, "") << model << ", " << c.what;
    }
  }
}

TEST(StepGeometry, TheFixedMeshGrowsWithTheHistoryCarriedAndStaysGrownUntilReset) {
  // As NssCarriesItsHistoryAcrossAStepOfAOverB, with the default fz_max: the new patch (b2 =
  // 1.46 b0) is wider than the mesh (1.14 b0), which grows. The history carried over, the force
  // neither drops towards a fresh start's nor jumps; it settles on steady FastSim's.
  const double area = 6e-3 * 4e-3, a1 = std::sqrt(area * 1.4), b1 = std::sqrt(area / 1.4),
               a2 = std::sqrt(area * 0.7), b2 = std::sqrt(area / 0.7);
  for (const char* model : {"nss", "shen-li"}) {
    NssModel m(params(model), ChiTable::shipped()), fresh(params(model), ChiTable::shipped());
    SteadyModel steady(params("steady"));
    const double sizedA = m.mesh().a(), sizedB = m.mesh().b();
    ASSERT_LT(sizedB, b2);
    StepOutput before, after, last;
    for (int k = 0; k < 200; ++k) before = m.step(withPatch(rolling(1e-3, 1e-3), a1, b1));
    after = m.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    EXPECT_GE(m.mesh().b(), b2) << model;
    const StepOutput first = fresh.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    EXPECT_LT(first.fy / before.fy, 0.7) << model;  // what a cleared history would give
    EXPECT_GT(after.fx / before.fx, 0.8) << model;
    EXPECT_GT(after.fy / before.fy, 0.8) << model;
    EXPECT_LT(after.fx / before.fx, 1.1) << model;
    EXPECT_LT(after.fy / before.fy, 1.1) << model;
    for (int k = 0; k < 200; ++k) last = m.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    const StepOutput want = steady.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    EXPECT_NEAR(last.fx, want.fx, 0.03 * std::abs(want.fx)) << model;
    EXPECT_NEAR(last.fy, want.fy, 0.03 * std::abs(want.fy)) << model;
    // Back to the first patch: the mesh stays as grown.
    const double grownA = m.mesh().a(), grownB = m.mesh().b();
    m.step(withPatch(rolling(1e-3, 1e-3), a1, b1));
    EXPECT_EQ(m.mesh().a(), grownA) << model;
    EXPECT_EQ(m.mesh().b(), grownB) << model;
    // reset() and a loss of contact clear the history and give the mesh its own size again.
    m.reset();
    EXPECT_EQ(m.mesh().a(), sizedA) << model;
    EXPECT_EQ(m.mesh().b(), sizedB) << model;
    m.step(withPatch(rolling(1e-3, 1e-3), a2, b2));
    EXPECT_GT(m.mesh().b(), sizedB) << model;
    m.step(rolling(1e-3, 1e-3, 0.0, 0.0));
    EXPECT_EQ(m.mesh().b(), sizedB) << model;
  }
}

TEST(StepGeometry, ExactHonoursTheStepPatchAndRejectsOneBeyondItsGrid) {
  ContactParameters p = params("exact");
  p.fz_max = 2.0 * p.fz0;
  const double s = 4.5e-3;
  ExactModel given(p), fresh(p);
  StepOutput g, r;
  // The patch the parameters give at this load, given explicitly: the same problem.
  const HertzEllipse h = ReferencePatch{p.a0, p.b0, p.fz0}.at(7e4);
  for (int k = 0; k < 30; ++k) {
    g = given.step(withPatch(rolling(1e-3, 0.0, 0.0, 7e4), h.a, h.b));
    r = fresh.step(rolling(1e-3, 0.0, 0.0, 7e4));
  }
  EXPECT_NEAR(g.fx, r.fx, 1e-9 * std::abs(r.fx));
  // A smaller round patch differs from the elongated one in force and reports its a, b.
  for (int k = 0; k < 30; ++k) g = given.step(withPatch(rolling(1e-3, 0.0, 0.0, 7e4), s, s));
  EXPECT_EQ(g.a, s);
  EXPECT_GT(std::abs(g.fx - r.fx), 0.05 * std::abs(r.fx));
  const StepOutput beyond = given.step(withPatch(rolling(1e-3), 6e-3, 20e-3));
  EXPECT_EQ(beyond.status, StepStatus::kRejected);
  EXPECT_STREQ(beyond.message,
               "exact model: the step's a or b exceeds the fixed grid's patch (a0, b0 at fz_max)");
}

TEST(StepGeometry, ShippedChiIsStableAtEveryAOverB) {
  // nss re-picks chi at each new a/b and rejects the step where the interpolated second-order F
  // is unstable: on the shipped table that must happen nowhere in Kalker's range, on any mesh.
  const ChiTable table = ChiTable::shipped();
  for (int n : table.meshes()) {
    ContactParameters p = params("nss", "adaptive");
    p.nx = p.ny = n;
    NssModel m(p, table);
    for (int k = 0; k <= 400; ++k) {
      const double ab = 0.1001 * std::pow(9.999 / 0.1001, k / 400.0), s = 5e-3;
      const StepOutput out =
          m.step(withPatch(rolling(1e-3, 1e-3, 1.0), s * std::sqrt(ab), s / std::sqrt(ab)));
      ASSERT_EQ(out.status, StepStatus::kOk)
          << "mesh " << n << " a/b " << ab << ": " << out.message;
    }
  }
}
