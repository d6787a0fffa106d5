// rostest: every input contact_node must refuse gives exactly one output on both topics with the
// documented status and the held output (the last accepted step's forces, bit for bit, or zero
// forces before any), and the node stays up. Contacts: "r" (max_dt 0.5 s,
// time_jump_reset 5 s, max_load_age 0.2 s) and "nojump" (time_jump_reset off).
#include <diagnostic_msgs/DiagnosticArray.h>

#include <limits>

#include "rostest_helpers.hpp"

using namespace wrc_test;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const uint8_t kOk = ContactState::STATUS_OK, kNoLoad = ContactState::STATUS_NO_LOAD,
              kStandstill = ContactState::STATUS_STANDSTILL,
              kRejected = ContactState::STATUS_REJECTED;

ros::Time at(double t) {
  return ros::Time(100.0 + t);
}

void expectZero(const ContactState& s) {
  EXPECT_EQ(s.fx, 0.0);
  EXPECT_EQ(s.fy, 0.0);
  EXPECT_EQ(s.mz, 0.0);
}

/// A rejected step: the forces of the last accepted step `accepted`, on both outputs.
void expectHeld(const ContactState& s, const ContactState& accepted) {
  EXPECT_EQ(s.status, ContactState::STATUS_REJECTED);
  EXPECT_TRUE(s.held);
  EXPECT_EQ(s.fx, accepted.fx);
  EXPECT_EQ(s.fy, accepted.fy);
  EXPECT_EQ(s.fz, accepted.fz);
  EXPECT_EQ(s.mz, accepted.mz);
  EXPECT_EQ(s.a, accepted.a);
  EXPECT_EQ(s.b, accepted.b);
  EXPECT_EQ(s.adhesion_fraction, accepted.adhesion_fraction);
}

class Rejections : public ::testing::Test {
 protected:
  void SetUp() override {
    r = std::make_unique<ContactClient>(nh, "r");
    ASSERT_TRUE(r->connect());
    ASSERT_TRUE(r->reset());
  }
  void TearDown() override {
    if (r) {
      EXPECT_TRUE(r->oneOutputPerInput());
    }
  }
  /// A valid creepage after a load: status ok, forces non-zero.
  void good(double t, ContactState* s = nullptr) {
    ContactState tmp;
    ASSERT_TRUE(r->creep(at(t), 0.01, 0.005, 0.1, 0.025, &tmp));
    EXPECT_EQ(tmp.status, kOk) << tmp.message;
    EXPECT_NE(tmp.fx, 0.0);
    if (s) *s = tmp;
  }
  ros::NodeHandle nh;
  std::unique_ptr<ContactClient> r;
};

}  // namespace

TEST_F(Rejections, NoLoadYetAndNonPositiveLoadGiveZeroForcesWithNoLoadStatus) {
  ContactState s;
  ASSERT_TRUE(r->creep(at(0.0), 0.01, 0.0, 0.0, 0.025, &s));
  EXPECT_EQ(s.status, kNoLoad);
  EXPECT_NE(s.message.find("no normal load"), std::string::npos) << s.message;
  expectZero(s);
  EXPECT_EQ(s.load_match, ContactState::LOAD_NONE);
  for (double fz : {0.0, -50.0}) {
    const double t = fz < 0 ? 0.02 : 0.01;
    r->load(at(t), fz);
    ASSERT_TRUE(r->creep(at(t), 0.01, 0.0, 0.0, 0.025, &s));
    EXPECT_EQ(s.status, kNoLoad);
    EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP);
    expectZero(s);
  }
}

TEST_F(Rejections, NonFiniteFieldsAreRejectedAndTheNodeGoesOn) {
  // Before any accepted step: zero creep forces, fz = the step's own load.
  ContactState first, accepted;
  r->load(at(0.0), 470.5);
  ASSERT_TRUE(r->creep(at(0.0), kNan, 0, 0, 0.025, &first));
  EXPECT_EQ(first.status, kRejected);
  EXPECT_FALSE(first.held);
  expectZero(first);
  EXPECT_EQ(first.fz, 470.5);
  good(0.0, &accepted);
  const double bad[][4] = {{kNan, 0, 0, 0.025},
                           {0.01, kInf, 0, 0.025},
                           {0.01, 0, -kInf, 0.025},
                           {0.01, 0, 0, kNan},
                           {0.01, 0, 0, kInf}};
  ContactState s;
  for (const auto& b : bad) {
    ASSERT_TRUE(r->creep(at(0.1), b[0], b[1], b[2], b[3], &s));
    EXPECT_NE(s.message.find("not finite"), std::string::npos) << s.message;
    expectHeld(s, accepted);
  }
  r->load(at(0.05), kNan);      // a NaN load is dropped: the previous one stays
  good(0.1, &s);                // no load stamped 0.1 s: after load_wait, the latest one, flagged
  EXPECT_DOUBLE_EQ(s.dt, 0.1);  // from the last accepted message
  EXPECT_EQ(s.fz, 470.5);
  EXPECT_EQ(s.load_match, ContactState::LOAD_UNMATCHED);
  EXPECT_EQ(s.load_stamp, at(0.0));
  EXPECT_NE(s.message.find("load_wait"), std::string::npos) << s.message;
  wheel_rail_contact::Step::Response res;
  ASSERT_TRUE(r->step(at(0.2), 0.01, 0, 0, 0.025, kNan, &res));
  EXPECT_EQ(res.status, kRejected);
  EXPECT_TRUE(res.held);
  EXPECT_EQ(res.fx, s.fx);
  EXPECT_EQ(res.fz, s.fz);
  EXPECT_EQ(r->states.back().fx, s.fx);  // published held too
}

