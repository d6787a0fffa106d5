// rostest: wheelset_node (or its nodelet) against contact_cli wheelset on the same profiles,
// parameters and wheelset states (the patches' geometry, normal forces, creepages and forces),
// through the wheelset_step service and the wheelset_input/wheelset_forces topics (one answer per
// input, equal to the service's after a reset), each tick with its own cant as the CLI's cant
// column; the hold rule (stamp out of order, unknown, missing and repeated names, a cant beyond
// 0.2 rad); the diagnostics. Private
// parameter ~ns: the node's namespace. No sleeps: every wait is for an event, with a timeout.
#include <diagnostic_msgs/DiagnosticArray.h>

#include <map>

#include "../../examples/wait_for_link.hpp"
#include "rostest_helpers.hpp"
#include "wheel_rail_contact/WheelsetForces.h"
#include "wheel_rail_contact/WheelsetInput.h"
#include "wheel_rail_contact/WheelsetStep.h"

using namespace wrc_test;
using wheel_rail_contact::PatchContactState;
using wheel_rail_contact::WheelContactState;
using wheel_rail_contact::WheelsetContactState;
using wheel_rail_contact::WheelsetForces;
using wheel_rail_contact::WheelsetInput;
using wheel_rail_contact::WheelsetKinematics;

namespace {

std::string ns = "/wheelsets";
const char* const kNames[] = {"front", "rear"};
constexpr int kTicks = 40;
constexpr int64_t kStep = 1000000;  // 1 ms [ns]

/// Wheelset w's state at tick k: the front one moves out toward its flange (tread, gauge corner),
/// the rear one sways on its treads; V 20 m/s, 50 kN per wheel, a 300 m left curve whose cant
/// (the outer, right rail raised) grows under the front wheelset and sways under the rear one.
WheelsetKinematics state(int w, int k) {
  WheelsetKinematics s;
  s.name = kNames[w];
  const double q = static_cast<double>(k) / kTicks;
  s.lateral = w == 0 ? 1e-3 + 5e-3 * q : 1e-3 * std::sin(6.0 * q);
  s.yaw = w == 0 ? 2e-3 * q : -1e-3 * std::cos(6.0 * q);
  s.roll = 0.0;
  s.velocity = 20.0;
  s.pitch_rate = 20.0 / 0.46 * (1.0 - 2e-4 * (w + 1));
  s.lateral_velocity = w == 0 ? 0.125 : 0.15 * std::cos(6.0 * q);
  s.yaw_rate = w == 0 ? 0.05 : 0.15 * std::sin(6.0 * q);
  s.load_left = 5e4 + 2e3 * w;
  s.load_right = 5e4 - 1e3 * k;
  s.curvature = 1.0 / 300.0;
  s.cant = w == 0 ? -0.02 - 0.12 * q : -0.1 + 0.03 * std::sin(6.0 * q);
  return s;
}

WheelsetInput tick(int k, int64_t t0 = 1000 * kStep) {
  WheelsetInput in;
  in.header.stamp.fromNSec(static_cast<uint64_t>(t0 + k * kStep));
  for (int w = 0; w < 2; ++w) in.wheelsets.push_back(state(w, k));
  return in;
}

/// contact_cli wheelset's rows: [wheelset][tick] -> rows of that tick, left wheel first.
struct CliRow {
  std::string wheel, patch, status;
  double v[16];  // y_rail .. pmax (the columns between patch and status)
};

bool cliReference(std::vector<std::vector<std::vector<CliRow>>>* ref) {
  const std::string node = ns + "/wheelset_node";
  std::string wheel, rail;
  if (!ros::param::get(node + "/wheel_profile", wheel) ||
      !ros::param::get(node + "/rail_profile", rail))
    return false;
  const std::string scheme = "package://wheel_rail_contact/";
  if (wheel.rfind(scheme, 0) == 0)
    wheel = std::string(WRC_SOURCE_DIR) + "/" + wheel.substr(scheme.size());
  if (rail.rfind(scheme, 0) == 0)
    rail = std::string(WRC_SOURCE_DIR) + "/" + rail.substr(scheme.size());
  ref->assign(2, {});
  for (int w = 0; w < 2; ++w) {
    const std::string csv =
        "/tmp/rostest_wheelset_" + std::to_string(getpid()) + "_" + std::to_string(w);
    {
      std::ofstream f(csv + ".csv");
      f << "t,y,yaw,roll,V,omega,fz_left,fz_right,vy,yaw_rate,curvature,cant\n";
      f.precision(17);
      for (int k = 0; k < kTicks; ++k) {
        const WheelsetKinematics s = state(w, k);
        f << 1.0 + k * 1e-3 << "," << s.lateral << "," << s.yaw << "," << s.roll << ","
          << s.velocity << "," << s.pitch_rate << "," << s.load_left << "," << s.load_right << ","
          << s.lateral_velocity << "," << s.yaw_rate << "," << s.curvature << "," << s.cant << "\n";
      }
    }
    std::string out;
    const std::string cmd = std::string(WRC_CONTACT_CLI) + " wheelset --wheel-profile '" + wheel +
                            "' --rail-profile '" + rail + "' --scenario " + csv + ".csv" +
                            cliOptionsOf(node) + " > " + csv + ".out";
    const int code = run(cmd, &out);
    if (code != 0) {
      ADD_FAILURE() << cmd << "\n" << out;
      return false;
    }
    std::istringstream lines(fileText(csv + ".out"));
    std::string line;
    std::getline(lines, line);  // header
    (*ref)[w].assign(kTicks, {});
    std::map<std::string, int> tickOf;
    int k = -1;
    std::string lastT;
    while (std::getline(lines, line)) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      std::string x;
      while (std::getline(ss, x, ',')) f.push_back(x);
      if (f.size() != 19) continue;
      if (f[0] != lastT) {
        ++k;
        lastT = f[0];
      }
      CliRow r;
      r.wheel = f[1];
      r.patch = f[2];
      r.status = f[18];
      for (int i = 0; i < 15; ++i) r.v[i] = f[3 + i].empty() ? 0.0 : std::stod(f[3 + i]);
      if (k >= 0 && k < kTicks) (*ref)[w][k].push_back(r);
    }
    if (k != kTicks - 1) {
      ADD_FAILURE() << "contact_cli wheelset gave " << k + 1 << " ticks";
      return false;
    }
  }
  return true;
}

