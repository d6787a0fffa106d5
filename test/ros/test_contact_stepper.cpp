// ContactStepper: the node's ROS-free bookkeeping (load pairing, stamps, dt, rejections and the
// held output, per-step geometry, resets). The load wait runs on a clock the test gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../../src/ros/contact_stepper.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

using namespace wheel_rail_contact;

namespace {

const int64_t kS = 1000000000;  // 1 s in ns
const int64_t kMs = kS / 1000;

/// Records what it is given; fx = -xi * fz, fy = dt, mz = mu, a, b = the given a, b (or 1, 2),
/// adhesion fraction = number of steps since reset.
class FakeModel : public ContactModel {
 public:
  explicit FakeModel(std::vector<StepInput>* log) : log_(log) {}
  StepOutput step(const StepInput& in) override {
    StepOutput o;
    o.message = checkStepInput(in);
    if (*o.message || in.V < 0.0) {
      o.status = StepStatus::kRejected;
      return o;
    }
    if (!(in.fz > 0.0)) {
      o.status = StepStatus::kNoLoad;
      steps_ = 0;
      return o;
    }
    if (in.V == 0.0) {
      o.status = StepStatus::kStandstill;
      return o;
    }
    log_->push_back(in);
    o.fx = -in.xi * in.fz;
    o.fy = in.dt;
    o.fz = in.fz;
    o.mz = in.mu;
    o.a = in.a > 0.0 ? in.a : 1.0;
    o.b = in.b > 0.0 ? in.b : 2.0;
    o.adhesionFraction = ++steps_;
    return o;
  }
  void reset() override { steps_ = 0; }
  std::string name() const override { return "fake"; }

 private:
  std::vector<StepInput>* log_;
  int steps_ = 0;
};

StepInput creepage(double V, double xi, double a = 0.0, double b = 0.0, double mu = 0.0) {
  StepInput in;
  in.V = V;
  in.xi = xi;
  in.a = a;
  in.b = b;
  in.mu = mu;
  return in;
}

struct Fixture : ::testing::Test {
  std::vector<StepInput> log;
  StepperOptions options;
  std::unique_ptr<ContactStepper> make() {
    return std::make_unique<ContactStepper>(std::make_unique<FakeModel>(&log), options,
                                            ContactParameters{});
  }
  /// One creepage whose result must come out at once.
  StepResult step(ContactStepper* s, int64_t stamp, double V, double xi, int64_t now = 0) {
    s->addCreepage(stamp, creepage(V, xi), now);
    auto out = s->takeReady();
    EXPECT_EQ(out.size(), 1u) << "stamp " << stamp;
    return out.empty() ? StepResult{} : out.front();
  }
  /// The same with the old "latest load" semantics.
  std::unique_ptr<ContactStepper> makeLatest() {
    options.load_pairing = LoadPairing::kLatest;
    return make();
  }
};

void expectFiniteZero(const StepResult& r) {
  EXPECT_EQ(r.out.fx, 0.0);
  EXPECT_EQ(r.out.fy, 0.0);
  EXPECT_EQ(r.out.mz, 0.0);
  EXPECT_TRUE(std::isfinite(r.out.fz) && std::isfinite(r.out.a) && std::isfinite(r.out.b));
}

void expectSameForces(const StepOutput& a, const StepOutput& b) {
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.mz, b.mz);
  EXPECT_EQ(a.fz, b.fz);
  EXPECT_EQ(a.a, b.a);
  EXPECT_EQ(a.b, b.b);
  EXPECT_EQ(a.adhesionFraction, b.adhesionFraction);
}

}  // namespace

// ---- stamp pairing (the default) ----------------------------------------------------------------

TEST_F(Fixture, DefaultPairingIsByStamp) {
  EXPECT_EQ(StepperOptions{}.load_pairing, LoadPairing::kStamp);
  EXPECT_GT(StepperOptions{}.load_wait, 0.0);
}

TEST_F(Fixture, ACreepageWaitsForTheLoadWithItsStamp) {
  auto s = make();
  s->addCreepage(10 * kS, creepage(20.0, 0.001), 0);
  EXPECT_TRUE(s->takeReady().empty());
  EXPECT_EQ(s->pending(), 1u);
  EXPECT_EQ(s->addLoad(10 * kS, 500.0, kMs), "");
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.status, StepStatus::kOk);
  EXPECT_EQ(out[0].out.fz, 500.0);
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kSameStamp);
  EXPECT_EQ(out[0].loadStampNs, 10 * kS);
  EXPECT_EQ(out[0].stampNs, 10 * kS);
  EXPECT_EQ(out[0].message, "");
  EXPECT_EQ(s->counters().unmatched, 0u);
  // A load first: stepped at once with it.
  EXPECT_EQ(s->addLoad(11 * kS, 600.0, kMs), "");
  const StepResult r = step(s.get(), 11 * kS, 20.0, 0.001);
  EXPECT_EQ(r.out.fz, 600.0);
  EXPECT_EQ(r.loadMatch, LoadMatch::kSameStamp);
}

