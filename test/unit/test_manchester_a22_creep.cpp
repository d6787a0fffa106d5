// The Manchester contact benchmark's case, creep forces: every loaded patch of every case of
// both wheels, fx, fs and mz from WheelsetContact with each model (steady, nss's and shen-li's
// steady limits: run at the constant state until settled) against the exact tangential solution on
// the same patch (validation/manchester_a22.hpp, runA22Creep; doc/manchester.md).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "validation/manchester_a22.hpp"

using namespace wheel_rail_contact;

namespace {

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/test/data/profiles/";

/// The exact grid of these tests: 32 x 24 elements over each patch's interpenetration region.
/// Against 64 x 48 (manchester_a22 --creep-mx 64 --creep-my 48) the exact fx, fs differ by at most
/// 0.43 % of mu fn on these patches (24 x 18: 1.7 %), mz by 1.0 % of mu fn sqrt(ab).
constexpr int kExactMx = 32, kExactMy = 24;

struct Case {
  A22State state;
  std::vector<A22Creep> patches;
};

A22Options exactOptions() {
  A22Options o;
  o.exact_mx = kExactMx;
  o.exact_my = kExactMy;
  return o;
}

/// CONTACT's published patches (reference points, never targets).
const std::vector<A22Reference>& references() {
  static const std::vector<A22Reference> refs =
      readA22Reference(kDataDir + "contact_a22_reference.csv");
  return refs;
}

/// All 42 wheels, run once for the whole file.
const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    const ContactSearch search{WheelsetTrackData{}};
    std::vector<Case> out;
    for (const A22State& s : readA22States(kDataDir + "a22_cases.csv")) {
      const A22Wheel w = runA22Wheel(search, s, exactOptions());
      out.push_back({s, runA22Creep(w, exactOptions(), A22CreepOptions{}, references())});
    }
    return out;
  }();
  return all;
}

std::string label(const Case& c, const A22Creep& k) {
  return std::string(c.state.side == WheelSide::kLeft ? "left" : "right") + " wheel, y " +
         std::to_string(c.state.y_mm) + " mm, patch " + std::to_string(k.index);
}

const A22ModelForces& forces(const A22Creep& k, const std::string& model) {
  for (const A22ModelForces& f : k.models)
    if (f.model == model) return f;
  ADD_FAILURE() << "no model " << model;
  return k.models.front();
}

/// Error of a model's fx or fs in units of mu fn.
double error(const A22Creep& k, double model, double exact) {
  return std::abs(model - exact) / (0.3 * k.fn);
}

}  // namespace

TEST(ManchesterA22Creep, EveryLoadedPatchHasTheModelsAndTheExactSolution) {
  ASSERT_EQ(cases().size(), 42u);
  int patches = 0;
  for (const Case& c : cases()) {
    EXPECT_GE(c.patches.size(), 1u);
    for (const A22Creep& k : c.patches) {
      ++patches;
      EXPECT_GT(k.fn, 0.0) << label(c, k);
      EXPECT_TRUE(k.exact.converged) << label(c, k);
      ASSERT_EQ(k.models.size(), 3u);
      for (const A22ModelForces& f : k.models) {
        EXPECT_TRUE(f.found) << label(c, k) << " " << f.model;
        EXPECT_TRUE(f.settled) << label(c, k) << " " << f.model;
        for (double v : {f.fx, f.fs, f.mz}) EXPECT_TRUE(std::isfinite(v)) << label(c, k);
      }
    }
  }
  EXPECT_EQ(patches, 43);  // the gauge corner's jump at 5 mm: tread and corner at once
}

TEST(ManchesterA22Creep, CentredStateIsMirroredBetweenTheWheels) {
  // At y = 0 the wheelset is symmetric: the left wheel's patch is the right's mirrored, so the
  // exact (fx, fs, mz) on the left is (fx, -fs, -mz) on the right; each solved in its own wheel's
  // contact frame (its y = -eta on the left), within the solver's tolerance.
  const A22Creep *right = nullptr, *left = nullptr;
  for (const Case& c : cases())
    if (c.state.y_mm == 0.0 && c.patches.size() == 1)
      (c.state.side == WheelSide::kLeft ? left : right) = &c.patches.front();
  ASSERT_TRUE(right && left);
  const double scale = 0.3 * right->fn;
  EXPECT_GT(std::abs(right->exact.fs), 0.05 * scale);
  EXPECT_NEAR(left->exact.fx, right->exact.fx, 1e-4 * scale);
  EXPECT_NEAR(left->exact.fs, -right->exact.fs, 1e-4 * scale);
  EXPECT_NEAR(left->exact.mz, -right->exact.mz, 1e-4 * scale * 1e-2);
}

