// Shared by the rostest nodes: a client of one contact_node (topics and services) and contact_cli.
#pragma once

#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../process.hpp"
#include "wheel_rail_contact/ContactState.h"
#include "wheel_rail_contact/Creepage.h"
#include "wheel_rail_contact/NormalLoad.h"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/Step.h"
#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/scenario.hpp"

namespace wrc_test {

using wheel_rail_contact::ContactState;

/// Spins the global queue until pred() or timeout (wall seconds).
template <class Pred>
bool spinUntil(Pred pred, double timeout = 5.0) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    if (pred()) return true;
    ros::WallDuration(0.0001).sleep();
  }
  ros::spinOnce();
  return pred();
}

inline void spinFor(double seconds) {
  spinUntil([] { return false; }, seconds);
}

/// True when every node publishing `topic` (a resolved name) holds an established connection to
/// this node for it, read from the publisher's own XML-RPC getBusInfo. A subscriber counts a
/// publisher (getNumPublishers) as soon as it starts connecting; the publisher adds the link only
/// once the handshake is done, and from then on every message it publishes reaches us. So this,
/// not getNumPublishers, says that nothing published from now on is lost.
inline bool publishersConnectedToUs(const std::string& topic) {
  XmlRpc::XmlRpcValue req, res, state;
  req[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", req, res, state, false)) return false;
  std::vector<std::string> nodes;
  const XmlRpc::XmlRpcValue& publishers = state[0];
  for (int i = 0; i < publishers.size(); ++i)
    if (static_cast<std::string>(publishers[i][0]) == topic)
      for (int j = 0; j < publishers[i][1].size(); ++j)
        nodes.push_back(static_cast<std::string>(publishers[i][1][j]));
  if (nodes.empty()) return false;
  for (const auto& node : nodes) {
    XmlRpc::XmlRpcValue lookup, lookupRes, uri;
    lookup[0] = ros::this_node::getName();
    lookup[1] = node;
    if (!ros::master::execute("lookupNode", lookup, lookupRes, uri, false)) return false;
    std::string host;
    uint32_t port = 0;
    if (!ros::network::splitURI(static_cast<std::string>(uri), host, port)) return false;
    XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
    XmlRpc::XmlRpcValue args, info;
    args[0] = ros::this_node::getName();
    if (!client.execute("getBusInfo", args, info) ||
        info.getType() != XmlRpc::XmlRpcValue::TypeArray || info.size() < 3)
      return false;
    bool linked = false;
    const XmlRpc::XmlRpcValue& links = info[2];
    for (int i = 0; i < links.size() && !linked; ++i)
      linked = links[i].size() > 4 && static_cast<std::string>(links[i][2]) == "o" &&
               static_cast<std::string>(links[i][4]) == topic &&
               static_cast<std::string>(links[i][1]) == ros::this_node::getName();
    if (!linked) return false;
  }
  return true;
}

/// One contact_node seen from outside: publishes inputs, collects both outputs, calls services.
class ContactClient {
 public:
  ContactClient(ros::NodeHandle& nh, const std::string& ns) : ns_(ns) {
    creepPub_ = nh.advertise<wheel_rail_contact::Creepage>(ns + "/creepage", 1000);
    loadPub_ = nh.advertise<wheel_rail_contact::NormalLoad>(ns + "/normal_load", 1000);
    stateSub_ = nh.subscribe(ns + "/contact_state", 10000, &ContactClient::onState, this,
                             ros::TransportHints().tcpNoDelay());
    forceSub_ = nh.subscribe(ns + "/creep_force", 10000, &ContactClient::onForce, this,
                             ros::TransportHints().tcpNoDelay());
    reset_ = nh.serviceClient<wheel_rail_contact::Reset>(ns + "/reset");
    // Persistent: one connection for the whole run, not a new TCP handshake per call (which
    // failed now and then on a loaded 2-core machine after the node had done the step).
    step_ = nh.serviceClient<wheel_rail_contact::Step>(ns + "/step", true);
  }

  /// Waits (to `timeout` wall seconds) until both directions are connected end to end and both
  /// services are up: from then on nothing published on either side is lost.
  bool connect(double timeout = 30.0) {
    // Our publishers count a subscriber once its handshake is done (deterministic); for the
    // node's outputs only the node's side knows (publishersConnectedToUs).
    const bool topics = spinUntil(
        [&] {
          return creepPub_.getNumSubscribers() > 0 && loadPub_.getNumSubscribers() > 0 &&
                 stateSub_.getNumPublishers() > 0 && forceSub_.getNumPublishers() > 0 &&
                 publishersConnectedToUs(stateSub_.getTopic()) &&
                 publishersConnectedToUs(forceSub_.getTopic());
        },
        timeout);
    return topics && reset_.waitForExistence(ros::Duration(timeout)) &&
           step_.waitForExistence(ros::Duration(timeout));
  }

  bool reset() {
    wheel_rail_contact::Reset srv;
    return reset_.call(srv) && srv.response.success;
  }

  /// Publishes a normal load (the node pairs it with the creepage of the same stamp).
  void load(const ros::Time& stamp, double fz) {
    wheel_rail_contact::NormalLoad m;
    m.header.stamp = stamp;
    m.force = fz;
    loadPub_.publish(m);
  }

  /// Publishes one creepage (optional geometry and friction in `m`'s a, b, curvature_x,
  /// curvature_y, mu) without waiting for its output.
  void publishCreepage(const ros::Time& stamp, double xi, double eta, double phi, double V,
                       wheel_rail_contact::Creepage m = {}) {
    m.header.stamp = stamp;
    m.longitudinal = xi;
    m.lateral = eta;
    m.spin = phi;
    m.velocity = V;
    creepPub_.publish(m);
    ++sent;
  }

  /// Publishes one creepage and waits for exactly one message on each output (its load must be
  /// on its way already, or a later one: otherwise it waits the node's load_wait).
  ::testing::AssertionResult creep(const ros::Time& stamp, double xi, double eta, double phi,
                                   double V, ContactState* out = nullptr,
                                   const wheel_rail_contact::Creepage& geometry = {}) {
    const size_t s0 = states.size(), f0 = forces.size();
    publishCreepage(stamp, xi, eta, phi, V, geometry);
    if (!spinUntil([&] { return states.size() > s0 && forces.size() > f0; }, 20.0))
      return ::testing::AssertionFailure() << ns_ << ": no output for the creepage at " << stamp;
    if (states.size() != s0 + 1 || forces.size() != f0 + 1)
      return ::testing::AssertionFailure() << ns_ << ": more than one output per input";
    const ContactState& s = states.back();
    const geometry_msgs::WrenchStamped& w = forces.back();
    if (s.header.stamp != stamp || w.header.stamp != stamp)
      return ::testing::AssertionFailure() << ns_ << ": stamp not copied";
    if (w.wrench.force.x != s.fx || w.wrench.force.y != s.fy || w.wrench.force.z != s.fz ||
        w.wrench.torque.z != s.mz)
      return ::testing::AssertionFailure() << ns_ << ": creep_force differs from contact_state";
    for (double v : {s.fx, s.fy, s.fz, s.mz, s.a, s.b, s.adhesion_fraction, s.dt, s.solver_time})
      if (!std::isfinite(v)) return ::testing::AssertionFailure() << ns_ << ": non-finite output";
    if (out) *out = s;
    return ::testing::AssertionSuccess();
  }

  /// One Step call; `request` may carry the optional geometry and friction.
  bool step(const ros::Time& stamp, double xi, double eta, double phi, double V, double fz,
            wheel_rail_contact::Step::Response* out,
            wheel_rail_contact::Step::Request request = {}) {
    wheel_rail_contact::Step srv;
    srv.request = request;
    srv.request.stamp = stamp;
    srv.request.longitudinal = xi;
    srv.request.lateral = eta;
    srv.request.spin = phi;
    srv.request.velocity = V;
    srv.request.normal_force = fz;
    if (!step_.call(srv)) return false;
    ++sent;
    *out = srv.response;
    return true;
  }

  /// Waits until both outputs have as many messages as creepages and step calls were sent (an
  /// extra message, already received, fails too).
  ::testing::AssertionResult oneOutputPerInput(double timeout = 20.0) {
    spinUntil([&] { return states.size() >= sent && forces.size() >= sent; }, timeout);
    if (states.size() == sent && forces.size() == sent) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << ns_ << ": " << sent << " inputs, " << states.size()
                                         << " contact_state, " << forces.size() << " creep_force";
  }

  std::vector<ContactState> states;
  std::vector<geometry_msgs::WrenchStamped> forces;
  size_t sent = 0;  ///< creepage messages and step calls

 private:
  void onState(const ContactState::ConstPtr& m) { states.push_back(*m); }
  void onForce(const geometry_msgs::WrenchStamped::ConstPtr& m) { forces.push_back(*m); }

  std::string ns_;
  ros::Publisher creepPub_, loadPub_;
  ros::Subscriber stateSub_, forceSub_;
  ros::ServiceClient reset_, step_;
};

struct Row {
  double t, fx, fy, mz, fz, a, b, adhesion;
  std::string status;
};

/// Parses contact_cli run's CSV output.
inline std::vector<Row> parseCliOutput(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (header) {
      header = line.rfind("t,fx", 0) != 0;
      continue;
    }
    Row r;
    char status[64] = {0};
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%63[^\n]", &r.t, &r.fx, &r.fy,
                    &r.mz, &r.fz, &r.a, &r.b, &r.adhesion, status) == 9) {
      r.status = status;
      rows.push_back(r);
    }
  }
  return rows;
}

