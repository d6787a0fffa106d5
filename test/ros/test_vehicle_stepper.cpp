// VehicleStepper: N named contacts stepped per tick equal N separate ContactSteppers; unknown,
// missing and repeated names, malformed geometry, the hold rule and reset are defined outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "../../src/ros/vehicle_stepper.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

using namespace wheel_rail_contact;

namespace {

const int64_t kMs = 1000000;  // 1 ms in ns

std::vector<VehicleContactConfig> configs(const std::vector<std::string>& names,
                                          const std::string& model = "steady") {
  std::vector<VehicleContactConfig> c;
  for (const auto& n : names) {
    VehicleContactConfig k;
    k.name = n;
    k.parameters.model = model;
    k.parameters.nx = k.parameters.ny = 8;
    c.push_back(k);
  }
  return c;
}

VehicleContactInput entry(const std::string& name, double xi, double fz, double V = 20.0) {
  VehicleContactInput e;
  e.name = name;
  e.in.V = V;
  e.in.xi = xi;
  e.in.eta = -0.5 * xi;
  e.in.phi = 0.1;
  e.in.fz = fz;
  return e;
}

std::unique_ptr<ContactStepper> single(const VehicleContactConfig& c) {
  return std::make_unique<ContactStepper>(makeContactModel(c.parameters), c.options);
}

void expectSame(const StepResult& a, const StepResult& b) {
  EXPECT_EQ(a.out.status, b.out.status);
  EXPECT_EQ(a.out.fx, b.out.fx);
  EXPECT_EQ(a.out.fy, b.out.fy);
  EXPECT_EQ(a.out.mz, b.out.mz);
  EXPECT_EQ(a.out.fz, b.out.fz);
  EXPECT_EQ(a.out.a, b.out.a);
  EXPECT_EQ(a.out.b, b.out.b);
  EXPECT_EQ(a.dt, b.dt);
  EXPECT_EQ(a.message, b.message);
}

}  // namespace

TEST(VehicleStepper, EqualsSeparateSteppersInAnyEntryOrder) {
  const std::vector<std::string> names{"w1_left", "w1_right", "w2_left", "w2_right"};
  auto cfg = configs(names, "nss");
  VehicleStepper v(cfg);
  std::vector<std::unique_ptr<ContactStepper>> s;
  for (const auto& c : cfg) s.push_back(single(c));
  std::vector<VehicleContactResult> out;
  for (int k = 0; k < 30; ++k) {
    std::vector<VehicleContactInput> in;
    for (size_t i = 0; i < names.size(); ++i)
      in.push_back(entry(names[i], 1e-4 * std::sin(0.3 * k + i), 7e4 + 1e3 * i + 50.0 * k));
    if (k % 2) std::swap(in[0], in[3]);  // the order of entries is the sender's choice
    v.step(k * kMs, in, &out);
    ASSERT_EQ(out.size(), in.size());
    for (size_t j = 0; j < in.size(); ++j) {
      const int i = v.find(in[j].name);
      ASSERT_EQ(out[j].contact, i);
      EXPECT_EQ(out[j].event, VehicleEvent::kStepped);
      expectSame(out[j].step, s[i]->stepWithLoad(k * kMs, in[j].in));
      EXPECT_EQ(out[j].step.out.status, StepStatus::kOk);
    }
  }
}

TEST(VehicleStepper, UnknownMissingAndRepeatedNamesAreRejectedEntriesNeverDropped) {
  VehicleStepper v(configs({"left", "right", "spare"}));
  std::vector<VehicleContactResult> out;
  v.step(0, {entry("left", 1e-3, 8e4), entry("right", 1e-3, 8e4), entry("spare", 1e-3, 8e4)}, &out);
  const StepOutput leftOk = out[0].step.out;
  ASSERT_EQ(leftOk.status, StepStatus::kOk);
  ASSERT_NE(leftOk.fx, 0.0);

  // right twice, spare absent, one unknown name: 4 entries + 1 missing.
  v.step(kMs,
         {entry("right", 2e-3, 8e4), entry("lefty", 1e-3, 8e4), entry("left", 2e-3, 8e4),
          entry("right", 3e-3, 8e4)},
         &out);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].event, VehicleEvent::kDuplicate);
  EXPECT_EQ(out[3].event, VehicleEvent::kDuplicate);
  EXPECT_NE(out[0].step.message.find("appears 2 times"), std::string::npos);
  EXPECT_EQ(out[1].event, VehicleEvent::kUnknownName);
  EXPECT_EQ(out[1].contact, -1);
  EXPECT_EQ(out[1].step.out.fx, 0.0);  // no contact to hold for
  EXPECT_NE(out[1].step.message.find("unknown contact 'lefty'"), std::string::npos);
  EXPECT_EQ(out[2].event, VehicleEvent::kStepped);
  EXPECT_EQ(out[2].step.out.status, StepStatus::kOk);
  EXPECT_EQ(out[4].event, VehicleEvent::kMissing);
  EXPECT_EQ(out[4].contact, v.find("spare"));
  EXPECT_NE(out[4].step.message.find("missing"), std::string::npos);
  for (size_t j : {0u, 1u, 3u, 4u}) EXPECT_EQ(out[j].step.out.status, StepStatus::kRejected) << j;
  // The rejected contacts repeat their last accepted forces (tick 0's, equal for all three).
  for (size_t j : {0u, 3u, 4u}) {
    EXPECT_TRUE(out[j].held);
    EXPECT_EQ(out[j].step.out.fx, leftOk.fx);
    EXPECT_EQ(out[j].step.out.fy, leftOk.fy);
    EXPECT_EQ(out[j].step.out.fz, leftOk.fz);
  }
  EXPECT_EQ(v.counters(v.find("right")).duplicate, 2u);
  EXPECT_EQ(v.counters(v.find("spare")).missing, 1u);
  EXPECT_EQ(v.counters().unknownNames, 1u);

  // An empty tick: every contact missing, nothing stepped, nothing lost.
  v.step(2 * kMs, {}, &out);
  ASSERT_EQ(out.size(), 3u);
  for (const auto& r : out) EXPECT_EQ(r.event, VehicleEvent::kMissing);
  // A rejected contact was not stepped: its next dt spans the ticks it missed.
  v.step(3 * kMs, {entry("left", 1e-3, 8e4), entry("right", 1e-3, 8e4), entry("spare", 1e-3, 8e4)},
         &out);
  EXPECT_DOUBLE_EQ(out[0].step.dt, 2e-3);
  EXPECT_DOUBLE_EQ(out[1].step.dt, 3e-3);
  EXPECT_DOUBLE_EQ(out[2].step.dt, 3e-3);
}