TEST_F(Fixture, ArrivalOrderDoesNotChangeTheOutputs) {
  // 200 steps, each with its own load, fed in many arrival orders (loads in stamp order among
  // themselves, creepages likewise, interleaved at random, with load_wait never expiring): every
  // order gives the outputs of the Step-call sequence, bit for bit.
  const int n = 200;
  auto stampOf = [](int k) { return 5 * kS + k * kMs; };
  auto fzOf = [](int k) { return 400.0 + 37.0 * std::sin(0.1 * k); };
  auto xiOf = [](int k) { return 1e-3 * std::cos(0.07 * k); };
  std::vector<StepResult> reference;
  {
    auto s = make();
    for (int k = 0; k < n; ++k)
      reference.push_back(s->stepWithLoad(stampOf(k), 20.0, xiOf(k), 0.0, 0.0, fzOf(k)));
  }
  std::mt19937 rng(7);
  for (int order = 0; order < 30; ++order) {
    auto s = make();
    std::vector<bool> isLoad;  // the interleaving: n loads and n creepages
    for (int k = 0; k < n; ++k) isLoad.insert(isLoad.end(), {true, false});
    if (order == 1)  // every creepage before its load
      for (int k = 0; k < n; ++k) isLoad[2 * k] = false, isLoad[2 * k + 1] = true;
    if (order >= 2) std::shuffle(isLoad.begin(), isLoad.end(), rng);
    int nextLoad = 0, nextCreep = 0;
    std::vector<StepResult> got;
    for (bool load : isLoad) {
      if (load) {
        EXPECT_EQ(s->addLoad(stampOf(nextLoad), fzOf(nextLoad), 0), "");
        ++nextLoad;
      } else {
        s->addCreepage(stampOf(nextCreep), creepage(20.0, xiOf(nextCreep)), 0);
        ++nextCreep;
      }
      for (auto& r : s->takeReady()) got.push_back(r);
    }
    ASSERT_EQ(got.size(), reference.size()) << "order " << order;
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(got[k].stampNs, stampOf(k)) << "order " << order;
      EXPECT_EQ(got[k].loadMatch, LoadMatch::kSameStamp) << "order " << order << " step " << k;
      EXPECT_EQ(got[k].dt, reference[k].dt);
      expectSameForces(got[k].out, reference[k].out);
    }
    EXPECT_EQ(s->counters().unmatched, 0u);
    EXPECT_EQ(s->pending(), 0u);
  }
}

TEST_F(Fixture, NoLoadWithinLoadWaitStepsWithTheLatestLoadAndFlagsIt) {
  options.load_wait = 0.05;
  auto s = make();
  s->addLoad(1 * kS, 500.0, 0);
  EXPECT_EQ(step(s.get(), 1 * kS, 20.0, 0.001).out.fz, 500.0);
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 100 * kMs);
  int64_t deadline = 0;
  ASSERT_TRUE(s->nextDeadline(&deadline));
  EXPECT_EQ(deadline, 150 * kMs);
  s->release(150 * kMs - 1);
  EXPECT_TRUE(s->takeReady().empty());
  s->release(150 * kMs);
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.status, StepStatus::kOk);
  EXPECT_EQ(out[0].out.fz, 500.0);
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kUnmatched);
  EXPECT_EQ(out[0].loadStampNs, 1 * kS);
  EXPECT_NE(out[0].message.find("load_wait"), std::string::npos) << out[0].message;
  EXPECT_EQ(s->counters().unmatched, 1u);
  EXPECT_EQ(s->counters().unmatchedWaitExpired, 1u);
  EXPECT_FALSE(s->nextDeadline(&deadline));
  // The late load is still accepted (it answers nothing twice: one output per input).
  EXPECT_EQ(s->addLoad(2 * kS, 510.0, 200 * kMs), "");
  EXPECT_TRUE(s->takeReady().empty());
  EXPECT_EQ(s->load(), 510.0);
}

TEST_F(Fixture, ALaterLoadEndsTheWaitAtOnce) {
  auto s = make();
  s->addLoad(1 * kS, 500.0, 0);
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 0);
  s->addCreepage(3 * kS, creepage(20.0, 0.002), 0);
  EXPECT_TRUE(s->takeReady().empty());
  // The load of 2 s never comes: the load of 3 s shows it (loads come in stamp order).
  s->addLoad(3 * kS, 700.0, 0);
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].stampNs, 2 * kS);
  EXPECT_EQ(out[0].out.fz, 500.0);  // the load in force at 2 s, never one from its future
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kUnmatched);
  EXPECT_NE(out[0].message.find("later stamp"), std::string::npos) << out[0].message;
  EXPECT_EQ(out[1].stampNs, 3 * kS);
  EXPECT_EQ(out[1].out.fz, 700.0);
  EXPECT_EQ(out[1].loadMatch, LoadMatch::kSameStamp);
  EXPECT_EQ(s->counters().unmatchedLaterLoad, 1u);
}