/// Within rel of the scale (dt from ns stamps and from the CSV's t differ in the last bits).
void expectNear(double node, double cli, double scale, const char* what) {
  EXPECT_NEAR(node, cli, 1e-9 * scale + 1e-12) << what;
}

void expectSameAnswer(const WheelsetContactState& a, const WheelsetContactState& b) {
  for (const auto& [x, y] : {std::pair{&a.left, &b.left}, std::pair{&a.right, &b.right}}) {
    EXPECT_EQ(x->status, y->status);
    EXPECT_EQ(x->held, y->held);
    ASSERT_EQ(x->patches.size(), y->patches.size());
    for (size_t i = 0; i < x->patches.size(); ++i) {
      EXPECT_EQ(x->patches[i].fx, y->patches[i].fx);
      EXPECT_EQ(x->patches[i].fs, y->patches[i].fs);
      EXPECT_EQ(x->patches[i].mz, y->patches[i].mz);
      EXPECT_EQ(x->patches[i].fn, y->patches[i].fn);
    }
    EXPECT_EQ(x->wrench.force.x, y->wrench.force.x);
    EXPECT_EQ(x->wrench.force.y, y->wrench.force.y);
    EXPECT_EQ(x->wrench.force.z, y->wrench.force.z);
    EXPECT_EQ(x->wrench.torque.x, y->wrench.torque.x);
    EXPECT_EQ(x->wrench.torque.z, y->wrench.torque.z);
  }
}

class WheelsetClient {
 public:
  WheelsetClient() {
    ros::NodeHandle nh;
    sub_ = nh.subscribe(ns + "/wheelset_forces", 1000, &WheelsetClient::onForces, this,
                        ros::TransportHints().tcpNoDelay());
    pub_ = nh.advertise<WheelsetInput>(ns + "/wheelset_input", 1000);
    EXPECT_TRUE(ros::service::waitForService(ns + "/wheelset_step", ros::Duration(120.0)));
    step_ = nh.serviceClient<wheel_rail_contact::WheelsetStep>(ns + "/wheelset_step", true);
    reset_ = nh.serviceClient<wheel_rail_contact::Reset>(ns + "/reset");
    EXPECT_TRUE(spinUntil([&] { return pub_.getNumSubscribers() > 0; }, 30.0));
    EXPECT_TRUE(wheel_rail_contact_examples::waitForLink(
        ros::names::resolve(ns + "/wheelset_forces"), 30.0));
  }
  bool step(const WheelsetInput& in, WheelsetForces* out) {
    wheel_rail_contact::WheelsetStep srv;
    srv.request.input = in;
    if (!step_.call(srv)) return false;
    *out = srv.response.forces;
    // Its publication too, so that the topic's answers below are only the topic's.
    const uint64_t stamp = in.header.stamp.toNSec();
    return spinUntil([&] { return received.count(stamp) > 0; }, 20.0);
  }
  bool reset() {
    wheel_rail_contact::Reset srv;
    return reset_.call(srv) && srv.response.success;
  }
  ros::Publisher pub_;
  std::map<uint64_t, WheelsetForces> received;
  size_t count = 0;

