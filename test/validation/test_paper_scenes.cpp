// The paper's scenes (Guiral et al. 2013, eqs. 16-18 and section 4.2) against our exact solver at
// a coarse CI grid (20x20). Tolerance: at this grid the exact reference itself is about 5 % too
// stiff in adhesion (its steady C11 is 4.43 against Kalker's 4.23), so the CI bound on nss is 8 %
// of the peak force; the 5 % figures in doc/validation.md come from the 40x40 run of
// accuracy_report. What must hold at any grid: nss beats shen-li and steady FastSim on every scene;
// auto keeps the same bound and is never worse than steady FastSim, which it runs where the chart
// finds it within auto's tolerance (the varying-load scenes at lambda/a0 = 15).
#include <gtest/gtest.h>

#include <memory>

#include "validation/paper_scenes.hpp"

using namespace wheel_rail_contact;

namespace {

SceneError errors(const PaperScene& s, const char* model, const std::vector<StepOutput>& exact,
                  const char* mesh = "fixed", const char* fastsim = nullptr) {
  ContactParameters p = s.params;
  p.model = model;
  if (fastsim) setParameter(&p, "fastsim", fastsim);  // else the model's own
  p.mesh = std::string(model) == "auto" ? "adaptive" : mesh;
  p.nx = p.ny = 20;
  auto m = makeContactModel(p);
  return sceneError(s, runScene(*m, s.rows), exact);
}

double error(const PaperScene& s, const char* model, const std::vector<StepOutput>& exact,
             const char* mesh = "fixed") {
  return errors(s, model, exact, mesh).rmsOverPeak;
}

std::vector<StepOutput> exactRun(const PaperScene& s) {
  ContactParameters p = s.params;
  p.model = "exact";
  p.nx = p.ny = 20;
  auto exactModel = makeContactModel(p);
  return runScene(*exactModel, s.rows);
}

// tie: how far nss may lie above shen-li on the fixed mesh (1: strictly below).
void check(const PaperScene& s, double tie = 1.0) {
  const std::vector<StepOutput> exact = exactRun(s);
  const double nss = error(s, "nss", exact), shenLi = error(s, "shen-li", exact),
               steady = error(s, "steady", exact);
  EXPECT_LT(nss, 0.08) << s.name;
  EXPECT_LT(nss, tie * shenLi) << s.name;
  if (tie > 1.0) {  // where the fixed mesh ties, the adaptive one (fitted to the patch) must not
    EXPECT_LT(error(s, "nss", exact, "adaptive"), error(s, "shen-li", exact, "adaptive")) << s.name;
  }
  EXPECT_LT(nss, steady) << s.name;
  // auto (tolerance 0.05: it picks its mesh and when to run nss).
  const double automatic = error(s, "auto", exact);
  EXPECT_LT(automatic, 0.08) << s.name;
  EXPECT_LE(automatic, steady) << s.name;
}

}  // namespace

TEST(PaperScenes, CombinedCreepages) {
  for (int c = 1; c <= 3; ++c) check(combinedCreepageScene(c, 3, 2.2 * 0.02 / 20));
}

TEST(PaperScenes, CalibratedNssBeatsClassicOnCombinedCreepages) {
  // Combined creepages with spin: calibrated FastSim's steady curves are right in partial slip, and
  // its time-term filters blend the kinds by the forces they put along each direction (x: kind 11
  // alone; doc/calibrated_fastsim.md, "Non-steady accuracy"). Margin against this 20x20 reference:
  // 2.0 / 2.7 / 2.3 % of the peak against classic's 4.1 / 4.2 / 2.8 %. Constant load: the adaptive
  // mesh runs the same steps.
  for (int c = 1; c <= 3; ++c) {
    const PaperScene s = combinedCreepageScene(c, 3, 2.2 * 0.02 / 20);
    const std::vector<StepOutput> exact = exactRun(s);
    const double classic = errors(s, "nss", exact, "fixed", "classic").rmsOverPeak,
                 calibrated = errors(s, "nss", exact, "fixed", "calibrated").rmsOverPeak;
    EXPECT_LT(calibrated, classic) << s.name;
  }
}

TEST(PaperScenes, VaryingLoad) {
  // On the fixed mesh under this varying load nss and shen-li tie at xi >= 0.05 (near full slip the
  // time term acts only in the small adhesion zone): nss errs up to 0.8 % above shen-li against
  // this 20x20 reference (xi = 0.05; 1.9 % below against a 30x30 one), 5 % below at xi = 0.01 and
  // 10 % below at xi = 0.002. Before the fixed mesh integrated from the patch's leading edge, its
  // 11 % too stiff linear coefficient offset the 20x20 reference's own 5 % and made nss look 3-38 %
  // better.
  for (double xi : {0.002, 0.01, 0.05})
    check(varyingLoadScene(xi, 15.0, 3, 2.2 * 0.02 * 1.08 / 20), 1.03);
}

TEST(PaperScenes, VaryingLoadFollowsTheLoad) {
  // Where nss and shen-li tie (above), the RMS is the mean error: FastSim's steady bias against the
  // exact solution, which both share (doc/validation.md, "Why nss and shen-li tie under a varying
  // load"). The part that follows the load, the RMS of the error about its mean over the period, is
  // the one the time term acts on: there nss must beat shen-li on every varying-load case, on the
  // fixed mesh (measured here: nss at most 0.93 of shen-li, at xi = 0.1, lambda/a0 = 40) and by a
  // fifth or more on the adaptive one, mesh for mesh (at most 0.75 of it, xi = 0.1, 40).
  for (double xi : {0.002, 0.01, 0.05, 0.1})
    for (double l : {5.0, 15.0, 40.0}) {
      const PaperScene s = varyingLoadScene(xi, l, 3, 2.2 * 0.02 * 1.08 / 20);
      const std::vector<StepOutput> exact = exactRun(s);
      EXPECT_LT(errors(s, "nss", exact).rmsAboutMeanOverPeak,
                errors(s, "shen-li", exact).rmsAboutMeanOverPeak)
          << s.name;
      EXPECT_LT(errors(s, "nss", exact, "adaptive").rmsAboutMeanOverPeak,
                0.8 * errors(s, "shen-li", exact, "adaptive").rmsAboutMeanOverPeak)
          << s.name;
      // The fastest load change in near-full adhesion crosses the fixed mesh's nodes most often:
      // a node the trailing edge newly covers must take its upstream node's history (NssModel::
      // coverTrailingNodes). Measured: 3.28 % of the peak; 4.19 % when it kept the zero it had
      // outside the patch.
      if (xi == 0.002 && l == 5.0) {
        EXPECT_LT(error(s, "nss", exact), 0.037) << s.name;
      }
    }
}