TEST_F(Fixture, OutputsKeepTheInputOrder) {
  auto s = make();
  s->addCreepage(1 * kS, creepage(20.0, 0.001), 0);
  s->addCreepage(2 * kS, creepage(20.0, 0.002), 0);
  s->addCreepage(3 * kS, creepage(20.0, 0.003), 0);
  s->addLoad(1 * kS, 500.0, 0);
  auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].stampNs, 1 * kS);
  s->addLoad(2 * kS, 600.0, 0);
  s->addLoad(3 * kS, 700.0, 0);
  out = s->takeReady();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].out.fz, 600.0);
  EXPECT_EQ(out[1].out.fz, 700.0);
  EXPECT_EQ(s->counters().pendingMax, 3u);
}

TEST_F(Fixture, AFullPairingBufferStepsTheOldestCreepage) {
  options.pairing_buffer = 2;
  auto s = make();
  s->addLoad(kS, 500.0, 0);
  for (int k = 1; k <= 3; ++k) s->addCreepage(kS + k * kMs, creepage(20.0, 0.001), 0);
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].stampNs, kS + kMs);
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kUnmatched);
  EXPECT_NE(out[0].message.find("buffer full"), std::string::npos);
  EXPECT_EQ(s->counters().unmatchedBufferFull, 1u);
  EXPECT_EQ(s->pending(), 2u);
}

TEST_F(Fixture, LoadWaitZeroNeverWaits) {
  options.load_wait = 0.0;
  auto s = make();
  s->addLoad(kS, 500.0, 0);
  const StepResult r = step(s.get(), 2 * kS, 20.0, 0.001, 42);
  EXPECT_EQ(r.loadMatch, LoadMatch::kUnmatched);
  EXPECT_EQ(r.out.fz, 500.0);
}

TEST_F(Fixture, UnstampedLoadsDoNotPoisonTheStampedStream) {
  auto s = make();
  EXPECT_EQ(s->addLoad(0, 999.0, 0), "");  // unstamped
  EXPECT_EQ(s->counters().loadsUnstamped, 1u);
  // Stamped creepages still wait for their stamped loads and take them, whatever the order.
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 0);
  EXPECT_TRUE(s->takeReady().empty()) << "an unstamped load must not release a creepage";
  EXPECT_EQ(s->addLoad(2 * kS, 500.0, 0), "");
  auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.fz, 500.0);
  EXPECT_EQ(s->addLoad(0, 998.0, 0), "");       // an unstamped load in the middle
  EXPECT_EQ(s->addLoad(3 * kS, 600.0, 0), "");  // is not "newer" than any stamp
  EXPECT_EQ(step(s.get(), 3 * kS, 20.0, 0.001).out.fz, 600.0);
  // An unmatched creepage takes the latest load at its stamp: the unstamped one if it came
  // after the newest stamped load not after the creepage.
  EXPECT_EQ(s->addLoad(0, 997.0, 0), "");
  s->addCreepage(4 * kS, creepage(20.0, 0.001), 0);
  s->release(std::numeric_limits<int64_t>::max());
  out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.fz, 997.0);
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kUnmatched);
  EXPECT_EQ(out[0].loadStampNs, 0);
  EXPECT_NE(out[0].message.find("unstamped"), std::string::npos) << out[0].message;
  EXPECT_EQ(s->addLoad(4 * kS + kMs, 650.0, 0), "");  // a stamped load after it: newest wins
  s->addCreepage(5 * kS, creepage(20.0, 0.001), 0);
  s->release(std::numeric_limits<int64_t>::max());
  out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.fz, 650.0);
  // With only unstamped loads, an unstamped creepage is stepped at once with the latest one.
  auto u = make();
  u->addLoad(0, 321.0, 0);
  const StepResult r = step(u.get(), 0, 20.0, 0.001);
  EXPECT_EQ(r.out.fz, 321.0);
  EXPECT_EQ(r.loadMatch, LoadMatch::kLatest);
}

TEST_F(Fixture, UnstampedLoadsDoNotPoisonLatestPairingEither) {
  auto s = makeLatest();
  EXPECT_EQ(s->addLoad(5 * kS, 500.0, 0), "");
  EXPECT_EQ(s->addLoad(0, 999.0, 0), "");
  EXPECT_EQ(step(s.get(), 5 * kS, 20.0, 0.001).out.fz, 999.0);  // latest received
  // The unstamped load did not move the stamp order: a stamped load later than 5 s is accepted,
  // one older is still refused.
  EXPECT_EQ(s->addLoad(6 * kS, 600.0, 0), "");
  EXPECT_NE(s->addLoad(4 * kS, 400.0, 0), "");
  EXPECT_EQ(step(s.get(), 6 * kS, 20.0, 0.001).out.fz, 600.0);
}

