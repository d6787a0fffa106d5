// The scoring behind scripts/speed_accuracy.sh on a coarse setting (no timing here). The harmonic
// reference must carry the right sign, amplitude and phase: the exact model stepped in time must
// match its own grid's frequency-domain response; and the chart's first claim must hold at any
// grid: on a short wave nss is far closer to the exact response than steady FastSim.
#include <gtest/gtest.h>

#include "validation/harmonic_scenes.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

constexpr int kGrid = 16;                     // exact grid (elements per side)
constexpr double kStep = 2.2 * 0.02 / kGrid;  // one exact element [m] (the scheme's dq = dx)

double error(const HarmonicScene& h, const char* model, int n) {
  ContactParameters p = h.scene.params;
  p.model = model;
  p.nx = p.ny = n;
  const NonSteadyCoefficients exact(h.kind, 1.0, p.nu, kGrid, kGrid);
  const std::vector<StepOutput> reference = harmonicResponse(h, exact.at(h.lambdaOverA));
  return sceneError(h.scene, runScene(*makeContactModel(p), h.scene.rows), reference).rmsOverPeak;
}

}  // namespace

TEST(SpeedAccuracy, ScoreOfAHistoryAgainstItselfIsZero) {
  const HarmonicScene h = harmonicScene(CreepageKind::kEta, 5.0, kStep);
  const std::vector<StepOutput> r = harmonicResponse(h, {3.0, -1.0});
  EXPECT_EQ(sceneError(h.scene, r, r).rmsOverPeak, 0.0);
}

// Time stepping and the frequency domain differ only in how a step sees the creepage (its end value
// against its mean: a phase of pi dx / lambda = 0.022 rad at lambda/a = 20) and in the slip of a
// finite mu (F ~ 1e-3 mu Fz). A wrong sign gives 200 %, a wrong norm or a lost factor tens of %.
TEST(SpeedAccuracy, ExactModelMatchesItsFrequencyResponseOnALongWave) {
  for (CreepageKind kind : kCreepageKinds)
    EXPECT_LT(error(harmonicScene(kind, 20.0, kStep), "exact", kGrid), 0.04) << toString(kind);
}

// At lambda/a = 2 the exact force amplitude is about a quarter of the steady one and lags it, so
// steady FastSim's error is about 4 exact peaks; nss on a 10x10 mesh (a 20x20 chi table) about
// 0.23.
TEST(SpeedAccuracy, NssBeatsSteadyOnAShortWave) {
  const HarmonicScene h = harmonicScene(CreepageKind::kXi, 2.0, kStep);
  const double nss = error(h, "nss", 10), steady = error(h, "steady", 10);
  EXPECT_LT(nss, 0.35);
  EXPECT_GT(steady, 2.0);
  EXPECT_LT(nss, 0.1 * steady);
}
