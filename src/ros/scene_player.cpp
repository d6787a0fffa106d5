// scene_player: stands in for a vehicle simulator. Replays a scenario CSV (t,V,xi,eta,phi,fz, the
// format contact_cli run reads) on the relative topics normal_load and creepage, one row per step,
// stamps = stamp_offset + t, paced in wall time by time_scale. For each row the load goes first,
// load_lead seconds before the creepage when it changed, so the node steps with that row's load.
// Private parameters: scene (path, required), time_scale (scene s per wall s, default 1),
// start_delay (wall s after the node subscribed, default 1), subscribers (wait for this many
// creepage subscribers, default 1), stamp_offset (s; < 0 = ros::Time::now() at start, the default),
// load_lead (wall s, default 0.002), wait_for (a list of topics, relative, that must each have a
// subscriber before the scene starts, e.g. [contact_state] so a recorder sees the first step).
#include <ros/ros.h>

#include <ros/master.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "wheel_rail_contact/Creepage.h"
#include "wheel_rail_contact/NormalLoad.h"
#include "wheel_rail_contact/scenario.hpp"

namespace {

/// True if the master lists a subscriber of `topic` (a resolved name).
bool hasSubscriber(const std::string& topic) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", request, response, payload, false)) return false;
  const XmlRpc::XmlRpcValue& subscribers = payload[1];
  for (int i = 0; i < subscribers.size(); ++i)
    if (static_cast<std::string>(subscribers[i][0]) == topic) return subscribers[i][1].size() > 0;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "scene_player");
  ros::NodeHandle nh, pnh("~");
  std::string scene;
  double timeScale = 1.0, startDelay = 1.0, stampOffset = -1.0, loadLead = 0.002;
  int subscribers = 1;
  pnh.param("time_scale", timeScale, timeScale);
  pnh.param("start_delay", startDelay, startDelay);
  pnh.param("stamp_offset", stampOffset, stampOffset);
  pnh.param("load_lead", loadLead, loadLead);
  pnh.param("subscribers", subscribers, subscribers);
  std::vector<std::string> waitFor;
  pnh.param("wait_for", waitFor, waitFor);
  if (!pnh.getParam("scene", scene)) {
    ROS_FATAL("scene_player: scene: parameter ~scene (a scenario CSV) is required");
    return 1;
  }
  if (!(timeScale > 0.0)) {
    ROS_FATAL("scene_player: time_scale: must be > 0");
    return 1;
  }
  std::vector<wheel_rail_contact::ScenarioRow> rows;
  try {
    std::ifstream in(scene);
    if (!in) throw std::runtime_error("scene: cannot open '" + scene + "'");
    rows = wheel_rail_contact::readScenario(in, scene);
  } catch (const std::exception& e) {
    ROS_FATAL("scene_player: %s", e.what());
    return 1;
  }
  ros::Publisher loadPub = nh.advertise<wheel_rail_contact::NormalLoad>("normal_load", 1000);
  ros::Publisher creepPub = nh.advertise<wheel_rail_contact::Creepage>("creepage", 1000);

  while (ros::ok() && (static_cast<int>(creepPub.getNumSubscribers()) < subscribers ||
                       static_cast<int>(loadPub.getNumSubscribers()) < subscribers))
    ros::WallDuration(0.01).sleep();
  for (const auto& topic : waitFor)
    while (ros::ok() && !hasSubscriber(nh.resolveName(topic))) ros::WallDuration(0.05).sleep();
  ros::WallDuration(startDelay).sleep();
  if (!ros::ok()) return 0;

  const ros::Time base = stampOffset >= 0.0 ? ros::Time(stampOffset) : ros::Time::now();
  const ros::WallTime start = ros::WallTime::now();
  ROS_INFO("scene_player %s: %zu rows of %s at %gx", nh.getNamespace().c_str(), rows.size(),
           scene.c_str(), timeScale);
  double lastLoad = std::nan("");
  for (const auto& r : rows) {
    const ros::WallTime due = start + ros::WallDuration((r.t - rows.front().t) / timeScale);
    const ros::WallDuration wait = due - ros::WallTime::now();
    if (wait > ros::WallDuration(0)) wait.sleep();
    if (!ros::ok()) return 0;
    const ros::Time stamp = base + ros::Duration(r.t);
    wheel_rail_contact::NormalLoad load;
    load.header.stamp = stamp;
    load.force = r.fz;
    loadPub.publish(load);
    if (loadLead > 0.0 && r.fz != lastLoad) ros::WallDuration(loadLead).sleep();
    lastLoad = r.fz;
    wheel_rail_contact::Creepage c;
    c.header.stamp = stamp;
    c.longitudinal = r.xi;
    c.lateral = r.eta;
    c.spin = r.phi;
    c.velocity = r.V;
    creepPub.publish(c);
  }
  ROS_INFO("scene_player %s: done, %zu rows published", nh.getNamespace().c_str(), rows.size());
  ros::WallDuration(0.5).sleep();  // let the last messages leave
  return 0;
}