TEST_F(Fixture, TheFirstStepAfterAResetPairsWithItsLoadPublishedInTheSameTick) {
  auto s = make();
  s->addLoad(kS, 500.0, 0);
  step(s.get(), kS, 20.0, 0.001);
  s->reset();
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 0);  // the creepage overtakes the load
  s->addLoad(2 * kS, 450.0, 0);
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].out.status, StepStatus::kOk);
  EXPECT_EQ(out[0].out.fz, 450.0);
  EXPECT_EQ(out[0].dt, 0.0);
}

TEST_F(Fixture, ResetAnswersTheWaitingCreepagesRejected) {
  auto s = make();
  s->addLoad(kS, 500.0, 0);
  const StepResult accepted = step(s.get(), kS, 20.0, 0.001);
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 0);
  s->addCreepage(3 * kS, creepage(20.0, 0.001), 0);
  s->reset();
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 2u);
  for (const auto& r : out) {
    EXPECT_EQ(r.out.status, StepStatus::kRejected);
    EXPECT_EQ(r.event, StepEvent::kDroppedByReset);
    EXPECT_TRUE(r.held);
    expectSameForces(r.out, accepted.out);
  }
  EXPECT_EQ(out[1].stampNs, 3 * kS);
  EXPECT_EQ(s->pending(), 0u);
  EXPECT_EQ(s->counters().droppedByReset, 2u);
  EXPECT_FALSE(s->hasLoad());
}

TEST_F(Fixture, AStepCallAnswersOlderWaitingCreepagesFirst) {
  auto s = make();
  s->addLoad(kS, 500.0, 0);
  s->addCreepage(2 * kS, creepage(20.0, 0.001), 0);
  const StepResult r = s->stepWithLoad(3 * kS, 20.0, 0.002, 0.0, 0.0, 800.0);
  const auto before = s->takeReady();
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].stampNs, 2 * kS);
  EXPECT_EQ(before[0].out.fz, 500.0);
  EXPECT_EQ(r.out.fz, 800.0);
  EXPECT_EQ(r.loadMatch, LoadMatch::kSameStamp);
  EXPECT_DOUBLE_EQ(r.dt, 1.0);
  EXPECT_EQ(s->load(), 800.0);
}

TEST_F(Fixture, TimeJumpStartsANewPairingTimeLine) {
  options.time_jump_reset = 2.0;
  auto s = make();
  for (int k = 0; k < 3; ++k) {
    s->addLoad(100 * kS + k * kS, 500.0 + k, 0);
    step(s.get(), 100 * kS + k * kS, 20.0, 0.001);
  }
  // The simulator restarts at 1 s: its creepage comes before its load. The old run's later loads
  // must not end its wait (they belong to another time line).
  s->addCreepage(1 * kS, creepage(20.0, 0.001), 0);
  EXPECT_TRUE(s->takeReady().empty());
  EXPECT_EQ(s->addLoad(1 * kS, 400.0, 0), "");
  const auto out = s->takeReady();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].timeJumpReset);
  EXPECT_EQ(out[0].out.fz, 400.0);
  EXPECT_EQ(out[0].loadMatch, LoadMatch::kSameStamp);
  EXPECT_EQ(out[0].out.adhesionFraction, 1.0);  // the model's first step since the reset
  EXPECT_EQ(s->counters().timeJumpResets, 1u);
}

// ---- rules shared by both pairings (shown with latest, the old behaviour) -----------------------

TEST_F(Fixture, DtIsTheStampDifferenceAndZeroAtTheFirstStep) {
  auto s = makeLatest();
  EXPECT_EQ(s->addLoad(10 * kS, 500.0, 0), "");
  const StepResult r0 = step(s.get(), 10 * kS, 20.0, 0.001);
  EXPECT_EQ(r0.out.status, StepStatus::kOk);
  EXPECT_EQ(r0.dt, 0.0);
  EXPECT_EQ(r0.loadMatch, LoadMatch::kLatest);
  const StepResult r1 = step(s.get(), 10 * kS + 2500000, 20.0, 0.002);
  EXPECT_DOUBLE_EQ(r1.dt, 0.0025);
  EXPECT_DOUBLE_EQ(r1.out.fy, 0.0025);
  EXPECT_DOUBLE_EQ(r1.out.fx, -0.002 * 500.0);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[1].fz, 500.0);
  EXPECT_EQ(s->counters().ok, 2u);
  EXPECT_EQ(s->modelName(), "fake");
}

TEST_F(Fixture, NoLoadYetGivesZeroForcesAndNoLoadStatus) {
  auto s = makeLatest();
  const StepResult r = step(s.get(), kS, 20.0, 0.001);
  EXPECT_EQ(r.out.status, StepStatus::kNoLoad);
  EXPECT_EQ(r.event, StepEvent::kNoLoadYet);
  EXPECT_EQ(r.loadMatch, LoadMatch::kNone);
  EXPECT_EQ(r.message, "no normal load for this step");
  expectFiniteZero(r);
  s->addLoad(kS, -5.0, 0);  // load <= 0: no contact
  const StepResult r2 = step(s.get(), 2 * kS, 20.0, 0.001);
  EXPECT_EQ(r2.out.status, StepStatus::kNoLoad);
  expectFiniteZero(r2);
  EXPECT_EQ(s->counters().noLoad, 2u);
}

