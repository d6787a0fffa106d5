// Regression tests of the fuzzing findings (test/fuzz/, doc/hardening.md): each
// failed before its fix.
#include <gtest/gtest.h>

#include <cmath>

#include "core/fastsim/fastsim.hpp"
#include "core/models/exact_model.hpp"
#include "core/models/nss_model.hpp"
#include "wheel_rail_contact/contact_model.hpp"

using namespace wheel_rail_contact;

namespace {

ContactParameters params(const char* model, const char* mesh, int n) {
  ContactParameters p;
  p.model = model;
  p.mesh = mesh;
  p.nx = p.ny = n;
  return p;
}

}  // namespace

// dt = 0 after the load fell: the held traction was integrated against the old load, 4.4 mu fz.
TEST(Hardening, HeldTractionRespectsTheNewLoadsBound) {
  for (const char* model : {"shen-li", "nss"})
    for (const char* mesh : {"fixed", "adaptive"}) {
      auto m = makeContactModel(params(model, mesh, 16));
      m->step({1e-3, 20.0, 0.05, 0.05, 0.0, 8e4});  // saturated at 80 kN
      const StepOutput o = m->step({0.0, 20.0, 0.05, 0.05, 0.0, 1e3});
      ASSERT_EQ(o.status, StepStatus::kOk);
      EXPECT_LE(std::hypot(o.fx, o.fy), 0.3 * 1e3 * (1 + 1e-9)) << model << " " << mesh;
      const TractionField& f = dynamic_cast<const NssModel&>(*m).traction();
      for (Eigen::Index k = 0; k < f.tx.size(); ++k)
        ASSERT_LE(std::hypot(f.tx(k), f.ty(k)), f.bound(k) * (1 + 1e-9)) << model << " " << k;
    }
}

// dt = 0 with the load unchanged still returns the previous step's forces exactly.
TEST(Hardening, HeldTractionAtTheSameLoadIsThePreviousStep) {
  auto m = makeContactModel(params("nss", "adaptive", 12));
  const StepOutput a = m->step({1e-3, 20.0, 2e-3, 1e-3, 1.0, 8e4});
  const StepOutput b = m->step({0.0, 20.0, 2e-3, 1e-3, 1.0, 8e4});
  EXPECT_NEAR(a.fx, b.fx, 1e-12 * std::abs(a.fx));
  EXPECT_NEAR(a.fy, b.fy, 1e-12 * std::abs(a.fy));
  EXPECT_EQ(a.adhesionFraction, b.adhesionFraction);
}

// Huge inputs overflowed the FastSim march (NaN forces, poisoned history): now out of range.
TEST(Hardening, HugeInputsAreRejectedAndLeaveTheStateAlone) {
  for (const char* model : {"steady", "shen-li", "nss", "exact"}) {
    auto m = makeContactModel(params(model, "fixed", 6));
    m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
    for (StepInput in :
         {StepInput{1e-3, 20.0, 1e13, 0.0, 0.0, 8e4}, StepInput{1e-3, 20.0, 2e-3, 0.0, -1e13, 8e4},
          StepInput{1e13, 20.0, 2e-3, 0.0, 0.0, 8e4}}) {
      const StepOutput o = m->step(in);
      EXPECT_EQ(o.status, StepStatus::kRejected) << model;
      EXPECT_EQ(o.fx, 0.0) << model;
    }
    const StepOutput o = m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
    EXPECT_TRUE(std::isfinite(o.fx) && o.fx != 0.0) << model;
  }
}

// A load of 1e-200 N made the exact solver's squared tractions underflow: NaN forever after.
TEST(Hardening, NegligibleLoadIsNoContact) {
  for (const char* model : {"steady", "nss", "exact"}) {
    auto m = makeContactModel(params(model, "fixed", 5));
    m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
    EXPECT_EQ(m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 1e-200}).status, StepStatus::kNoLoad);
    EXPECT_EQ(m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 1e-6}).status, StepStatus::kOk) << model;
    m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
    const StepOutput o = m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
    EXPECT_TRUE(std::isfinite(o.fx) && o.fx < 0.0) << model;
  }
}

// A travel of 1e24 m (V and dt at 1e12) overflowed the exact model's cast of the element count to
// long (UB under -fsanitize=undefined): now clamped first; the step restarts 10 nx elements before
// its end.
TEST(Hardening, ExactModelLongTravelRestartsFromRest) {
  ExactModel m(params("exact", "fixed", 6));
  m.step({0.0, 1e12, 2e-3, 0.0, 0.0, 8e4});
  const StepOutput o = m.step({1e12, 1e12, 2e-3, 0.0, 0.0, 8e4});
  EXPECT_EQ(m.subSteps(), 10 * 6);
  EXPECT_TRUE(std::isfinite(o.fx) && o.fx < 0.0);
}