 private:
  void onForces(const WheelsetForces::ConstPtr& m) {
    received[m->header.stamp.toNSec()] = *m;
    ++count;
  }
  ros::Subscriber sub_;
  ros::ServiceClient step_, reset_;
};

}  // namespace

TEST(WheelsetNode, EqualsContactCliWheelsetAndTheTopicEqualsTheService) {
  std::vector<std::vector<std::vector<CliRow>>> ref;
  ASSERT_TRUE(cliReference(&ref));
  WheelsetClient c;
  ASSERT_TRUE(c.reset());
  std::vector<WheelsetForces> service(kTicks);
  int patches = 0, flange = 0;
  for (int k = 0; k < kTicks; ++k) {
    ASSERT_TRUE(c.step(tick(k), &service[k])) << k;
    const WheelsetForces& f = service[k];
    ASSERT_EQ(f.wheelsets.size(), 2u);
    for (int w = 0; w < 2; ++w) {
      const WheelsetContactState& s = f.wheelsets[w];
      EXPECT_EQ(s.name, kNames[w]);
      EXPECT_EQ(s.dt, k == 0 ? 0.0 : 1e-3);
      size_t row = 0;
      for (const WheelContactState* wheel : {&s.left, &s.right}) {
        const std::string side = wheel == &s.left ? "left" : "right";
        std::vector<const CliRow*> rows;
        for (const CliRow& r : ref[w][k])
          if (r.wheel == side) rows.push_back(&r);
        ASSERT_FALSE(rows.empty());
        ++row;
        if (rows[0]->patch == "none") {  // the CLI's wheel without a patch: the node holds it
          EXPECT_TRUE(wheel->held || rows[0]->status == "no_load") << rows[0]->status;
          continue;
        }
        ASSERT_EQ(wheel->status, WheelContactState::STATUS_OK) << wheel->message;
        // The wheel's wrench: the sum of its patches'.
        geometry_msgs::Wrench sum;
        for (const PatchContactState& p : wheel->patches) {
          sum.force.x += p.wrench.force.x;
          sum.force.y += p.wrench.force.y;
          sum.force.z += p.wrench.force.z;
          sum.torque.x += p.wrench.torque.x;
          sum.torque.y += p.wrench.torque.y;
          sum.torque.z += p.wrench.torque.z;
        }
        expectNear(wheel->wrench.force.x, sum.force.x, 5e4, "force.x");
        expectNear(wheel->wrench.force.y, sum.force.y, 5e4, "force.y");
        expectNear(wheel->wrench.force.z, sum.force.z, 5e4, "force.z");
        expectNear(wheel->wrench.torque.x, sum.torque.x, 5e4, "torque.x");
        expectNear(wheel->wrench.torque.y, sum.torque.y, 5e4, "torque.y");
        expectNear(wheel->wrench.torque.z, sum.torque.z, 5e4, "torque.z");
        ASSERT_EQ(wheel->patches.size(), rows.size()) << "wheelset " << w << " tick " << k;
        for (size_t i = 0; i < rows.size(); ++i) {
          const PatchContactState& p = wheel->patches[i];
          const double* v = rows[i]->v;
          EXPECT_EQ(p.slot, rows[i]->patch);
          if (p.zone != PatchContactState::ZONE_TREAD) ++flange;
          ++patches;
          expectNear(p.y_rail, v[0], 0.1, "y_rail");
          expectNear(p.z_rail, v[1], 0.1, "z_rail");
          expectNear(p.y_wheel, v[2], 0.1, "y_wheel");
          expectNear(p.contact_angle, v[3], 1.0, "contact_angle");
          expectNear(p.rolling_radius, v[4], 1.0, "rolling_radius");
          expectNear(p.xi, v[5], 1e-2, "xi");
          expectNear(p.eta, v[6], 1e-2, "eta");
          expectNear(p.phi, v[7], 1.0, "phi");
          expectNear(p.fn, v[8], 5e4, "fn");
          expectNear(p.fx, v[9], 5e4, "fx");
          expectNear(p.fs, v[10], 5e4, "fs");
          expectNear(p.mz, v[11], 100.0, "mz");
          expectNear(p.a, v[12], 1e-2, "a");
          expectNear(p.b, v[13], 1e-2, "b");
          // The patch's force in track axes: its x is fx (the contact frame's x is the track's).
          expectNear(p.wrench.force.x, p.fx, 5e4, "wrench.force.x");
          EXPECT_GT(p.wrench.force.z, 0.0);
          EXPECT_EQ(rows[i]->status, "ok");
          EXPECT_EQ(p.status, PatchContactState::STATUS_OK);
        }
      }
    }
  }
  EXPECT_GT(patches, 4 * kTicks - 8);  // nearly every wheel in contact, most ticks compared
  EXPECT_GT(flange, 0) << "the front wheelset never reached its gauge corner";

  // The same ticks over the topics after a reset: one answer per input, the service's answers.
  ASSERT_TRUE(c.reset());
  c.received.clear();
  c.count = 0;
  for (int k = 0; k < kTicks; ++k) c.pub_.publish(tick(k));
  EXPECT_TRUE(spinUntil([&] { return c.count >= static_cast<size_t>(kTicks); }, 30.0));
  ASSERT_EQ(c.count, static_cast<size_t>(kTicks));
  for (int k = 0; k < kTicks; ++k) {
    const auto it = c.received.find(tick(k).header.stamp.toNSec());
    ASSERT_NE(it, c.received.end());
    for (int w = 0; w < 2; ++w) expectSameAnswer(it->second.wheelsets[w], service[k].wheelsets[w]);
  }
}