TEST_F(Fixture, NonFiniteInputIsRejectedHeldAndLeavesTheTimeBase) {
  auto s = makeLatest();
  s->addLoad(kS, 500.0, 0);
  const StepResult accepted = step(s.get(), kS, 20.0, 0.001);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double bad[][4] = {{nan, 0, 0, 0}, {20, nan, 0, 0}, {20, 0, inf, 0}, {20, 0, 0, -inf}};
  for (const auto& b : bad) {
    StepInput in;
    in.V = b[0];
    in.xi = b[1];
    in.eta = b[2];
    in.phi = b[3];
    s->addCreepage(2 * kS, in, 0);
    const auto out = s->takeReady();
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].out.status, StepStatus::kRejected);
    EXPECT_EQ(out[0].event, StepEvent::kNonFinite);
    EXPECT_FALSE(out[0].message.empty());
    EXPECT_TRUE(out[0].held);
    expectSameForces(out[0].out, accepted.out);
  }
  EXPECT_EQ(s->counters().nonFinite, 4u);
  const StepResult r = step(s.get(), kS + kS / 2, 20.0, 0.001);  // dt from the last good one
  EXPECT_EQ(r.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(r.dt, 0.5);
  EXPECT_EQ(r.out.adhesionFraction, 2.0);  // the model saw two steps only
  EXPECT_EQ(s->addLoad(3 * kS, nan, 0), "normal load is not finite");
  EXPECT_EQ(s->load(), 500.0);
  const StepResult rl = s->stepWithLoad(4 * kS, 20.0, 0.001, 0.0, 0.0, inf);
  EXPECT_EQ(rl.out.status, StepStatus::kRejected);
  EXPECT_EQ(rl.event, StepEvent::kNonFinite);
  EXPECT_EQ(s->load(), 500.0);
}

TEST_F(Fixture, ARejectedStepHoldsTheLastAcceptedOutput) {
  options.max_dt = 0.5;
  auto s = make();
  // Before any accepted step: no creep force, fz = the step's own load (0 if none).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s->addLoad(kS, 500.0, 0);
  s->addCreepage(kS, creepage(20.0, nan), 0);
  auto first = s->takeReady();
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].out.status, StepStatus::kRejected);
  EXPECT_FALSE(first[0].held);
  expectFiniteZero(first[0]);
  EXPECT_EQ(first[0].out.fz, 500.0);
  EXPECT_EQ(s->stepWithLoad(kS, 20.0, 0.0, 0.0, 0.0, nan).out.fz, 0.0);
  // After one: every kind of rejection holds it, bit for bit, with its own status and reason.
  s->addLoad(2 * kS, 600.0, 0);
  const StepResult accepted = step(s.get(), 2 * kS, 20.0, 0.003);
  ASSERT_EQ(accepted.out.status, StepStatus::kOk);
  std::vector<StepResult> rejected;
  s->addLoad(3 * kS, 700.0, 0);
  rejected.push_back(step(s.get(), 2 * kS, 20.0, 0.001));                 // out of order
  rejected.push_back(step(s.get(), 3 * kS, -20.0, 0.001));                // refused by the model
  rejected.push_back(s->stepWithLoad(4 * kS, 20.0, 0.001, 0, 0, 700.0));  // dt 2 s > max_dt
  StepInput geometry = creepage(20.0, 0.001, 0.006, 0.0);                 // a without b
  rejected.push_back(s->stepWithLoad(4 * kS + kMs, geometry));
  for (const auto& r : rejected) {
    EXPECT_EQ(r.out.status, StepStatus::kRejected) << r.message;
    EXPECT_TRUE(r.held);
    expectSameForces(r.out, accepted.out);
    EXPECT_FALSE(r.message.empty());
  }
  EXPECT_EQ(rejected[0].event, StepEvent::kOutOfOrder);
  EXPECT_EQ(rejected[2].event, StepEvent::kDtTooLarge);
  EXPECT_EQ(rejected[3].event, StepEvent::kBadGeometry);
  // No load and standstill are answers, not rejections: no load then becomes what is held.
  const StepResult none = s->stepWithLoad(4 * kS + 2 * kMs, 20.0, 0.001, 0.0, 0.0, 0.0);
  EXPECT_EQ(none.out.status, StepStatus::kNoLoad);
  const StepResult after = s->stepWithLoad(4 * kS, 20.0, 0.001, 0.0, 0.0, 10.0);
  EXPECT_EQ(after.out.status, StepStatus::kRejected);
  expectSameForces(after.out, none.out);
  // A reset forgets what was accepted.
  s->reset();
  const StepResult fresh = s->stepWithLoad(kS, 20.0, nan, 0.0, 0.0, 300.0);
  EXPECT_FALSE(fresh.held);
  expectFiniteZero(fresh);
  EXPECT_EQ(fresh.out.fz, 300.0);
}

