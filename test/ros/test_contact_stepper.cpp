// ContactStepper: the node's ROS-free bookkeeping (stamps, dt, load, rejections, resets).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../../src/ros/contact_stepper.hpp"

using namespace wheel_rail_contact;

namespace {

const int64_t kS = 1000000000;  // 1 s in ns

/// Records what it is given; fx = -xi * fz, fy = dt, a = number of steps since reset.
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
    log_->push_back(in);
    o.fx = -in.xi * in.fz;
    o.fy = in.dt;
    o.fz = in.fz;
    o.a = ++steps_;
    return o;
  }
  void reset() override { steps_ = 0; }
  std::string name() const override { return "fake"; }

 private:
  std::vector<StepInput>* log_;
  int steps_ = 0;
};

struct Fixture : ::testing::Test {
  std::vector<StepInput> log;
  StepperOptions options;
  std::unique_ptr<ContactStepper> make() {
    return std::make_unique<ContactStepper>(std::make_unique<FakeModel>(&log), options);
  }
};

void expectFiniteZero(const StepResult& r) {
  EXPECT_EQ(r.out.fx, 0.0);
  EXPECT_EQ(r.out.fy, 0.0);
  EXPECT_EQ(r.out.mz, 0.0);
  EXPECT_TRUE(std::isfinite(r.out.fz) && std::isfinite(r.out.a) && std::isfinite(r.out.b));
}

}  // namespace

