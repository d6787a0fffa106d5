// rostest: vehicle_node (or its nodelet) against separate contacts. Every output of a tick, through
// the vehicle_input topic and the vehicle_step service, equals that contact's own contact_node (its
// step service) for the same inputs, to 1e-9; per-tick geometry and friction equal a ContactStepper
// given the same a, b, mu; unknown, missing and repeated names give rejected entries holding the
// last accepted forces; reset clears every contact.
#include <diagnostic_msgs/DiagnosticArray.h>

#include <algorithm>
#include <map>
#include <set>

#include "../../examples/wait_for_link.hpp"
#include "../../src/ros/ros_conversions.hpp"
#include "../../src/ros/vehicle_stepper.hpp"
#include "rostest_helpers.hpp"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/VehicleState.h"
#include "wheel_rail_contact/VehicleStep.h"
#include "wheel_rail_contact/geometry/hertz.hpp"

using namespace wrc_test;
using wheel_rail_contact::ContactInput;
using wheel_rail_contact::VehicleInput;
using wheel_rail_contact::VehicleState;

namespace {

std::string vehicleNs = "vehicle", vehicleNode = "vehicle/vehicle_node", singleNs = "single";
std::vector<std::string> names;  // the vehicle node's ~contacts

class VehicleClient {
 public:
  explicit VehicleClient(ros::NodeHandle& nh) {
    input_ = nh.advertise<VehicleInput>(vehicleNs + "/vehicle_input", 1000);
    stateSub_ = nh.subscribe(vehicleNs + "/vehicle_state", 10000, &VehicleClient::onState, this,
                             ros::TransportHints().tcpNoDelay());
    reset_ = nh.serviceClient<wheel_rail_contact::Reset>(vehicleNs + "/reset");
  }

  bool connect(ros::NodeHandle& nh) {
    if (!ros::service::waitForService(vehicleNs + "/vehicle_step", ros::Duration(30.0)))
      return false;
    // Persistent, made once the service is there: one connection for the whole run.
    step_ = nh.serviceClient<wheel_rail_contact::VehicleStep>(vehicleNs + "/vehicle_step", true);
    return spinUntil([&] { return input_.getNumSubscribers() > 0; }, 30.0) &&
           wheel_rail_contact_examples::waitForLink(vehicleNs + "/vehicle_state", 30.0) &&
           reset_.waitForExistence(ros::Duration(30.0));
  }

  bool reset() {
    wheel_rail_contact::Reset srv;
    return reset_.call(srv) && srv.response.success;
  }

  /// One tick through the topic: waits for its VehicleState (matched by stamp).
  ::testing::AssertionResult viaTopic(const VehicleInput& in, VehicleState* out) {
    input_.publish(in);
    return take(in.header.stamp, out);
  }

  /// One tick through the service; its answer is also published, and taken here.
  ::testing::AssertionResult viaService(const VehicleInput& in, VehicleState* out) {
    wheel_rail_contact::VehicleStep srv;
    srv.request.input = in;
    if (!step_.call(srv))
      return ::testing::AssertionFailure() << "vehicle_step call failed (valid " << step_.isValid()
                                           << ", exists " << step_.exists() << ")";
    *out = srv.response.state;
    VehicleState published;
    auto r = take(in.header.stamp, &published);
    if (!r) return r;
    bool same = published.names == out->names && published.contacts.size() == out->contacts.size();
    for (size_t j = 0; same && j < out->contacts.size(); ++j)
      same = published.contacts[j].fx == out->contacts[j].fx &&
             published.contacts[j].fy == out->contacts[j].fy &&
             published.contacts[j].status == out->contacts[j].status;
    if (!same) return ::testing::AssertionFailure() << "vehicle_state differs from the answer";
    return r;
  }