TEST_F(Fixture, OlderOrEqualStampsAreRejectedAndCounted) {
  auto s = makeLatest();
  s->addLoad(kS, 500.0, 0);
  step(s.get(), 5 * kS, 20.0, 0.001);
  for (int64_t stamp : {5 * kS, 4 * kS, 1 * kS}) {
    const StepResult r = step(s.get(), stamp, 20.0, 0.001);
    EXPECT_EQ(r.out.status, StepStatus::kRejected);
    EXPECT_EQ(r.event, StepEvent::kOutOfOrder);
    EXPECT_NE(r.message.find("not after"), std::string::npos);
  }
  EXPECT_EQ(s->counters().outOfOrder, 3u);
  EXPECT_EQ(s->counters().timeJumpResets, 0u);
  EXPECT_DOUBLE_EQ(step(s.get(), 6 * kS, 20.0, 0.001).dt, 1.0);
}

TEST_F(Fixture, AbsurdDtIsRejectedAndTheTimeBaseRestarts) {
  options.max_dt = 0.1;
  auto s = makeLatest();
  s->addLoad(kS, 500.0, 0);
  step(s.get(), kS, 20.0, 0.001);
  const StepResult r = step(s.get(), 100 * kS, 20.0, 0.001);
  EXPECT_EQ(r.out.status, StepStatus::kRejected);
  EXPECT_EQ(r.event, StepEvent::kDtTooLarge);
  EXPECT_NE(r.message.find("max_dt"), std::string::npos);
  const StepResult next = step(s.get(), 100 * kS + kS / 100, 20.0, 0.001);
  EXPECT_EQ(next.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(next.dt, 0.01);
  EXPECT_EQ(s->counters().dtTooLarge, 1u);
}

TEST_F(Fixture, BackwardsTimeJumpResetsWhenEnabled) {
  options.time_jump_reset = 2.0;
  auto s = makeLatest();
  auto fresh = make();
  s->addLoad(kS / 2, 500.0, 0);
  step(s.get(), 100 * kS, 20.0, 0.001);
  step(s.get(), 101 * kS, 20.0, 0.001);
  // 0.5 s back: below the threshold, rejected.
  EXPECT_EQ(step(s.get(), 100 * kS + kS / 2, 20.0, 0.0).event, StepEvent::kOutOfOrder);
  // 100 s back: reset, then stepped as a first message (the load, older, is kept).
  fresh->addLoad(kS / 2, 500.0, 0);
  const StepResult a = step(s.get(), 1 * kS, 20.0, 0.003);
  const StepResult b = fresh->stepWithLoad(1 * kS, 20.0, 0.003, 0.0, 0.0, 500.0);
  EXPECT_TRUE(a.timeJumpReset);
  EXPECT_EQ(a.dt, 0.0);
  EXPECT_EQ(a.out.fx, b.out.fx);
  EXPECT_EQ(a.out.adhesionFraction, b.out.adhesionFraction);
  EXPECT_EQ(s->counters().timeJumpResets, 1u);
  // A load from the old time line (newer than the message) is dropped by the jump.
  s->addLoad(50 * kS, 700.0, 0);
  const StepResult c = step(s.get(), 49 * kS, 20.0, 0.003);
  EXPECT_FALSE(c.timeJumpReset);
  const StepResult d = step(s.get(), 10 * kS, 20.0, 0.003);
  EXPECT_TRUE(d.timeJumpReset);
  EXPECT_EQ(d.out.status, StepStatus::kNoLoad);
  // Loads also accept a backwards jump beyond the threshold.
  EXPECT_EQ(s->addLoad(60 * kS, 700.0, 0), "");
  EXPECT_EQ(s->addLoad(1 * kS, 600.0, 0), "");
  EXPECT_NE(s->addLoad(kS / 2, 600.0, 0), "");
}

TEST_F(Fixture, LoadRulesOrderAndAge) {
  options.max_load_age = 0.5;
  auto s = makeLatest();
  EXPECT_EQ(s->addLoad(2 * kS, 500.0, 0), "");
  EXPECT_EQ(s->addLoad(2 * kS, 510.0, 0), "");  // equal stamp: replaces
  EXPECT_NE(s->addLoad(1 * kS, 520.0, 0).find("older"), std::string::npos);
  EXPECT_EQ(s->load(), 510.0);
  EXPECT_EQ(s->counters().loadsOutOfOrder, 1u);
  const StepResult fresh = step(s.get(), 2 * kS + kS / 4, 20.0, 0.001);
  EXPECT_FALSE(fresh.staleLoad);
  EXPECT_DOUBLE_EQ(fresh.loadAge, 0.25);
  const StepResult old = step(s.get(), 3 * kS, 20.0, 0.001);
  EXPECT_TRUE(old.staleLoad);
  EXPECT_EQ(old.out.status, StepStatus::kOk);  // a stale load is still used, with a warning
  EXPECT_EQ(s->counters().staleLoad, 1u);
}

TEST_F(Fixture, StepWithLoadUsesAndKeepsTheLoad) {
  auto s = makeLatest();
  const StepResult r = s->stepWithLoad(kS, 20.0, 0.001, 0.0, 0.0, 800.0);
  EXPECT_EQ(r.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(r.out.fx, -0.8);
  EXPECT_EQ(s->load(), 800.0);
  EXPECT_DOUBLE_EQ(step(s.get(), 2 * kS, 20.0, 0.001).out.fx, -0.8);
}

TEST_F(Fixture, ResetGivesFreshStartOutputs) {
  for (LoadPairing pairing : {LoadPairing::kStamp, LoadPairing::kLatest}) {
    options.load_pairing = pairing;
    auto s = make();
    auto run = [this](ContactStepper* st) {
      std::vector<double> out;
      for (int k = 1; k <= 5; ++k) {
        st->addLoad(k * kS / 10, 500.0 + k, 0);
        const StepResult r = step(st, k * kS / 10, 20.0, 0.001 * k);
        out.insert(out.end(), {r.out.fx, r.out.fy, r.out.adhesionFraction, r.dt});
      }
      return out;
    };
    const auto first = run(s.get());
    s->reset();
    EXPECT_FALSE(s->hasLoad());
    EXPECT_EQ(s->stepWithLoad(kS, 20.0, 0.001, 0.0, 0.0, 0.0).out.status, StepStatus::kNoLoad);
    s->reset();
    EXPECT_EQ(run(s.get()), first);
    EXPECT_EQ(s->counters().resets, 2u);
  }
}

TEST_F(Fixture, ModelRefusalsPassThroughAndStatusesMapToTheMessage) {
  auto s = make();
  const StepResult r = s->stepWithLoad(kS, -1.0, 0.001, 0.0, 0.0, 500.0);
  EXPECT_EQ(r.out.status, StepStatus::kRejected);
  EXPECT_EQ(s->counters().rejectedByModel, 1u);
  EXPECT_EQ(contactStateStatus(StepStatus::kOk), 0);
  EXPECT_EQ(contactStateStatus(StepStatus::kNoLoad), 1);
  EXPECT_EQ(contactStateStatus(StepStatus::kStandstill), 2);
  EXPECT_EQ(contactStateStatus(StepStatus::kRejected), 3);
  EXPECT_EQ(contactStateStatus(StepStatus::kNotConverged), 4);
}

// ---- per-step geometry and friction (plumbing: the models honour them elsewhere) ----------------

TEST_F(Fixture, SemiAxesAndFrictionReachTheModelUnchanged) {
  auto s = make();
  s->addCreepage(kS, creepage(20.0, 0.001, 0.007, 0.0045, 0.21), 0);
  s->addLoad(kS, 500.0, 0);
  ASSERT_EQ(s->takeReady().size(), 1u);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].a, 0.007);
  EXPECT_EQ(log[0].b, 0.0045);
  EXPECT_EQ(log[0].mu, 0.21);
  StepInput in = creepage(20.0, 0.001);  // none given: zeros, the parameters apply
  in.fz = 510.0;
  s->stepWithLoad(2 * kS, in);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[1].a, 0.0);
  EXPECT_EQ(log[1].b, 0.0);
  EXPECT_EQ(log[1].mu, 0.0);
  in.mu = 0.15;  // friction alone
  s->stepWithLoad(3 * kS, in);
  EXPECT_EQ(log.back().mu, 0.15);
}