TEST(WheelsetNode, EachTicksCantIsTaken) {
  // The same two ticks at the states' cants and at cant 0 (nss: the first step rolls nothing):
  // each patch's spin at the second differs by the track frame's turning kappa (sin(c) n_y +
  // (cos(c) - 1) n_z), n = (0, +-sin(delta), cos(delta)) its normal (+ on the right wheel: the
  // contact angle leans toward the track centre).
  WheelsetClient c;
  WheelsetForces canted, level;
  const int k = kTicks - 1;  // the front wheelset on its gauge corner
  ASSERT_TRUE(c.reset());
  ASSERT_TRUE(c.step(tick(k - 1, 7000 * kStep), &canted));
  ASSERT_TRUE(c.step(tick(k, 7000 * kStep), &canted));
  ASSERT_TRUE(c.reset());
  for (int j : {k - 1, k}) {
    WheelsetInput in = tick(j, 7000 * kStep);
    for (WheelsetKinematics& s : in.wheelsets) s.cant = 0.0;
    ASSERT_TRUE(c.step(in, &level));
  }
  int leaning = 0;
  for (int w = 0; w < 2; ++w) {
    const WheelsetKinematics s = state(w, k);
    for (int side = 0; side < 2; ++side) {
      const WheelContactState& a = side ? canted.wheelsets[w].right : canted.wheelsets[w].left;
      const WheelContactState& b = side ? level.wheelsets[w].right : level.wheelsets[w].left;
      ASSERT_EQ(a.status, WheelContactState::STATUS_OK) << a.message;
      ASSERT_EQ(a.patches.size(), b.patches.size());
      for (size_t i = 0; i < a.patches.size(); ++i) {
        const PatchContactState &p = a.patches[i], &q = b.patches[i];
        const double ny = (side ? 1.0 : -1.0) * std::sin(p.contact_angle);
        const double nz = std::cos(p.contact_angle);
        const double dphi = s.curvature * (std::sin(s.cant) * ny + (std::cos(s.cant) - 1.0) * nz);
        EXPECT_NEAR(p.phi - q.phi, dphi, 1e-10) << w << " " << side << " " << p.slot;
        EXPECT_EQ(p.fn, q.fn);  // the geometry and the loads are the rails' plane's
        if (std::abs(dphi) > 1e-4) {
          ++leaning;
          EXPECT_NE(p.mz, q.mz);
        }
      }
    }
  }
  EXPECT_GT(leaning, 0) << "no patch whose normal leans enough to show the cant";
}