// A subnormal V (travel V dt far below the patch) made the time term 1 / (V dt) infinite: NaN.
TEST(Hardening, NegligibleTravelHoldsTheHistory) {
  for (const char* mesh : {"fixed", "adaptive"}) {
    auto m = makeContactModel(params("shen-li", mesh, 8));
    const StepOutput a = m->step({1e-3, 20.0, 0.05, 0.0, 0.0, 2e4});
    const StepOutput b = m->step({0.08, 8e-317, 0.05, 0.0, 0.0, 2e4});
    ASSERT_EQ(b.status, StepStatus::kOk);
    // Held, up to the rounding of re-saturating the slipping nodes.
    EXPECT_NEAR(a.fx, b.fx, 1e-12 * std::abs(a.fx)) << mesh;
  }
}

// A light load on an even grid: the patch held no element centre and step() threw (the model
// contract is never to throw for input); now the central elements carry it.
TEST(Hardening, ExactModelPatchSmallerThanAnElement) {
  ContactParameters p = params("exact", "fixed", 4);
  auto m = makeContactModel(p);
  m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 8e4});
  StepOutput o;
  ASSERT_NO_THROW(o = m->step({1e-3, 20.0, 2e-3, 0.0, 0.0, 78.125}));
  EXPECT_EQ(o.status, StepStatus::kOk);
  EXPECT_LE(std::hypot(o.fx, o.fy), p.mu * 8e4);
  EXPECT_TRUE(std::isfinite(o.fx));
}

// A traction of 1e-200 Pa squared underflows to 0: it was kept at a node whose bound is 0.
TEST(Hardening, SubnormalTractionSaturatesAtAZeroBound) {
  TractionField f;
  f.resize(1);
  StripSums strip;
  double tx = 1e-200, ty = -1e-200;
  strip.node(0, 0.0, 0.0, &tx, &ty, FieldPointers(&f));
  EXPECT_EQ(f.tx(0), 0.0);
  EXPECT_EQ(f.ty(0), 0.0);
  EXPECT_TRUE(f.slip(0));
}

// A subnormal creepage made the exact solver's slip solve NaN.
TEST(Hardening, ExactModelSubnormalCreepage) {
  auto m = makeContactModel(params("exact", "fixed", 6));
  m->step({1e-3, 10.0, 2e-3, 0.0, 0.0, 8e4});
  const StepOutput o = m->step({1e-3, 10.0, 1.9e-314, 0.0, 0.0, 8e4});
  EXPECT_TRUE(std::isfinite(o.fx) && std::isfinite(o.fy) && std::isfinite(o.mz));
}

// validate() took any positive finite material: mu = 1e-200 or G = 1e200 made the exact solver
// NaN. It now holds them to physical ranges; at every corner of those ranges each model is finite.
TEST(Hardening, ParametersOutsideThePhysicalRangesAreRefused) {
  auto refused = [](void (*set)(ContactParameters*)) {
    ContactParameters p;
    set(&p);
    EXPECT_THROW(validate(p), std::invalid_argument);
  };
  refused([](ContactParameters* p) { p->mu = 1e-200; });
  refused([](ContactParameters* p) { p->G = 1e200; });
  refused([](ContactParameters* p) { p->a0 = p->b0 = 2.0; });
  refused([](ContactParameters* p) { p->fz0 = 1e-9; });
}

TEST(Hardening, EveryModelIsFiniteAtTheCornersOfThePhysicalRanges) {
  struct Corner {
    double G, mu, a0, fz0;
  };
  for (const Corner c : {Corner{1e3, 1e-6, 1e-6, 1e9}, Corner{1e13, 1e3, 1.0, 1e-6},
                         Corner{1e13, 1e-6, 1e-6, 1e-6}, Corner{1e3, 1e3, 1.0, 1e9}}) {
    for (const char* model : {"steady", "nss", "exact"}) {
      ContactParameters p = params(model, "fixed", 6);
      p.G = c.G;
      p.mu = c.mu;
      p.a0 = p.b0 = c.a0;
      p.fz0 = c.fz0;
      auto m = makeContactModel(p);
      for (int k = 0; k < 4; ++k) {
        const double fz = c.fz0 * (1.0 + 0.2 * k);
        const StepOutput o = m->step({1e-4, 20.0, 2e-3, -1e-3, 1.0, fz});
        ASSERT_TRUE(std::isfinite(o.fx) && std::isfinite(o.fy) && std::isfinite(o.mz))
            << model << " G " << c.G << " mu " << c.mu << " a0 " << c.a0 << " fz0 " << c.fz0;
        EXPECT_LE(std::hypot(o.fx, o.fy), c.mu * fz * (1 + 1e-9)) << model;
      }
    }
  }
}