/// contact_cli's status text for a ContactState status.
inline std::string statusText(int status) {
  static const char* names[] = {"ok", "no load", "standstill", "rejected input"};
  return status >= 0 && status < 4 ? names[status] : "?";
}

/// Every output field of two steps, bit for bit.
inline bool sameBits(const ContactState& a, const ContactState& b) {
  return a.header.stamp == b.header.stamp && a.fx == b.fx && a.fy == b.fy && a.fz == b.fz &&
         a.mz == b.mz && a.a == b.a && a.b == b.b && a.adhesion_fraction == b.adhesion_fraction &&
         a.dt == b.dt && a.status == b.status && a.load_match == b.load_match &&
         a.load_stamp == b.load_stamp && a.held == b.held && a.message == b.message;
}

/// A parameter of `node` as the text setParameter() parses; false if unset or not a scalar.
inline bool parameterTextOf(const std::string& node, const std::string& name, std::string* text) {
  XmlRpc::XmlRpcValue v;
  if (!ros::param::get(node + "/" + name, v)) return false;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    *text = static_cast<std::string>(v);
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    *text = std::to_string(static_cast<int>(v));
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", static_cast<double>(v));
    *text = buf;
  } else {
    return false;
  }
  return true;
}

/// The contact_node's shared parameters as contact_cli options (--name value ...), read back from
/// the parameter server, so contact_cli runs exactly the node's configuration.
inline std::string cliOptionsOf(const std::string& nodeName) {
  std::string opts, text;
  for (const auto& d : wheel_rail_contact::parameterDocs())
    if (parameterTextOf(nodeName, d.name, &text) && !text.empty())
      opts += " --" + d.name + " '" + text + "'";
  return opts;
}