TEST(WheelsetNode, RejectedEntriesHoldTheLastAcceptedAnswer) {
  WheelsetClient c;
  ASSERT_TRUE(c.reset());
  WheelsetForces first, f;
  ASSERT_TRUE(c.step(tick(0, 5000 * kStep), &first));
  ASSERT_TRUE(c.step(tick(1, 5000 * kStep), &first));
  ASSERT_EQ(first.wheelsets[0].left.status, WheelContactState::STATUS_OK);

  auto expectHeld = [&](const WheelsetContactState& s, const WheelsetContactState& last) {
    EXPECT_EQ(s.left.status, WheelContactState::STATUS_REJECTED);
    EXPECT_EQ(s.right.status, WheelContactState::STATUS_REJECTED);
    EXPECT_TRUE(s.left.held);
    EXPECT_FALSE(s.left.message.empty());
    EXPECT_EQ(s.dt, 0.0);
    WheelsetContactState expected = last;
    expected.left.status = expected.right.status = WheelContactState::STATUS_REJECTED;
    expected.left.held = expected.right.held = true;
    expectSameAnswer(s, expected);
  };
  // A stamp not after the previous one: both wheelsets held.
  ASSERT_TRUE(c.step(tick(2, 4999 * kStep), &f));
  ASSERT_EQ(f.wheelsets.size(), 2u);
  for (int w = 0; w < 2; ++w) expectHeld(f.wheelsets[w], first.wheelsets[w]);

  // An unknown name, the front wheelset twice, the rear one missing: four answers.
  WheelsetInput in = tick(3, 5000 * kStep);
  in.wheelsets[1].name = "middle";
  in.wheelsets.push_back(in.wheelsets[0]);
  ASSERT_TRUE(c.step(in, &f));
  ASSERT_EQ(f.wheelsets.size(), 4u);
  EXPECT_EQ(f.wheelsets[0].name, "front");
  EXPECT_EQ(f.wheelsets[1].name, "middle");
  EXPECT_EQ(f.wheelsets[3].name, "rear");
  expectHeld(f.wheelsets[0], first.wheelsets[0]);
  expectHeld(f.wheelsets[2], first.wheelsets[0]);
  expectHeld(f.wheelsets[3], first.wheelsets[1]);
  EXPECT_EQ(f.wheelsets[1].left.status, WheelContactState::STATUS_REJECTED);
  EXPECT_FALSE(f.wheelsets[1].left.held);
  EXPECT_TRUE(f.wheelsets[1].left.patches.empty());
  EXPECT_EQ(f.wheelsets[1].header.frame_id, "");

  // A cant beyond 0.2 rad: stepped, both wheels refused as invalid input and held.
  in = tick(4, 5000 * kStep);
  in.wheelsets[0].cant = -0.25;
  ASSERT_TRUE(c.step(in, &f));
  for (const WheelContactState* w : {&f.wheelsets[0].left, &f.wheelsets[0].right}) {
    EXPECT_EQ(w->status, WheelContactState::STATUS_INVALID_INPUT);
    EXPECT_TRUE(w->held);
    EXPECT_NE(w->message.find("cant"), std::string::npos) << w->message;
  }
  {
    WheelsetContactState expected = first.wheelsets[0];
    expected.left.status = expected.right.status = WheelContactState::STATUS_INVALID_INPUT;
    expected.left.held = expected.right.held = true;
    expectSameAnswer(f.wheelsets[0], expected);
  }
  EXPECT_EQ(f.wheelsets[1].left.status, WheelContactState::STATUS_OK);
  EXPECT_FALSE(f.wheelsets[1].left.held);

  // A non-finite value: held; the next tick steps again.
  in = tick(5, 5000 * kStep);
  in.wheelsets[0].yaw = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(c.step(in, &f));
  expectHeld(f.wheelsets[0], first.wheelsets[0]);
  ASSERT_TRUE(c.step(tick(6, 5000 * kStep), &f));
  EXPECT_EQ(f.wheelsets[0].left.status, WheelContactState::STATUS_OK);
  EXPECT_FALSE(f.wheelsets[0].left.held);
  EXPECT_DOUBLE_EQ(f.wheelsets[0].dt, 2e-3);  // from the last stepped stamp, tick 4's
}

TEST(WheelsetNode, DiagnosticsReportEachWheelset) {
  WheelsetClient c;
  WheelsetForces f;
  ASSERT_TRUE(c.reset());
  ASSERT_TRUE(c.step(tick(0, 9000 * kStep), &f));
  std::map<std::string, std::string> seen;
  ros::NodeHandle nh;
  auto sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& s : m->status)
          for (const auto& kv : s.values)
            if (kv.key == "steps") seen[s.name] = kv.value;  // "<node name>: wheelset ..."
      });
  const std::string front = "wheelset " + ns + " front";
  auto reported = [&] {
    for (const auto& [name, steps] : seen)
      if (name.size() >= front.size() &&
          name.compare(name.size() - front.size(), front.size(), front) == 0 && steps != "0")
        return true;
    return false;
  };
  ASSERT_TRUE(spinUntil(reported, 30.0)) << "no diagnostics for " << front;
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rostest_wheelset");
  ros::NodeHandle pnh("~");
  pnh.param<std::string>("ns", ns, ns);
  return RUN_ALL_TESTS();
}
