// WheelsetStepper: N named wheelsets stepped per tick equal N separate WheelsetContacts (dt from
// the stamps, each tick's own cant); unknown, missing and repeated names, non-finite values,
// stamps, a cant beyond the limit, the hold rule, reset and the shared contact table are defined
// outputs. S1002 on UIC60 1:40 (built in), the Manchester benchmark's wheelset data.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../src/ros/wheelset_stepper.hpp"

using namespace wheel_rail_contact;

namespace {

const int64_t kMs = 1000000;  // 1 ms in ns

WheelsetStepperConfig config(const std::vector<std::string>& names,
                             const std::string& model = "nss") {
  WheelsetStepperConfig c;
  c.names = names;
  c.parameters.model = model;
  c.parameters.nx = c.parameters.ny = 10;
  c.options.use_contact_table = false;  // the direct search: no table to build in a unit test
  return c;
}

/// A wheelset near the benchmark's case A-2.2 (V 2 m/s, 10 kN per wheel), moving laterally with
/// k in a 500 m left curve whose cant changes with k; i sets it apart from the others.
WheelsetEntry entry(const std::string& name, int k, int i) {
  WheelsetEntry e;
  e.name = name;
  e.state.pose.y = 1e-3 * std::sin(0.2 * k + i);
  e.state.pose.yaw = 1e-3 * std::cos(0.1 * k + i);
  e.state.motion.V = 2.0;
  e.state.motion.omega = 2.0 / 0.46 * (1.0 + 1e-3 * i);
  e.state.motion.vy = 2e-4 * std::cos(0.2 * k + i);
  e.state.motion.curvature = 1.0 / 500.0;
  e.state.motion.cant = -0.1 - 0.05 * std::sin(0.3 * k + i);
  e.state.fz_left = 1e4 + 100.0 * i;
  e.state.fz_right = 1e4 - 50.0 * k;
  return e;
}

void expectSame(const WheelResult& a, const WheelResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  ASSERT_EQ(a.patches.size(), b.patches.size());
  for (size_t k = 0; k < a.patches.size(); ++k) {
    const PatchResult &p = a.patches[k], &q = b.patches[k];
    EXPECT_EQ(p.slot, q.slot);
    EXPECT_EQ(p.normal.fn, q.normal.fn);
    EXPECT_EQ(p.creepages.xi, q.creepages.xi);
    EXPECT_EQ(p.creepages.eta, q.creepages.eta);
    EXPECT_EQ(p.creepages.phi, q.creepages.phi);
    EXPECT_EQ(p.fx, q.fx);
    EXPECT_EQ(p.fs, q.fs);
    EXPECT_EQ(p.mz, q.mz);
    EXPECT_EQ(p.geometry.point, q.geometry.point);
    EXPECT_EQ(p.wrench.fy, q.wrench.fy);
    EXPECT_EQ(p.wrench.mx, q.wrench.mx);
  }
  for (double TrackWrench::*f : {&TrackWrench::fx, &TrackWrench::fy, &TrackWrench::fz,
                                 &TrackWrench::mx, &TrackWrench::my, &TrackWrench::mz})
    EXPECT_EQ(a.wrench.*f, b.wrench.*f);
  EXPECT_EQ(a.centre, b.centre);
}

}  // namespace