TEST_F(Fixture, DtIsTheStampDifferenceAndZeroAtTheFirstStep) {
  auto s = make();
  EXPECT_EQ(s->setLoad(10 * kS, 500.0), "");
  const StepResult r0 = s->step(10 * kS, 20.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(r0.out.status, StepStatus::kOk);
  EXPECT_EQ(r0.dt, 0.0);
  const StepResult r1 = s->step(10 * kS + 2500000, 20.0, 0.002, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(r1.dt, 0.0025);
  EXPECT_DOUBLE_EQ(r1.out.fy, 0.0025);
  EXPECT_DOUBLE_EQ(r1.out.fx, -0.002 * 500.0);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[1].fz, 500.0);
  EXPECT_EQ(s->counters().ok, 2u);
  EXPECT_EQ(s->modelName(), "fake");
}

TEST_F(Fixture, NoLoadYetGivesZeroForcesAndNoLoadStatus) {
  auto s = make();
  const StepResult r = s->step(kS, 20.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(r.out.status, StepStatus::kNoLoad);
  EXPECT_EQ(r.event, StepEvent::kNoLoadYet);
  EXPECT_EQ(r.message, "no normal load received yet");
  expectFiniteZero(r);
  s->setLoad(kS, -5.0);  // load <= 0: no contact
  const StepResult r2 = s->step(2 * kS, 20.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(r2.out.status, StepStatus::kNoLoad);
  expectFiniteZero(r2);
  EXPECT_EQ(s->counters().noLoad, 2u);
}

TEST_F(Fixture, NonFiniteInputIsRejectedAndLeavesTheTimeBase) {
  auto s = make();
  s->setLoad(0, 500.0);
  s->step(kS, 20.0, 0.001, 0.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double bad[][4] = {{nan, 0, 0, 0}, {20, nan, 0, 0}, {20, 0, inf, 0}, {20, 0, 0, -inf}};
  for (const auto& b : bad) {
    const StepResult r = s->step(2 * kS, b[0], b[1], b[2], b[3]);
    EXPECT_EQ(r.out.status, StepStatus::kRejected);
    EXPECT_EQ(r.event, StepEvent::kNonFinite);
    EXPECT_FALSE(r.message.empty());
    expectFiniteZero(r);
  }
  EXPECT_EQ(s->counters().nonFinite, 4u);
  const StepResult r = s->step(kS + kS / 2, 20.0, 0.001, 0.0, 0.0);  // dt from the last good one
  EXPECT_EQ(r.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(r.dt, 0.5);
  EXPECT_EQ(r.out.a, 2.0);  // the model saw two steps only
  EXPECT_EQ(s->setLoad(3 * kS, nan), "normal load is not finite");
  EXPECT_EQ(s->load(), 500.0);
  const StepResult rl = s->stepWithLoad(4 * kS, 20.0, 0.001, 0.0, 0.0, inf);
  EXPECT_EQ(rl.out.status, StepStatus::kRejected);
  EXPECT_EQ(s->load(), 500.0);
}

TEST_F(Fixture, OlderOrEqualStampsAreRejectedAndCounted) {
  auto s = make();
  s->setLoad(0, 500.0);
  s->step(5 * kS, 20.0, 0.001, 0.0, 0.0);
  for (int64_t stamp : {5 * kS, 4 * kS, 0 * kS}) {
    const StepResult r = s->step(stamp, 20.0, 0.001, 0.0, 0.0);
    EXPECT_EQ(r.out.status, StepStatus::kRejected);
    EXPECT_EQ(r.event, StepEvent::kOutOfOrder);
    EXPECT_NE(r.message.find("not after"), std::string::npos);
    expectFiniteZero(r);
  }
  EXPECT_EQ(s->counters().outOfOrder, 3u);
  EXPECT_EQ(s->counters().timeJumpResets, 0u);
  EXPECT_DOUBLE_EQ(s->step(6 * kS, 20.0, 0.001, 0.0, 0.0).dt, 1.0);
}

TEST_F(Fixture, AbsurdDtIsRejectedAndTheTimeBaseRestarts) {
  options.max_dt = 0.1;
  auto s = make();
  s->setLoad(0, 500.0);
  s->step(kS, 20.0, 0.001, 0.0, 0.0);
  const StepResult r = s->step(100 * kS, 20.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(r.out.status, StepStatus::kRejected);
  EXPECT_EQ(r.event, StepEvent::kDtTooLarge);
  EXPECT_NE(r.message.find("max_dt"), std::string::npos);
  expectFiniteZero(r);
  const StepResult next = s->step(100 * kS + kS / 100, 20.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(next.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(next.dt, 0.01);
  EXPECT_EQ(s->counters().dtTooLarge, 1u);
}

TEST_F(Fixture, BackwardsTimeJumpResetsWhenEnabled) {
  options.time_jump_reset = 2.0;
  auto s = make();
  auto fresh = make();
  s->setLoad(0, 500.0);
  s->step(100 * kS, 20.0, 0.001, 0.0, 0.0);
  s->step(101 * kS, 20.0, 0.001, 0.0, 0.0);
  // 0.5 s back: below the threshold, rejected.
  EXPECT_EQ(s->step(100 * kS + kS / 2, 20.0, 0.0, 0.0, 0.0).event, StepEvent::kOutOfOrder);
  // 100 s back: reset, then stepped as a first message (the load, older, is kept).
  fresh->setLoad(0, 500.0);
  const StepResult a = s->step(1 * kS, 20.0, 0.003, 0.0, 0.0);
  const StepResult b = fresh->step(1 * kS, 20.0, 0.003, 0.0, 0.0);
  EXPECT_TRUE(a.timeJumpReset);
  EXPECT_EQ(a.dt, 0.0);
  EXPECT_EQ(a.out.fx, b.out.fx);
  EXPECT_EQ(a.out.a, b.out.a);
  EXPECT_EQ(s->counters().timeJumpResets, 1u);
  // A load from the old time line (newer than the message) is dropped by the jump.
  s->setLoad(50 * kS, 700.0);
  const StepResult c = s->step(49 * kS, 20.0, 0.003, 0.0, 0.0);
  EXPECT_FALSE(c.timeJumpReset);
  const StepResult d = s->step(10 * kS, 20.0, 0.003, 0.0, 0.0);
  EXPECT_TRUE(d.timeJumpReset);
  EXPECT_EQ(d.out.status, StepStatus::kNoLoad);
  // Loads also accept a backwards jump beyond the threshold.
  EXPECT_EQ(s->setLoad(60 * kS, 700.0), "");
  EXPECT_EQ(s->setLoad(1 * kS, 600.0), "");
  EXPECT_NE(s->setLoad(kS / 2, 600.0), "");
}

TEST_F(Fixture, LoadRulesOrderAndAge) {
  options.max_load_age = 0.5;
  auto s = make();
  EXPECT_EQ(s->setLoad(2 * kS, 500.0), "");
  EXPECT_EQ(s->setLoad(2 * kS, 510.0), "");  // equal stamp: replaces
  EXPECT_NE(s->setLoad(1 * kS, 520.0).find("older"), std::string::npos);
  EXPECT_EQ(s->load(), 510.0);
  EXPECT_EQ(s->counters().loadsOutOfOrder, 1u);
  const StepResult fresh = s->step(2 * kS + kS / 4, 20.0, 0.001, 0.0, 0.0);
  EXPECT_FALSE(fresh.staleLoad);
  EXPECT_DOUBLE_EQ(fresh.loadAge, 0.25);
  const StepResult old = s->step(3 * kS, 20.0, 0.001, 0.0, 0.0);
  EXPECT_TRUE(old.staleLoad);
  EXPECT_EQ(old.out.status, StepStatus::kOk);  // a stale load is still used, with a warning
  EXPECT_EQ(s->counters().staleLoad, 1u);
}

TEST_F(Fixture, StepWithLoadUsesAndKeepsTheLoad) {
  auto s = make();
  const StepResult r = s->stepWithLoad(kS, 20.0, 0.001, 0.0, 0.0, 800.0);
  EXPECT_EQ(r.out.status, StepStatus::kOk);
  EXPECT_DOUBLE_EQ(r.out.fx, -0.8);
  EXPECT_EQ(s->load(), 800.0);
  EXPECT_DOUBLE_EQ(s->step(2 * kS, 20.0, 0.001, 0.0, 0.0).out.fx, -0.8);
}

TEST_F(Fixture, ResetGivesFreshStartOutputs) {
  auto s = make();
  auto run = [](ContactStepper* st) {
    std::vector<double> out;
    st->setLoad(0, 500.0);
    for (int k = 0; k < 5; ++k) {
      const StepResult r = st->step(k * kS / 10, 20.0, 0.001 * k, 0.0, 0.0);
      out.insert(out.end(), {r.out.fx, r.out.fy, r.out.a, r.dt});
    }
    return out;
  };
  const auto first = run(s.get());
  s->reset();
  EXPECT_FALSE(s->hasLoad());
  EXPECT_EQ(s->step(0, 20.0, 0.001, 0.0, 0.0).out.status, StepStatus::kNoLoad);
  s->reset();
  EXPECT_EQ(run(s.get()), first);
  EXPECT_EQ(s->counters().resets, 2u);
}

TEST_F(Fixture, ModelRefusalsPassThroughAndStatusesMapToTheMessage) {
  auto s = make();
  s->setLoad(0, 500.0);
  const StepResult r = s->step(kS, -1.0, 0.001, 0.0, 0.0);
  EXPECT_EQ(r.out.status, StepStatus::kRejected);
  EXPECT_EQ(s->counters().rejectedByModel, 1u);
  EXPECT_EQ(contactStateStatus(StepStatus::kOk), 0);
  EXPECT_EQ(contactStateStatus(StepStatus::kNoLoad), 1);
  EXPECT_EQ(contactStateStatus(StepStatus::kStandstill), 2);
  EXPECT_EQ(contactStateStatus(StepStatus::kRejected), 3);
}

TEST(StepperOptions, ValidationNamesTheParameter) {
  StepperOptions o;
  EXPECT_NO_THROW(validate(o));
  o.max_dt = 0.0;
  try {
    validate(o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("max_dt", 0), 0u);
  }
  o = StepperOptions{};
  o.time_jump_reset = -1.0;
  EXPECT_THROW(validate(o), std::invalid_argument);
  o = StepperOptions{};
  o.max_load_age = std::nan("");
  EXPECT_THROW(validate(o), std::invalid_argument);
}