TEST_F(Fixture, CurvaturesGiveTheHertzPatchOfThePairedLoad) {
  ContactParameters material;
  material.G = 7.9e10;
  material.nu = 0.3;
  auto s = std::make_unique<ContactStepper>(std::make_unique<FakeModel>(&log), options, material);
  const GapCurvatures k{2.1, 6.5};
  // The load comes after the creepage: the patch is the one of that load, not of an older one.
  s->addLoad(kS, 30000.0, 0);
  s->takeReady();
  s->addCreepage(2 * kS, creepage(20.0, 0.001, 0, 0, 0.25), 0, k);
  s->addLoad(2 * kS, 90000.0, 0);
  ASSERT_EQ(s->takeReady().size(), 1u);
  const HertzEllipse e = hertzFromCurvatures(90000.0, 2.1, 6.5, 7.9e10, 0.3);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].a, e.a);
  EXPECT_EQ(log[0].b, e.b);
  EXPECT_EQ(log[0].mu, 0.25);
  StepInput in = creepage(20.0, 0.001);
  in.fz = 45000.0;
  s->stepWithLoad(3 * kS, in, k);
  const HertzEllipse e2 = hertzFromCurvatures(45000.0, 2.1, 6.5, 7.9e10, 0.3);
  EXPECT_EQ(log.back().a, e2.a);
  EXPECT_EQ(log.back().b, e2.b);
  // No load: no Hertz patch to make, the model answers "no load".
  in.fz = 0.0;
  EXPECT_EQ(s->stepWithLoad(4 * kS, in, k).out.status, StepStatus::kNoLoad);
}