TEST(WheelsetStepper, EqualsSeparateWheelsetContactsInAnyEntryOrder) {
  const std::vector<std::string> names{"ws1", "ws2", "ws3"};
  const WheelsetStepperConfig c = config(names);
  WheelsetStepper v(c);
  std::vector<std::unique_ptr<WheelsetContact>> single;
  for (size_t i = 0; i < names.size(); ++i)
    single.push_back(std::make_unique<WheelsetContact>(c.track, c.parameters, c.options));
  std::vector<WheelsetAnswer> out;
  for (int k = 0; k < 20; ++k) {
    std::vector<WheelsetEntry> in;
    for (size_t i = 0; i < names.size(); ++i) in.push_back(entry(names[i], k, i));
    if (k % 2) std::swap(in[0], in[2]);  // the order of entries is the sender's choice
    v.step(k * kMs, in, &out);
    ASSERT_EQ(out.size(), in.size());
    for (size_t j = 0; j < in.size(); ++j) {
      const int i = v.find(in[j].name);
      ASSERT_EQ(out[j].wheelset, i);
      EXPECT_EQ(out[j].event, WheelsetEvent::kStepped);
      EXPECT_EQ(out[j].dt, k == 0 ? 0.0 : 1e-3);
      const WheelsetResult r = single[i]->step(in[j].state, k == 0 ? 0.0 : 1e-3);
      EXPECT_EQ(out[j].left.status, WheelAnswerStatus::kOk) << out[j].left.message;
      EXPECT_EQ(out[j].right.status, WheelAnswerStatus::kOk) << out[j].right.message;
      EXPECT_FALSE(out[j].left.held);
      expectSame(out[j].left.result, r.left);
      expectSame(out[j].right.result, r.right);
    }
  }
  EXPECT_EQ(v.counters(0).steps, 20u);
  EXPECT_EQ(v.counters().ticks, 20u);
}

TEST(WheelsetStepper, ThreadsGiveTheSameAnswers) {
  const std::vector<std::string> names{"ws1", "ws2", "ws3", "ws4", "ws5"};
  WheelsetStepperConfig c = config(names);
  WheelsetStepper one(c);
  c.threads = 3;
  WheelsetStepper three(c);
  std::vector<WheelsetAnswer> a, b;
  for (int k = 0; k < 10; ++k) {
    std::vector<WheelsetEntry> in;
    for (size_t i = 0; i < names.size(); ++i) in.push_back(entry(names[i], k, i));
    in.pop_back();  // ws5 missing: answered after the stepped ones, in either case
    one.step(k * kMs, in, &a);
    three.step(k * kMs, in, &b);
    ASSERT_EQ(a.size(), b.size());
    for (size_t j = 0; j < a.size(); ++j) {
      EXPECT_EQ(a[j].wheelset, b[j].wheelset);
      EXPECT_EQ(a[j].event, b[j].event);
      EXPECT_EQ(a[j].left.status, b[j].left.status);
      expectSame(a[j].left.result, b[j].left.result);
      expectSame(a[j].right.result, b[j].right.result);
    }
  }
  EXPECT_EQ(three.counters(0).steps, 10u);
}

TEST(WheelsetStepper, OneAnswerPerEntryAndPerMissingWheelset) {
  WheelsetStepper v(config({"a", "b", "c"}, "steady"));
  std::vector<WheelsetAnswer> out;
  v.step(0, {entry("a", 0, 0), entry("b", 0, 1), entry("c", 0, 2)}, &out);
  const WheelResult acceptedB = out[1].left.result;
  ASSERT_FALSE(acceptedB.patches.empty());
  // b twice, an unknown name, c missing: five answers, in the input's order then c.
  v.step(kMs, {entry("b", 1, 1), entry("x", 1, 0), entry("a", 1, 0), entry("b", 1, 1)}, &out);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].event, WheelsetEvent::kDuplicate);
  EXPECT_EQ(out[3].event, WheelsetEvent::kDuplicate);
  EXPECT_EQ(out[1].event, WheelsetEvent::kUnknownName);
  EXPECT_EQ(out[1].wheelset, -1);
  EXPECT_FALSE(out[1].left.held);
  EXPECT_TRUE(out[1].left.result.patches.empty());
  EXPECT_EQ(out[1].left.status, WheelAnswerStatus::kRejected);
  EXPECT_EQ(out[2].event, WheelsetEvent::kStepped);
  EXPECT_EQ(out[4].event, WheelsetEvent::kMissing);
  EXPECT_EQ(out[4].wheelset, v.find("c"));
  for (size_t k : {0, 3, 4}) {
    EXPECT_TRUE(out[k].left.held);
    EXPECT_TRUE(out[k].right.held);
    EXPECT_EQ(out[k].left.status, WheelAnswerStatus::kRejected);
    EXPECT_FALSE(out[k].message.empty());
  }
  expectSame(out[0].left.result, acceptedB);         // b's last accepted answer, held
  EXPECT_EQ(v.counters(v.find("b")).duplicate, 2u);  // both entries
  EXPECT_EQ(v.counters(v.find("c")).missing, 1u);
  EXPECT_EQ(v.counters().unknown_names, 1u);
}