TEST_F(Rejections, OlderOrEqualStampsAreRejected) {
  r->load(at(1.0), 470.5);
  ContactState accepted, s;
  good(1.0, &accepted);
  for (double t : {1.0, 0.5}) {
    ASSERT_TRUE(r->creep(at(t), 0.01, 0, 0, 0.025, &s));
    EXPECT_NE(s.message.find("not after"), std::string::npos) << s.message;
    expectHeld(s, accepted);
  }
  r->load(at(1.1), 470.5);
  good(1.1);
}

TEST_F(Rejections, AbsurdDtIsRejectedAndTheNextMessageSteps) {
  r->load(at(0.0), 470.5);
  ContactState accepted, s;
  good(0.0, &accepted);
  r->load(at(3.0), 470.5);
  ASSERT_TRUE(r->creep(at(3.0), 0.01, 0, 0, 0.025, &s));  // dt 3 s > max_dt 0.5 s
  EXPECT_NE(s.message.find("max_dt"), std::string::npos) << s.message;
  expectHeld(s, accepted);
  r->load(at(3.1), 470.5);
  good(3.1, &s);
  EXPECT_NEAR(s.dt, 0.1, 1e-9);
}

TEST_F(Rejections, StandstillHoldsTheForcesAndBackwardsRollingIsMirrored) {
  r->load(at(0.0), 470.5);
  ContactState before, s;
  good(0.0, &before);
  r->load(at(0.1), 470.5);
  ASSERT_TRUE(r->creep(at(0.1), 0.02, 0.0, 0.0, 0.0, &s));  // V = 0
  EXPECT_EQ(s.status, kStandstill);
  EXPECT_EQ(s.fx, before.fx);
  EXPECT_EQ(s.fy, before.fy);
  r->load(at(0.2), 470.5);
  ASSERT_TRUE(r->creep(at(0.2), 0.01, 0.0, 0.0, -0.025, &s));  // V < 0: rolls backwards
  EXPECT_EQ(s.status, kOk);
  EXPECT_GT(s.fx,
            0.0);  // creepage / signed V: V xi < 0 slides backwards, the force pushes forwards
  r->load(at(0.3), 470.5);
  good(0.3);
}

TEST_F(Rejections, BackwardsTimeJumpResetsOnlyWhenEnabled) {
  // "r": a jump back beyond time_jump_reset = 5 s acts like a reset; the result equals a fresh
  // start fed the same load and message.
  r->load(at(10.0), 470.5);
  good(10.0);
  r->load(at(10.1), 470.5);
  good(10.1);
  r->load(at(0.0), 400.0);  // the simulator restarted: its load comes first
  ContactState jumped, fresh;
  ASSERT_TRUE(r->creep(at(0.0), 0.01, 0.005, 0.1, 0.025, &jumped));
  EXPECT_EQ(jumped.status, kOk) << jumped.message;
  EXPECT_EQ(jumped.dt, 0.0);
  ASSERT_TRUE(r->reset());
  r->load(at(0.0), 400.0);
  ASSERT_TRUE(r->creep(at(0.0), 0.01, 0.005, 0.1, 0.025, &fresh));
  EXPECT_EQ(jumped.fx, fresh.fx);
  EXPECT_EQ(jumped.fy, fresh.fy);
  EXPECT_EQ(jumped.fz, 400.0);

  ContactClient nojump(nh, "nojump");
  ASSERT_TRUE(nojump.connect());
  nojump.load(at(10.0), 470.5);
  ContactState accepted, s;
  ASSERT_TRUE(nojump.creep(at(10.0), 0.01, 0, 0, 0.025, &accepted));
  EXPECT_EQ(accepted.status, kOk);
  ASSERT_TRUE(nojump.creep(at(0.0), 0.01, 0, 0, 0.025, &s));  // answered at once: a later load
  expectHeld(s, accepted);
}

TEST_F(Rejections, ConflictingGeometryIsRejectedAndHeld) {
  r->load(at(0.0), 470.5);
  ContactState accepted, s;
  good(0.0, &accepted);
  wheel_rail_contact::Creepage both;  // semi-axes and curvatures at once
  both.a = 0.02;
  both.b = 0.02;
  both.curvature_x = 10.0;
  both.curvature_y = 10.0;
  wheel_rail_contact::Creepage half;  // a without b
  half.a = 0.02;
  wheel_rail_contact::Creepage negative;
  negative.mu = -0.1;
  for (const auto& g : {both, half, negative}) {
    ASSERT_TRUE(r->creep(at(0.0), 0.01, 0, 0, 0.025, &s, g));  // its load came already
    expectHeld(s, accepted);
  }
  EXPECT_NE(r->states[r->states.size() - 3].message.find("both"), std::string::npos);
  EXPECT_NE(r->states[r->states.size() - 2].message.find("together"), std::string::npos);
  EXPECT_NE(r->states.back().message.find("mu is negative"), std::string::npos);
}

TEST_F(Rejections, DiagnosticsCountTheRejections) {
  r->load(at(0.0), 470.5);
  good(0.0);
  ContactState s;
  ASSERT_TRUE(r->creep(at(0.0), 0.01, 0, 0, 0.025, &s));  // equal stamp
  diagnostic_msgs::DiagnosticArray last;
  bool found = false;
  ros::Subscriber sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& st : m->status)
          if (st.name.find("contact /r") != std::string::npos) {
            for (const auto& kv : st.values)
              if (kv.key == "rejected: creepage stamp out of order" && kv.value != "0")
                found = true;
          }
      });
  EXPECT_TRUE(spinUntil([&] { return found; }, 5.0)) << "no diagnostics with the rejections";
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rejections");
  return RUN_ALL_TESTS();
}