TEST_F(Fixture, InvalidOrConflictingGeometryIsRejectedWithItsReason) {
  auto s = make();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    StepInput in;
    GapCurvatures k;
    const char* reason;
  } cases[] = {
      {creepage(20, 0.001, 0.006, 0.0), {}, "together"},
      {creepage(20, 0.001, 0.0, 0.004), {}, "together"},
      {creepage(20, 0.001), {2.0, 0.0}, "together"},
      {creepage(20, 0.001), {0.0, 5.0}, "together"},
      {creepage(20, 0.001, 0.006, 0.004), {2.0, 5.0}, "both"},
      {creepage(20, 0.001, -0.006, 0.004), {}, "a is negative"},
      {creepage(20, 0.001, 0.006, nan), {}, "b is not finite"},
      {creepage(20, 0.001), {-2.0, 5.0}, "curvature_x is negative"},
      {creepage(20, 0.001), {2.0, INFINITY}, "curvature_y is not finite"},
      {creepage(20, 0.001, 0, 0, -0.3), {}, "mu is negative"},
      {creepage(20, 0.001, 0, 0, nan), {}, "mu is not finite"},
  };
  int64_t t = kS;
  for (const auto& c : cases) {
    StepInput in = c.in;
    in.fz = 500.0;
    const StepResult r = s->stepWithLoad(t, in, c.k);
    EXPECT_EQ(r.out.status, StepStatus::kRejected) << c.reason;
    EXPECT_EQ(r.event, StepEvent::kBadGeometry) << c.reason;
    EXPECT_NE(r.message.find(c.reason), std::string::npos) << r.message;
    t += kMs;
  }
  EXPECT_TRUE(log.empty()) << "a rejected step reached the model";
  EXPECT_EQ(s->counters().badGeometry, sizeof cases / sizeof cases[0]);
  // The time base was not touched: the next good step is the first.
  EXPECT_EQ(s->stepWithLoad(t, 20.0, 0.001, 0.0, 0.0, 500.0).dt, 0.0);
  // Without a material the stepper cannot make a Hertz patch and says so.
  ContactStepper bare(std::make_unique<FakeModel>(&log), options);
  StepInput in = creepage(20, 0.001);
  in.fz = 500.0;
  const StepResult r = bare.stepWithLoad(kS, in, {2.0, 5.0});
  EXPECT_EQ(r.event, StepEvent::kBadGeometry);
  EXPECT_NE(r.message.find("material"), std::string::npos);
}

TEST(StepperOptions, ValidationNamesTheParameter) {
  auto startsWith = [](const StepperOptions& o, const std::string& name) {
    try {
      validate(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).rfind(name, 0) == 0;
    }
    return false;
  };
  StepperOptions o;
  EXPECT_NO_THROW(validate(o));
  o.max_dt = 0.0;
  EXPECT_TRUE(startsWith(o, "max_dt"));
  o = StepperOptions{};
  o.time_jump_reset = -1.0;
  EXPECT_TRUE(startsWith(o, "time_jump_reset"));
  o = StepperOptions{};
  o.max_load_age = std::nan("");
  EXPECT_TRUE(startsWith(o, "max_load_age"));
  o = StepperOptions{};
  o.load_wait = -0.1;
  EXPECT_TRUE(startsWith(o, "load_wait"));
  o.load_wait = std::nan("");
  EXPECT_TRUE(startsWith(o, "load_wait"));
  o = StepperOptions{};
  o.pairing_buffer = 0;
  EXPECT_TRUE(startsWith(o, "pairing_buffer"));
  EXPECT_EQ(parseLoadPairing("stamp"), LoadPairing::kStamp);
  EXPECT_EQ(parseLoadPairing("latest"), LoadPairing::kLatest);
  EXPECT_STREQ(toString(LoadPairing::kLatest), "latest");
  try {
    parseLoadPairing("nearest");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("load_pairing", 0), 0u);
  }
}

TEST(FrameId, DefaultFromTheNamespace) {
  EXPECT_EQ(frameIdForNamespace("/bogie1/wheelset1/left"), "bogie1_wheelset1_left_contact");
  EXPECT_EQ(frameIdForNamespace("/bogie1/wheelset1/right"), "bogie1_wheelset1_right_contact");
  EXPECT_EQ(frameIdForNamespace("/sim"), "sim_contact");
  EXPECT_EQ(frameIdForNamespace("/"), "contact");
  EXPECT_EQ(frameIdForNamespace(""), "contact");
}