TEST(WheelsetStepper, RejectedEntriesHoldTheLastAcceptedAnswer) {
  WheelsetStepperConfig c = config({"a"}, "steady");
  c.max_dt = 0.01;
  WheelsetStepper v(c);
  std::vector<WheelsetAnswer> out;
  v.step(10 * kMs, {entry("a", 0, 0)}, &out);
  const WheelResult left = out[0].left.result, right = out[0].right.result;
  ASSERT_EQ(out[0].left.status, WheelAnswerStatus::kOk);

  auto expectHeld = [&](WheelsetEvent event) {
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].event, event) << toString(out[0].event);
    EXPECT_TRUE(out[0].left.held);
    EXPECT_TRUE(out[0].right.held);
    EXPECT_EQ(out[0].left.status, WheelAnswerStatus::kRejected);
    EXPECT_FALSE(out[0].left.message.empty());
    expectSame(out[0].left.result, left);
    expectSame(out[0].right.result, right);
  };
  WheelsetEntry bad = entry("a", 1, 0);
  bad.state.motion.vy = std::numeric_limits<double>::quiet_NaN();
  v.step(11 * kMs, {bad}, &out);
  expectHeld(WheelsetEvent::kNonFinite);
  // A cant beyond 0.2 rad: stepped, refused by WheelsetContact on both wheels, held.
  bad = entry("a", 1, 0);
  bad.state.motion.cant = -0.25;
  v.step(11 * kMs, {bad}, &out);
  EXPECT_EQ(out[0].event, WheelsetEvent::kStepped);
  for (const WheelAnswer* w : {&out[0].left, &out[0].right}) {
    EXPECT_EQ(w->status, WheelAnswerStatus::kInvalidInput);
    EXPECT_TRUE(w->held);
    EXPECT_NE(w->message.find("cant"), std::string::npos) << w->message;
  }
  expectSame(out[0].left.result, left);
  expectSame(out[0].right.result, right);
  EXPECT_EQ(v.counters(0).invalid_input, 2u);
  v.step(10 * kMs, {entry("a", 1, 0)}, &out);  // not after the accepted stamp
  expectHeld(WheelsetEvent::kOutOfOrder);
  v.step(100 * kMs, {entry("a", 1, 0)}, &out);  // dt 90 ms > max_dt
  expectHeld(WheelsetEvent::kDtTooLarge);
  v.step(101 * kMs, {entry("a", 2, 0)}, &out);  // the time base restarted at 100 ms
  EXPECT_EQ(out[0].event, WheelsetEvent::kStepped);
  EXPECT_DOUBLE_EQ(out[0].dt, 1e-3);
  EXPECT_FALSE(out[0].left.held);

  // A pose beyond the profiles' range: that wheel's answer is held, a zero load is accepted.
  const WheelResult lastLeft = out[0].left.result;
  WheelsetEntry far = entry("a", 3, 0);
  far.state.pose.y = 0.5;
  v.step(102 * kMs, {far}, &out);
  EXPECT_EQ(out[0].event, WheelsetEvent::kStepped);
  EXPECT_NE(out[0].left.status, WheelAnswerStatus::kOk);
  EXPECT_TRUE(out[0].left.held);
  EXPECT_FALSE(out[0].left.message.empty());
  expectSame(out[0].left.result, lastLeft);
  EXPECT_TRUE(out[0].right.held);  // 0.5 m to the left: the right wheel too
  WheelsetEntry lifted = entry("a", 4, 0);
  lifted.state.fz_left = 0.0;
  v.step(103 * kMs, {lifted}, &out);
  EXPECT_EQ(out[0].left.status, WheelAnswerStatus::kNoLoad);
  EXPECT_FALSE(out[0].left.held);
  EXPECT_TRUE(out[0].left.result.patches.empty());
  EXPECT_EQ(out[0].right.status, WheelAnswerStatus::kOk);
  const WheelsetCounters& n = v.counters(0);
  EXPECT_EQ(n.non_finite, 1u);
  EXPECT_EQ(n.out_of_order, 1u);
  EXPECT_EQ(n.dt_too_large, 1u);
  EXPECT_EQ(n.no_load, 1u);
  EXPECT_EQ(n.held, 10u);  // 4 entries x 2 wheels, and both wheels beyond the profiles
}