TEST(VehicleStepper, StepperRejectionsHoldTheLastAcceptedForces) {
  VehicleStepper v(configs({"c"}));
  std::vector<VehicleContactResult> out;
  v.step(10 * kMs, {entry("c", 1e-3, 8e4)}, &out);
  const StepOutput ok = out[0].step.out;
  auto nan = entry("c", std::numeric_limits<double>::quiet_NaN(), 8e4);
  v.step(11 * kMs, {nan}, &out);
  EXPECT_EQ(out[0].step.out.status, StepStatus::kRejected);
  EXPECT_EQ(out[0].step.event, StepEvent::kNonFinite);
  EXPECT_TRUE(out[0].held);
  EXPECT_EQ(out[0].step.out.fx, ok.fx);
  EXPECT_EQ(out[0].step.out.mz, ok.mz);
  v.step(5 * kMs, {entry("c", 2e-3, 8e4)}, &out);  // out of order
  EXPECT_EQ(out[0].step.event, StepEvent::kOutOfOrder);
  EXPECT_EQ(out[0].step.out.fy, ok.fy);
  // No load is an accepted step (zero force, the wheel is off the rail): it is what gets held.
  v.step(12 * kMs, {entry("c", 1e-3, 0.0)}, &out);
  EXPECT_EQ(out[0].step.out.status, StepStatus::kNoLoad);
  v.step(13 * kMs, {nan}, &out);
  EXPECT_TRUE(out[0].held);
  EXPECT_EQ(out[0].step.out.fx, 0.0);
  EXPECT_EQ(v.counters(0).held, 3u);
}

TEST(VehicleStepper, CurvaturesGiveTheHertzPatchOfTheTicksLoad) {
  VehicleStepper v(configs({"c"}));
  auto cfg = configs({"c"});
  auto s = single(cfg[0]);
  std::vector<VehicleContactResult> out;
  auto e = entry("c", 1e-3, 9e4);
  e.curvatureX = 2.0;
  e.curvatureY = 5.0;
  v.step(0, {e}, &out);
  const HertzEllipse h =
      hertzFromCurvatures(9e4, 2.0, 5.0, cfg[0].parameters.G, cfg[0].parameters.nu);
  StepInput in = e.in;
  in.a = h.a;
  in.b = h.b;
  expectSame(out[0].step, s->stepWithLoad(0, in));
  EXPECT_EQ(out[0].step.out.a, h.a);
  EXPECT_EQ(out[0].step.out.b, h.b);
  EXPECT_GT(h.a, h.b);  // the smaller curvature along x: the longer axis along x
}