TEST(ManchesterA22Creep, ExactHasTheSignsOfContactsPublishedForces) {
  // A sanity check of the frames and signs (not a target: CONTACT's normal force differs from ours
  // on the flange, doc/manchester.md): wherever CONTACT's fx or fs exceeds 5 % of its mu FN, our
  // exact one has its sign.
  int checked = 0;
  for (const Case& c : cases())
    for (const A22Creep& k : c.patches) {
      if (!k.contact) continue;
      const double scale = 0.05 * 0.3 * k.contact->fn;
      if (std::abs(k.contact->fx) > scale) {
        EXPECT_GT(k.exact.fx * k.contact->fx, 0.0) << label(c, k);
        ++checked;
      }
      if (std::abs(k.contact->fs) > scale) {
        EXPECT_GT(k.exact.fs * k.contact->fs, 0.0) << label(c, k);
        ++checked;
      }
    }
  EXPECT_GE(checked, 60);
}

/// The one patch where the models on the true patch miss the target: the right wheel at
/// 0.5 mm, the tread's plateau, where the exact patch spreads to 12.6 mm beside its point and the
/// normal problem's strips stop at 4.4 mm (doc/manchester.md, "Creep forces"; doc/true_patch.md).
bool onThePlateau(const Case& c) {
  return c.state.side == WheelSide::kRight && c.state.y_mm == 0.5;
}

TEST(ManchesterA22Creep, NssSteadyLimitWithinFivePercentOfMuFnOfExactOnEveryCaseButThePlateau) {
  // The target: nss's steady limit through WheelsetContact (the models on the true patch:
  // its strips where it is non-Hertzian, blended or beyond Kalker's table) within 5 % of mu fn of
  // exact on fx and fs (the spin moment is shown in doc/manchester.md, not asserted: mu fn has no
  // length); steady and shen-li (classic FastSim, the baselines) within 8 %. Measured on this
  // grid: nss within 1.3 %, steady and shen-li within 5.2 % (the left wheel at 0.5 mm, in partial
  // slip; the flange 4.6 %). Every patch of every case of both wheels but the plateau's, where
  // nss is 20.4 % off on fx and 7.3 % on fs: asserted outside the target, so that a fix shows.
  int checked = 0, plateau = 0;
  for (const Case& c : cases())
    for (const A22Creep& k : c.patches) {
      const A22ModelForces& nss = forces(k, "nss");
      EXPECT_EQ(nss.status, StepStatus::kOk) << label(c, k) << ": " << nss.message;
      if (onThePlateau(c)) {
        EXPECT_GT(error(k, nss.fx, k.exact.fx), 0.05) << label(c, k);
        ++plateau;
        continue;
      }
      EXPECT_LE(error(k, nss.fx, k.exact.fx), 0.05) << label(c, k);
      EXPECT_LE(error(k, nss.fs, k.exact.fs), 0.05) << label(c, k);
      for (const std::string model : {"steady", "shen-li"}) {
        const A22ModelForces& f = forces(k, model);
        EXPECT_LE(error(k, f.fx, k.exact.fx), 0.08) << label(c, k) << " " << model;
        EXPECT_LE(error(k, f.fs, k.exact.fs), 0.08) << label(c, k) << " " << model;
      }
      ++checked;
    }
  EXPECT_EQ(plateau, 1);
  EXPECT_EQ(checked, 42);
}

TEST(ManchesterA22Creep, TheNormalProblemsShareOfTheErrorIsSmallButOnThePlateau) {
  // The exact tangential solution on our normal pressure (WheelsetContact's strips) against the one
  // on the exact pressure, same fn and creepages: the part of a model's error that comes from the
  // normal problem, which no tangential model on our patch removes. Measured on this grid: at most
  // 1.1 % of mu fn on fx and fs, 2.7 % at y = 0 (the merged patch's two lumps); on the tread's
  // plateau (right wheel, 0.5 mm, where our strips stop 8 mm short of the exact patch) 19.2 % on
  // fx and 5.9 % on fs, asserted within a band so that a change either way shows: the 5 % target
  // there needs a better normal problem, not only the true patch.
  int checked = 0, plateau = 0;
  for (const Case& c : cases())
    for (const A22Creep& k : c.patches) {
      const double ex = error(k, k.exact_on_ours.fx, k.exact.fx),
                   es = error(k, k.exact_on_ours.fs, k.exact.fs);
      if (c.state.side == WheelSide::kRight && c.state.y_mm == 0.5) {
        EXPECT_GT(ex, 0.15) << label(c, k);
        EXPECT_LT(ex, 0.27) << label(c, k);
        EXPECT_GT(es, 0.05) << label(c, k);
        EXPECT_LT(es, 0.13) << label(c, k);
        ++plateau;
        continue;
      }
      EXPECT_LE(ex, c.state.y_mm == 0.0 ? 0.035 : 0.015) << label(c, k);
      EXPECT_LE(es, 0.015) << label(c, k);
      ++checked;
    }
  EXPECT_EQ(plateau, 1);
  EXPECT_EQ(checked, 42);
}
