// Accuracy of NSS-FastSim under a changing patch shape (per-step a, b) against our exact
// half-space solver given the same per-step geometry (doc/varying_geometry.md), at coarse CI
// settings: exact grid 16x16, FastSim 16x16 (the doc's grid 30 / mesh 20 numbers are lower).
// Tolerances: RMS error over the peak exact force in the scored period, about 1.3 times what
// these settings give (doc/varying_geometry.md, "CI settings"), and below steady FastSim's error on
// every scene.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "validation/varying_geometry.hpp"

using namespace wheel_rail_contact;

namespace {

constexpr int kGrid = 16, kMesh = 16;

double errorOf(const PaperScene& s, const std::vector<StepOutput>& exact, const char* model,
               const char* mesh) {
  ContactParameters p = s.params;
  p.model = model;
  p.mesh = mesh;
  p.nx = p.ny = kMesh;
  auto m = makeContactModel(p);
  const std::vector<StepOutput> out = runScene(*m, s.rows);
  for (const StepOutput& o : out) EXPECT_STREQ(o.message, "") << model << " " << mesh;
  return sceneError(s, out, exact).rmsOverPeak;
}

void expectNssWithin(const PaperScene& s, double fixedTolerance, double adaptiveTolerance) {
  ContactParameters p = s.params;
  p.model = "exact";
  p.nx = p.ny = kGrid;
  auto exactModel = makeContactModel(p);
  const std::vector<StepOutput> exact = runScene(*exactModel, s.rows);
  for (const StepOutput& o : exact) ASSERT_NE(o.status, StepStatus::kRejected) << o.message;
  const double steady = errorOf(s, exact, "steady", "fixed"),
               fixed = errorOf(s, exact, "nss", "fixed"),
               adaptive = errorOf(s, exact, "nss", "adaptive");
  EXPECT_LE(fixed, fixedTolerance) << s.name;
  EXPECT_LE(adaptive, adaptiveTolerance) << s.name;
  EXPECT_LT(fixed, steady) << s.name;
  EXPECT_LT(adaptive, steady) << s.name;
}

}  // namespace

TEST(VaryingGeometry, NssFollowsAHarmonicAOverB) {
  const double step = 2.2 * 0.02 * std::cbrt(1.8) / kGrid;  // one exact element per row
  expectNssWithin(harmonicAOverBScene(5.0, step), 0.07, 0.10);
  expectNssWithin(harmonicAOverBScene(10.0, step), 0.07, 0.09);
  expectNssWithin(harmonicAOverBScene(20.0, step), 0.065, 0.07);
}

TEST(VaryingGeometry, NssFollowsAStepOfAOverB) {
  const double step = 2.2 * 0.02 * std::cbrt(1.8) / kGrid;
  expectNssWithin(stepAOverBScene(step), 0.03, 0.03);
}
