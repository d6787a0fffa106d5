// Stability of every FastSim model exactly where methods fail: very short and very long waves,
// steps far smaller and far larger than an element, full slip, spin-dominated contact, creepages
// through zero, load lost and regained, speed through zero. Failure = NaN, a force above mu Fz,
// or an oscillation that does not die out under constant input.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "wheel_rail_contact/contact_model.hpp"

using namespace wheel_rail_contact;

namespace {

struct Case {
  double lambdaOverA, stepOverDx, xiAmp, xiMean, phi;
};

std::unique_ptr<ContactModel> model(const char* name, const char* mesh) {
  ContactParameters p;
  p.model = name;
  p.mesh = mesh;
  p.nx = p.ny = 12;
  return makeContactModel(p);
}

// Runs a harmonic xi with varying load, then holds the last input constant and checks the force
// settles (successive steps agree) without ever exceeding mu Fz or going non-finite.
void check(const char* name, const char* mesh, const Case& c) {
  auto m = model(name, mesh);
  const ContactParameters p;
  const double a = p.a0, dx = 2 * a / p.nx, V = 20.0, dt = c.stepOverDx * dx / V;
  const double lambda = c.lambdaOverA * a;
  const int steps = std::min(4000, static_cast<int>(2 * lambda / (V * dt)) + 200);
  StepInput in;
  for (int k = 0; k < steps; ++k) {
    const double q = k * V * dt;
    in = {k == 0 ? 0.0 : dt,
          V,
          c.xiMean + c.xiAmp * std::cos(2 * M_PI * q / lambda),
          -0.5 * c.xiAmp * std::sin(2 * M_PI * q / lambda),
          c.phi,
          p.fz0 * (1 + 0.2 * std::sin(2 * M_PI * q / (1.3 * lambda)))};
    const StepOutput o = m->step(in);
    ASSERT_TRUE(std::isfinite(o.fx) && std::isfinite(o.fy) && std::isfinite(o.mz))
        << name << " " << mesh << " step " << k;
    ASSERT_LE(std::hypot(o.fx, o.fy), p.mu * in.fz * (1 + 1e-9)) << name << " step " << k;
  }
  // Constant input: settles within a few patch transits.
  StepOutput prev = m->step(in), o;
  const int settle = static_cast<int>(20 * a / (V * dt)) + 20;
  for (int k = 0; k < std::min(settle, 200000); ++k) {
    o = m->step(in);
    if (k + 1 < std::min(settle, 200000)) prev = o;
  }
  EXPECT_NEAR(o.fx, prev.fx, 1e-6 * p.mu * in.fz) << name << " " << mesh;
}

}  // namespace

TEST(Stability, WavelengthStepAndSlipGrid) {
  for (const char* name : {"steady", "shen-li", "nss"})
    for (double l : {0.5, 2.0, 50.0, 200.0})
      for (double r : {0.01, 1.0, 10.0})
        for (double amp : {1e-5, 3e-3, 0.2}) check(name, "adaptive", {l, r, amp, 0.0, 0.0});
}

TEST(Stability, SpinDominatedAndFixedMesh) {
  for (const char* name : {"shen-li", "nss"})
    for (const char* mesh : {"fixed", "adaptive"})
      for (double phi : {5.0, -40.0}) check(name, mesh, {5.0, 1.0, 1e-4, 0.0, phi});
}

TEST(Stability, CreepageThroughZeroKeepsWeightsDefined) {
  // xi and eta cross zero together with zero spin: eq. 15's weights are 0/0 at that instant.
  auto m = model("nss", "fixed");
  const ContactParameters p;
  for (int k = 0; k < 2000; ++k) {
    const double s = std::cos(2 * M_PI * k / 400.0);
    const StepOutput o = m->step({k == 0 ? 0.0 : 1e-5, 20.0, 1e-3 * s, 1e-3 * s, 0.0, p.fz0});
    ASSERT_TRUE(std::isfinite(o.fx) && std::isfinite(o.fy)) << k;
  }
  EXPECT_EQ(m->step({1e-5, 20.0, 0.0, 0.0, 0.0, p.fz0}).status, StepStatus::kOk);
}

TEST(Stability, LoadLostAndRegainedAndSpeedThroughZero) {
  for (const char* name : {"steady", "shen-li", "nss"}) {
    auto m = model(name, "adaptive");
    const ContactParameters p;
    for (int k = 0; k < 3000; ++k) {
      const double fz = p.fz0 * std::sin(2 * M_PI * k / 1000.0);  // negative half the time
      const double V = 5.0 * std::cos(2 * M_PI * k / 700.0);      // crosses zero, goes negative
      const StepOutput o = m->step({k == 0 ? 0.0 : 1e-4, V, 2e-3, 1e-3, 1.0, fz});
      ASSERT_TRUE(std::isfinite(o.fx) && std::isfinite(o.fy)) << name << " " << k;
      if (fz <= 0.0) {
        EXPECT_EQ(o.fx, 0.0);
        EXPECT_EQ(o.status, V < 0.0 ? StepStatus::kRejected : StepStatus::kNoLoad);
      }
      if (V < 0.0) EXPECT_EQ(o.status, StepStatus::kRejected) << name;
      ASSERT_LE(std::hypot(o.fx, o.fy), p.mu * std::max(fz, 0.0) * (1 + 1e-9) + 1e-9);
    }
  }
}