  /// No vehicle_state beyond the one per input taken so far.
  ::testing::AssertionResult noneLeft() {
    ros::spinOnce();
    if (states.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << states.size() << " vehicle_state messages too many";
  }

  std::vector<VehicleState> states;  ///< received and not yet taken

 private:
  /// Waits for the vehicle_state with this stamp and removes it from `states`.
  ::testing::AssertionResult take(const ros::Time& stamp, VehicleState* out) {
    auto it = states.end();
    const bool got = spinUntil(
        [&] {
          it = std::find_if(states.begin(), states.end(),
                            [&](const VehicleState& s) { return s.header.stamp == stamp; });
          return it != states.end();
        },
        10.0);
    if (!got) return ::testing::AssertionFailure() << "no vehicle_state for " << stamp;
    *out = *it;
    states.erase(it);
    return ::testing::AssertionSuccess();
  }

  void onState(const VehicleState::ConstPtr& m) { states.push_back(*m); }
  ros::Publisher input_;
  ros::Subscriber stateSub_;
  ros::ServiceClient step_, reset_;
};

std::unique_ptr<VehicleClient> vehicle;
std::map<std::string, ros::ServiceClient> singleStep, singleReset;

ContactInput inputOf(const std::string& name, int k, size_t i) {
  ContactInput c;
  c.name = name;
  c.longitudinal = 1.5e-3 * std::sin(0.07 * k + i);
  c.lateral = 6e-4 * std::cos(0.05 * k + 2.0 * i);
  c.spin = 0.3 * std::sin(0.03 * k + i);
  c.velocity = 20.0 + 2.0 * std::sin(0.01 * k);
  c.normal_force = 7e4 + 8e3 * std::sin(0.04 * k + i);
  return c;
}

/// A tick with every contact, in an order that changes from tick to tick.
VehicleInput tickOf(int k, double t0) {
  VehicleInput in;
  in.header.stamp = ros::Time(t0 + 1e-3 * k);
  in.header.frame_id = "vehicle_body";
  for (size_t i = 0; i < names.size(); ++i) in.contacts.push_back(inputOf(names[i], k, i));
  std::rotate(in.contacts.begin(), in.contacts.begin() + k % names.size(), in.contacts.end());
  if (k % 3 == 0) std::reverse(in.contacts.begin(), in.contacts.end());
  return in;
}

::testing::AssertionResult near(const char* what, double got, double expected) {
  if (std::fabs(got - expected) <= 1e-9 * std::fabs(expected) + 1e-12)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << " " << got << " != " << expected;
}

/// One vehicle entry against a contact_node's Step response (or a stepper's StepResult).
template <class Ref>
void expectEqualState(const ContactState& s, const Ref& r, const std::string& where) {
  EXPECT_TRUE(near("fx", s.fx, r.fx)) << where;
  EXPECT_TRUE(near("fy", s.fy, r.fy)) << where;
  EXPECT_TRUE(near("fz", s.fz, r.fz)) << where;
  EXPECT_TRUE(near("mz", s.mz, r.mz)) << where;
  EXPECT_TRUE(near("a", s.a, r.a)) << where;
  EXPECT_TRUE(near("b", s.b, r.b)) << where;
  EXPECT_TRUE(near("adhesion", s.adhesion_fraction, r.adhesion_fraction)) << where;
  EXPECT_TRUE(near("dt", s.dt, r.dt)) << where;
  EXPECT_EQ(s.status, r.status) << where << ": " << s.message;
  EXPECT_EQ(s.message, r.message) << where;
}

/// The vehicle node's configuration of one contact, read back from the parameter server.
wheel_rail_contact::ContactParameters contactParametersOf(const std::string& name) {
  wheel_rail_contact::ContactParameters p;
  for (const auto& d : wheel_rail_contact::parameterDocs()) {
    XmlRpc::XmlRpcValue v;
    if (!ros::param::get(vehicleNode + "/" + name + "/" + d.name, v) &&
        !ros::param::get(vehicleNode + "/" + d.name, v))
      continue;
    wheel_rail_contact::setParameter(&p, d.name, wheel_rail_contact::parameterText(d.name, v));
  }
  return p;
}

void resetAll() {
  ASSERT_TRUE(vehicle->reset());
  for (auto& r : singleReset) {
    wheel_rail_contact::Reset srv;
    ASSERT_TRUE(r.second.call(srv)) << r.first;
  }
}

}  // namespace

TEST(Vehicle, EveryTickEqualsTheSingleContactNodes) {
  resetAll();
  for (int k = 0; k < 240; ++k) {
    VehicleInput in = tickOf(k, 10.0);
    if (k == 50) in.contacts[1].normal_force = 0.0;  // a wheel lifts: no load
    if (k == 90) in.contacts[2].velocity = 0.0;      // standstill
    VehicleState out;
    const bool topic = (k / 20) % 2 == 0;  // blocks of ticks through each path, one time line
    ASSERT_TRUE(topic ? vehicle->viaTopic(in, &out) : vehicle->viaService(in, &out)) << k;
    ASSERT_EQ(out.contacts.size(), in.contacts.size()) << k;
    ASSERT_EQ(out.names.size(), in.contacts.size()) << k;
    EXPECT_EQ(out.header.stamp, in.header.stamp);
    EXPECT_EQ(out.header.frame_id, "vehicle_body");
    for (size_t j = 0; j < in.contacts.size(); ++j) {
      const ContactInput& c = in.contacts[j];
      ASSERT_EQ(out.names[j], c.name) << k;  // the input's order
      wheel_rail_contact::Step srv;
      srv.request.stamp = in.header.stamp;
      srv.request.longitudinal = c.longitudinal;
      srv.request.lateral = c.lateral;
      srv.request.spin = c.spin;
      srv.request.velocity = c.velocity;
      srv.request.normal_force = c.normal_force;
      ASSERT_TRUE(singleStep[c.name].call(srv)) << c.name;
      const std::string where = "tick " + std::to_string(k) + " " + c.name;
      expectEqualState(out.contacts[j], srv.response, where);
      EXPECT_EQ(out.contacts[j].model, srv.response.model) << where;
      EXPECT_EQ(out.contacts[j].header.stamp, in.header.stamp) << where;
      if (k == 50 && j == 1) {
        EXPECT_EQ(srv.response.status, ContactState::STATUS_NO_LOAD);
      }
      if (k == 90 && j == 2) {
        EXPECT_EQ(srv.response.status, ContactState::STATUS_STANDSTILL);
      }
    }
  }
  EXPECT_TRUE(vehicle->noneLeft());
}

TEST(Vehicle, FramesAreUniquePerContactAndOverridable) {
  resetAll();
  VehicleState out;
  ASSERT_TRUE(vehicle->viaService(tickOf(0, 20.0), &out));
  std::set<std::string> frames;
  for (size_t j = 0; j < out.contacts.size(); ++j) {
    const std::string& f = out.contacts[j].header.frame_id;
    frames.insert(f);
    std::string override;
    if (ros::param::get(vehicleNode + "/" + out.names[j] + "/frame_id", override))
      EXPECT_EQ(f, override);
    else
      EXPECT_EQ(f, vehicleNs + "_" + out.names[j]);  // the namespace as a prefix
  }
  EXPECT_EQ(frames.size(), names.size());
  EXPECT_TRUE(vehicle->noneLeft());
}

TEST(Vehicle, PerTickGeometryAndFrictionEqualAStepperGivenTheSame) {
  resetAll();
  std::map<std::string, std::unique_ptr<wheel_rail_contact::ContactStepper>> steppers;
  std::map<std::string, wheel_rail_contact::ContactParameters> params;
  for (const auto& n : names) {
    params[n] = contactParametersOf(n);
    steppers[n] = std::make_unique<wheel_rail_contact::ContactStepper>(
        wheel_rail_contact::makeContactModel(params[n]), wheel_rail_contact::StepperOptions{});
  }
  for (int k = 0; k < 60; ++k) {
    VehicleInput in = tickOf(k, 30.0);
    for (size_t j = 0; j < in.contacts.size(); ++j) {
      ContactInput& c = in.contacts[j];
      if (j % 2 == 0) {  // semi-axes and friction changing every tick
        c.a = 6e-3 * (1.0 + 0.2 * std::sin(0.1 * k));
        c.b = 4e-3 * (1.0 + 0.3 * std::cos(0.1 * k));
        c.mu = 0.3 + 0.1 * std::sin(0.05 * k);
      } else {  // principal curvatures: Hertz gives a, b from this tick's load
        c.curvature_x = 4.0 + std::sin(0.1 * k);
        c.curvature_y = 6.0 + 2.0 * std::cos(0.1 * k);
      }
    }
    VehicleState out;
    ASSERT_TRUE(k % 2 ? vehicle->viaTopic(in, &out) : vehicle->viaService(in, &out));
    ASSERT_EQ(out.contacts.size(), in.contacts.size());
    for (size_t j = 0; j < in.contacts.size(); ++j) {
      const ContactInput& c = in.contacts[j];
      wheel_rail_contact::StepInput s;
      s.V = c.velocity;
      s.xi = c.longitudinal;
      s.eta = c.lateral;
      s.phi = c.spin;
      s.fz = c.normal_force;
      s.a = c.a;
      s.b = c.b;
      s.mu = c.mu;
      if (c.curvature_x > 0.0) {
        const auto h = wheel_rail_contact::hertzFromCurvatures(
            c.normal_force, c.curvature_x, c.curvature_y, params[c.name].G, params[c.name].nu);
        s.a = h.a;
        s.b = h.b;
      }
      const auto r =
          steppers[c.name]->stepWithLoad(static_cast<int64_t>(in.header.stamp.toNSec()), s);
      ContactState ref;
      ref.fx = r.out.fx, ref.fy = r.out.fy, ref.fz = r.out.fz, ref.mz = r.out.mz;
      ref.a = r.out.a, ref.b = r.out.b, ref.adhesion_fraction = r.out.adhesionFraction;
      ref.dt = r.dt, ref.status = wheel_rail_contact::contactStateStatus(r.out.status);
      ref.message = r.message;
      expectEqualState(out.contacts[j], ref, "tick " + std::to_string(k) + " " + c.name);
    }
  }
  EXPECT_TRUE(vehicle->noneLeft());
}

TEST(Vehicle, UnknownMissingAndRepeatedNamesAreRejectedAndHoldTheirForces) {
  resetAll();
  ASSERT_GE(names.size(), 3u);
  VehicleState first;
  ASSERT_TRUE(vehicle->viaService(tickOf(0, 40.0), &first));
  std::map<std::string, ContactState> accepted;
  for (size_t j = 0; j < first.names.size(); ++j) {
    ASSERT_EQ(first.contacts[j].status, ContactState::STATUS_OK) << first.contacts[j].message;
    accepted[first.names[j]] = first.contacts[j];
  }
  for (int path = 0; path < 2; ++path) {
    VehicleInput full = tickOf(1 + path, 40.0), in;
    in.header = full.header;
    // names[0] twice, an unknown name, names[1] once; names[2..] missing.
    ContactInput unknown = full.contacts[0];
    unknown.name = "no_such_wheel";
    in.contacts = {inputOf(names[0], 1, 0), unknown, inputOf(names[1], 1, 1),
                   inputOf(names[0], 1, 0)};
    VehicleState out;
    ASSERT_TRUE(path ? vehicle->viaTopic(in, &out) : vehicle->viaService(in, &out));
    ASSERT_EQ(out.contacts.size(), 4 + names.size() - 2);
    std::vector<std::string> expectedNames = {names[0], "no_such_wheel", names[1], names[0]};
    for (size_t i = 2; i < names.size(); ++i) expectedNames.push_back(names[i]);
    EXPECT_EQ(out.names, expectedNames);
    for (size_t j = 0; j < out.contacts.size(); ++j) {
      const ContactState& s = out.contacts[j];
      if (j == 2) {
        EXPECT_EQ(s.status, ContactState::STATUS_OK) << s.message;
        accepted[names[1]] = s;
        continue;
      }
      EXPECT_EQ(s.status, ContactState::STATUS_REJECTED) << j;
      if (j == 1) {
        EXPECT_NE(s.message.find("unknown contact 'no_such_wheel'"), std::string::npos);
        EXPECT_EQ(s.fx, 0.0);
        EXPECT_EQ(s.header.frame_id, "");
        continue;
      }
      EXPECT_NE(s.message.find(j < 4 ? "appears 2 times" : "missing from the input"),
                std::string::npos)
          << s.message;
      // The last accepted forces of that contact, not zero.
      const ContactState& h = accepted[out.names[j]];
      EXPECT_EQ(s.fx, h.fx) << out.names[j];
      EXPECT_EQ(s.fy, h.fy) << out.names[j];
      EXPECT_EQ(s.fz, h.fz) << out.names[j];
      EXPECT_EQ(s.mz, h.mz) << out.names[j];
      EXPECT_NE(s.fz, 0.0);
    }
  }
  EXPECT_TRUE(vehicle->noneLeft());
}

TEST(Vehicle, ResetClearsEveryContact) {
  resetAll();
  std::vector<VehicleState> first;
  for (int k = 0; k < 10; ++k) {
    VehicleState s;
    ASSERT_TRUE(vehicle->viaService(tickOf(k, 50.0), &s));
    first.push_back(s);
  }
  ASSERT_TRUE(vehicle->reset());
  for (int k = 0; k < 10; ++k) {  // the same stamps again: a fresh start, the same forces
    VehicleState s;
    ASSERT_TRUE(k % 2 ? vehicle->viaTopic(tickOf(k, 50.0), &s)
                      : vehicle->viaService(tickOf(k, 50.0), &s));
    ASSERT_EQ(s.contacts.size(), first[k].contacts.size());
    for (size_t j = 0; j < s.contacts.size(); ++j) {
      EXPECT_EQ(s.contacts[j].status, ContactState::STATUS_OK) << s.contacts[j].message;
      EXPECT_EQ(s.contacts[j].fx, first[k].contacts[j].fx) << k << " " << j;
      EXPECT_EQ(s.contacts[j].fy, first[k].contacts[j].fy) << k << " " << j;
      EXPECT_EQ(s.contacts[j].mz, first[k].contacts[j].mz) << k << " " << j;
      if (k == 0) {
        EXPECT_EQ(s.contacts[j].dt, 0.0);
      }
    }
  }
  EXPECT_TRUE(vehicle->noneLeft());
}

TEST(Vehicle, DiagnosticsReportTheVehicleAndEveryContact) {
  resetAll();
  VehicleInput in = tickOf(0, 60.0);
  // names[0] missing, for the first time in this run (the other tests only repeat it).
  const std::string missing = names.front();
  in.contacts.erase(std::find_if(in.contacts.begin(), in.contacts.end(),
                                 [&](const ContactInput& c) { return c.name == missing; }));
  VehicleState out;
  ASSERT_TRUE(vehicle->viaService(in, &out));
  ASSERT_TRUE(vehicle->noneLeft());
  ros::NodeHandle nh;
  std::map<std::string, std::map<std::string, std::string>> seen;  // status name -> key -> value
  auto sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& s : m->status)
          for (const auto& kv : s.values) seen[s.name][kv.key] = kv.value;
      });
  const std::string prefix = "/" + vehicleNs;
  auto contactStatus = [&](const std::string& n) {
    for (const auto& s : seen)
      if (s.first.find("contact " + prefix + " " + n) != std::string::npos) return &s.second;
    return static_cast<const std::map<std::string, std::string>*>(nullptr);
  };
  // The node reports every diagnostic_period (1 s): wait for a report that includes this tick.
  ASSERT_TRUE(spinUntil(
      [&] {
        const auto* m = contactStatus(missing);
        return m && m->count("rejected: missing from the input") &&
               std::stoul(m->at("rejected: missing from the input")) >= 1;
      },
      20.0))
      << "no diagnostics counting the missing contact " << missing;
  for (const auto& n : names) {
    const auto* m = contactStatus(n);
    ASSERT_TRUE(m) << n;
    EXPECT_EQ(m->count("model"), 1u) << n;
    EXPECT_EQ(m->count("rejected, forces held"), 1u) << n;
  }
  bool vehicleStatus = false;
  for (const auto& s : seen)
    if (s.first.find("vehicle " + prefix) != std::string::npos)
      vehicleStatus = s.second.count("ticks") && std::stoul(s.second.at("ticks")) >= 1;
  EXPECT_TRUE(vehicleStatus);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "vehicle_test");
  ros::NodeHandle nh, pnh("~");
  pnh.getParam("vehicle_ns", vehicleNs);
  pnh.getParam("vehicle_node", vehicleNode);
  pnh.getParam("single_ns", singleNs);
  if (!ros::param::get(vehicleNode + "/contacts", names) || names.empty()) {
    ADD_FAILURE() << vehicleNode << "/contacts not set";
    return 1;
  }
  vehicle = std::make_unique<VehicleClient>(nh);
  if (!vehicle->connect(nh)) {
    ADD_FAILURE() << "vehicle node not connected";
    return 1;
  }
  for (const auto& n : names) {
    const std::string ns = singleNs + "/" + n;
    if (!ros::service::waitForService(ns + "/step", ros::Duration(30.0)) ||
        !ros::service::waitForService(ns + "/reset", ros::Duration(30.0))) {
      ADD_FAILURE() << ns << " not available";
      return 1;
    }
    singleStep[n] = nh.serviceClient<wheel_rail_contact::Step>(ns + "/step", true);
    singleReset[n] = nh.serviceClient<wheel_rail_contact::Reset>(ns + "/reset");
  }
  const int result = RUN_ALL_TESTS();
  vehicle.reset();
  return result;
}