TEST(VehicleStepper, MalformedGeometryIsRejectedAndHeld) {
  struct Case {
    double a, b, cx, cy, mu;
    const char* why;
  } cases[] = {
      {1e-3, 0, 0, 0, 0, "a and b must be given together"},
      {0, 0, 0, 3.0, 0, "curvature_x and curvature_y must be given together"},
      {1e-3, 1e-3, 2.0, 3.0, 0, "both a, b and curvature_x, curvature_y given"},
      {-1e-3, 1e-3, 0, 0, 0, "a is negative"},
      {0, 0, 0, 0, std::numeric_limits<double>::infinity(), "mu is not finite"},
      {0, 0, std::numeric_limits<double>::quiet_NaN(), 1.0, 0, "curvature_x is not finite"},
      {0, 0, 1e13, 1.0, 0, "curvature_x exceeds"},
  };
  int64_t t = 0;
  for (const auto& c : cases) {
    VehicleStepper v(configs({"c"}));
    std::vector<VehicleContactResult> out;
    auto e = entry("c", 1e-3, 8e4);
    e.in.a = c.a;
    e.in.b = c.b;
    e.in.mu = c.mu;
    e.curvatureX = c.cx;
    e.curvatureY = c.cy;
    v.step(t += kMs, {e}, &out);
    EXPECT_EQ(out[0].event, VehicleEvent::kBadGeometry) << c.why;
    EXPECT_NE(out[0].step.message.find(c.why), std::string::npos) << out[0].step.message;
  }
  {
    // Curvatures with no load: the stepper reports no load, as it does without them.
    VehicleStepper v(configs({"c"}));
    std::vector<VehicleContactResult> out;
    auto e = entry("c", 1e-3, 0.0);
    e.curvatureX = e.curvatureY = 2.0;
    v.step(0, {e}, &out);
    EXPECT_EQ(out[0].event, VehicleEvent::kStepped);
    EXPECT_EQ(out[0].step.out.status, StepStatus::kNoLoad);
  }

  VehicleStepper v(configs({"c"}));
  std::vector<VehicleContactResult> out;
  v.step(0, {entry("c", 1e-3, 8e4)}, &out);
  const double fx = out[0].step.out.fx;
  auto bad = entry("c", 5e-3, 8e4);
  bad.in.a = 1e-3;
  v.step(kMs, {bad}, &out);
  EXPECT_EQ(out[0].event, VehicleEvent::kBadGeometry);
  EXPECT_EQ(out[0].step.out.status, StepStatus::kRejected);
  EXPECT_EQ(out[0].step.out.fx, fx);
  EXPECT_EQ(v.counters(0).badGeometry, 1u);
}

TEST(VehicleStepper, ResetClearsEveryContactAndTheHeldForces) {
  auto cfg = configs({"a", "b"}, "nss");
  VehicleStepper v(cfg);
  std::vector<VehicleContactResult> out, first;
  const std::vector<VehicleContactInput> tick{entry("a", 1e-3, 8e4), entry("b", -1e-3, 7e4)};
  v.step(100 * kMs, tick, &first);
  v.step(101 * kMs, tick, &out);
  v.reset();
  // The same stamps again: a fresh start, not out of order, and the same forces as at first.
  v.step(100 * kMs, tick, &out);
  for (size_t j = 0; j < 2; ++j) expectSame(out[j].step, first[j].step);
  v.reset();
  v.step(50 * kMs, {}, &out);
  for (const auto& r : out) EXPECT_EQ(r.step.out.fx, 0.0);  // nothing accepted since the reset
  EXPECT_EQ(v.stepper(0).counters().resets, 2u);
}

TEST(VehicleStepper, ConfigurationErrorsNameTheContact) {
  EXPECT_THROW(VehicleStepper({}), std::invalid_argument);
  try {
    VehicleStepper v(configs({"x", "x"}));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'x' is listed twice"), std::string::npos);
  }
  auto cfg = configs({"x", "y"});
  cfg[1].parameters.mu = -1.0;
  try {
    VehicleStepper v(cfg);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("y/mu", 0), 0u) << e.what();
  }
}

TEST(VehicleStepper, APatchBeyondTheFixedMeshGrowsItAndLosesNoForce) {
  // As in the core (StepGeometry.APatchBeyondTheDefaultFixedMeshLosesNoForce): default parameters
  // (nss on the fixed mesh sized for fz_max = 1.5 fz0), linear range; the ticks' patch doubled at
  // the same a/b and load gives four times the force, and the tick that grows the mesh says so.
  for (const char* model : {"nss", "auto"}) {
    VehicleContactConfig c;
    c.name = "w";
    c.parameters.model = model;
    VehicleStepper v({c});
    const double a0 = c.parameters.a0, b0 = c.parameters.b0;
    auto tick = [&](double scale) {
      VehicleContactInput e = entry("w", 1e-5, c.parameters.fz0);
      e.in.eta = e.in.phi = 0.0;
      e.in.a = scale * a0;
      e.in.b = scale * b0;
      return std::vector<VehicleContactInput>{e};
    };
    std::vector<VehicleContactResult> out;
    int64_t t = 0;
    for (int k = 0; k < 200; ++k) v.step(t += kMs / 10, tick(1.0), &out);
    const double before = out[0].step.out.fx;
    v.step(t += kMs / 10, tick(2.0), &out);
    EXPECT_EQ(out[0].step.out.status, StepStatus::kOk) << model;
    EXPECT_NE(out[0].step.message.find("grew"), std::string::npos) << model;
    for (int k = 0; k < 200; ++k) v.step(t += kMs / 10, tick(2.0), &out);
    EXPECT_NEAR(out[0].step.out.fx / before, 4.0, 0.04) << model;
    EXPECT_EQ(out[0].step.message, "") << model;
  }
}