TEST(WheelsetStepper, ResetAndTimeJumpStartAFreshTimeLine) {
  WheelsetStepperConfig c = config({"a"});
  c.time_jump_reset = 0.5;
  WheelsetStepper v(c), fresh(c);
  std::vector<WheelsetAnswer> out, ref;
  for (int k = 0; k < 5; ++k) v.step((1000 + k) * kMs, {entry("a", k, 0)}, &out);
  // 1 s back: beyond time_jump_reset, so the wheelset starts again from this entry.
  v.step(5 * kMs, {entry("a", 7, 0)}, &out);
  fresh.step(5 * kMs, {entry("a", 7, 0)}, &ref);
  EXPECT_TRUE(out[0].time_jump_reset);
  EXPECT_EQ(out[0].dt, 0.0);
  expectSame(out[0].left.result, ref[0].left.result);
  v.step(6 * kMs, {entry("a", 8, 0)}, &out);
  fresh.step(6 * kMs, {entry("a", 8, 0)}, &ref);
  expectSame(out[0].right.result, ref[0].right.result);

  v.reset();
  WheelsetStepper fresh2(c);
  v.step(1 * kMs, {entry("a", 9, 0)}, &out);  // earlier than before the reset: a new time line
  fresh2.step(1 * kMs, {entry("a", 9, 0)}, &ref);
  EXPECT_EQ(out[0].event, WheelsetEvent::kStepped);
  expectSame(out[0].left.result, ref[0].left.result);
  expectSame(out[0].right.result, ref[0].right.result);
  EXPECT_EQ(v.counters(0).resets, 1u);
  EXPECT_EQ(v.counters(0).time_jump_resets, 1u);
}

TEST(WheelsetStepper, WheelsetsShareOneContactTable) {
  WheelsetStepperConfig c = config({"a", "b"}, "steady");
  c.options.use_contact_table = true;
  c.options.table.max_abs_lateral = 0.003;  // a small table covering the states: quick to build
  c.options.table.max_abs_yaw = 0.01;
  c.options.table.max_abs_roll = 0.005;
  WheelsetStepper v(c);
  ASSERT_TRUE(v.contactTable());
  // The same answers as a WheelsetContact on that table.
  WheelsetContactOptions o = c.options;
  o.contact_table = v.contactTable();
  WheelsetContact single(c.track, c.parameters, o);
  std::vector<WheelsetAnswer> out;
  v.step(0, {entry("a", 0, 0), entry("b", 0, 0)}, &out);
  const WheelsetResult r = single.step(entry("a", 0, 0).state, 0.0);
  ASSERT_EQ(out[0].left.status, WheelAnswerStatus::kOk) << out[0].left.message;
  ASSERT_EQ(out[1].right.status, WheelAnswerStatus::kOk) << out[1].right.message;
  expectSame(out[0].left.result, r.left);
  expectSame(out[1].right.result, r.right);
}

TEST(WheelsetStepper, ConfigurationErrorsNameTheParameter) {
  auto message = [](WheelsetStepperConfig c) {
    try {
      WheelsetStepper v(std::move(c));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(config({})).rfind("wheelsets:", 0), 0u);
  EXPECT_EQ(message(config({"a", "a"})).rfind("wheelsets:", 0), 0u);
  EXPECT_EQ(message(config({""})).rfind("wheelsets:", 0), 0u);
  WheelsetStepperConfig c = config({"a"});
  c.max_dt = 0.0;
  EXPECT_EQ(message(c).rfind("max_dt:", 0), 0u);
  c = config({"a"});
  c.time_jump_reset = -1.0;
  EXPECT_EQ(message(c).rfind("time_jump_reset:", 0), 0u);
  c = config({"a"});
  c.threads = 0;
  EXPECT_EQ(message(c).rfind("threads:", 0), 0u);
  c = config({"a"});
  c.track.gauge = 3.0;
  EXPECT_NE(message(c).find("gauge ="), std::string::npos);
  c = config({"a"});
  c.parameters.mu = -1.0;
  EXPECT_EQ(message(c).rfind("mu", 0), 0u);
}