/// The largest magnitude of one field over rows (the scale of a relative tolerance).
inline double largest(const std::vector<Row>& rows, double Row::*field) {
  double s = 1e-300;
  for (const auto& r : rows) s = std::max(s, std::fabs(r.*field));
  return s;
}

/// The scene of a node-vs-CLI test: its rows, and `contact_cli run` on them with the config file
/// and every shared parameter the node really runs with (read back from the parameter server).
/// False, with a failure added, if contact_cli fails.
inline bool sceneAndCliReference(const std::string& ns, const std::string& scene,
                                 const std::string& config,
                                 std::vector<wheel_rail_contact::ScenarioRow>* rows,
                                 std::vector<Row>* reference) {
  std::ifstream in(scene);
  *rows = wheel_rail_contact::readScenario(in, scene);
  std::string out;
  const std::string command = std::string(WRC_CONTACT_CLI) + " run --scenario '" + scene +
                              "' --config '" + config + "'" + cliOptionsOf(ns + "/contact_node");
  if (run(command, &out) != 0) {
    ADD_FAILURE() << command << "\n" << out;
    return false;
  }
  *reference = parseCliOutput(out);
  return true;
}

/// A scene-driven rostest node's inputs: its private parameters ns (the contact's namespace), scene
/// (scenario CSV) and config (the node's YAML), the scene's rows and contact_cli's output for them
/// (sceneAndCliReference). Stamps are offset + t [s].
struct SceneUnderTest {
  explicit SceneUnderTest(double stampOffset) : offset(stampOffset) {}
  std::string ns, scene, config;
  std::vector<wheel_rail_contact::ScenarioRow> rows;
  std::vector<Row> reference;
  double offset;
  ros::Time stampOf(double t) const { return ros::Time(offset + t); }
};

/// main() of a scene-driven rostest node `name`: fills `sut`, then runs every test; 1 if
/// contact_cli fails.
inline int runSceneTests(int argc, char** argv, const char* name, SceneUnderTest* sut) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::NodeHandle pnh("~");
  pnh.getParam("ns", sut->ns);
  pnh.getParam("scene", sut->scene);
  pnh.getParam("config", sut->config);
  if (!sceneAndCliReference(sut->ns, sut->scene, sut->config, &sut->rows, &sut->reference))
    return 1;
  return RUN_ALL_TESTS();
}

/// A node's shared parameters, read back from the parameter server.
inline wheel_rail_contact::ContactParameters parametersOf(const std::string& node) {
  wheel_rail_contact::ContactParameters p;
  std::string text;
  for (const auto& d : wheel_rail_contact::parameterDocs())
    if (parameterTextOf(node, d.name, &text)) wheel_rail_contact::setParameter(&p, d.name, text);
  return p;
}

/// The node `executable` started as node `name` after its private parameters `params` are set on
/// the parameter server: exit code 1 (the controlled failure; a node that keeps running, a valid
/// configuration, ends with SIGINT's after 20 s) and a ROS_FATAL "invalid parameter <text>".
inline void expectFatalParameters(
    const std::string& executable, const std::string& name,
    const std::vector<std::pair<std::string, XmlRpc::XmlRpcValue>>& params,
    const std::string& text) {
  for (const auto& p : params) ros::param::set("/" + name + "/" + p.first, p.second);
  std::string out;
  const int code = run(
      std::string("timeout --preserve-status -s INT 20 ") + executable + " __name:=" + name, &out);
  EXPECT_EQ(code, 1) << text << "\n" << out;
  EXPECT_NE(out.find("FATAL"), std::string::npos) << out;
  EXPECT_NE(out.find("invalid parameter " + text), std::string::npos) << text << "\n" << out;
}

}  // namespace wrc_test
