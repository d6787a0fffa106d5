// step_client: a simulator's side of wheel_rail_contact, in C++.
//   1. one contact (contact_node) through its `step` service: inputs in, forces back in the reply;
//   2. the same contact through its topics: normal_load and creepage out, contact_state back;
//   3. a whole vehicle (vehicle_node) through `vehicle_step`, then through vehicle_input/_state.
// Every step prints: path contact k stamp xi eta phi V fz fx fy mz status.
//   rosrun wheel_rail_contact step_client _contact:=/contact _vehicle:=/vehicle _steps:=5
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "wait_for_link.hpp"
#include "wheel_rail_contact/ContactState.h"
#include "wheel_rail_contact/Creepage.h"
#include "wheel_rail_contact/NormalLoad.h"
#include "wheel_rail_contact/Step.h"
#include "wheel_rail_contact/VehicleState.h"
#include "wheel_rail_contact/VehicleStep.h"

namespace wrc = wheel_rail_contact;

// A simulator's kinematics would give these; here: a slow sway of one wheelset at 20 m/s. The
// single contact carries a steady load; the vehicle's wheels trade load between left and right.
const double kV = 20.0, kDt = 1e-3, kFz = 8e4;
double xiAt(int k, int wheel) {
  return 1e-3 * std::sin(0.05 * k) * (wheel % 2 ? -1.0 : 1.0);
}
double etaAt(int k) {
  return 5e-4 * std::cos(0.05 * k);
}
double fzAt(int k, int wheel) {
  return kFz + 2e3 * std::sin(0.02 * k) * (wheel % 2 ? -1.0 : 1.0);
}

void print(const char* path, const std::string& name, int k, const ros::Time& t, double xi,
           double eta, double fz, double fx, double fy, double mz, int status) {
  std::printf("%s %s %d %.9f %.17g %.17g 0 %g %.17g %.17g %.17g %.17g %d\n", path, name.c_str(), k,
              t.toSec(), xi, eta, kV, fz, fx, fy, mz, status);
}

/// Waits for the answer with this stamp (one contact_state or vehicle_state per input).
template <class Msg>
bool waitFor(const Msg& latest, const ros::Time& stamp) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (ros::ok() && latest.header.stamp != stamp && ros::WallTime::now() < end)
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
  return latest.header.stamp == stamp;
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "step_client");
  ros::NodeHandle nh, pnh("~");
  const std::string contact = pnh.param<std::string>("contact", "contact");
  const std::string vehicle = pnh.param<std::string>("vehicle", "vehicle");
  const int steps = pnh.param("steps", 5);
  std::vector<std::string> wheels = {"left", "right"};
  pnh.getParam("contacts", wheels);  // names of the vehicle node's contacts
  int k = 0;                         // one time line per contact: stamps keep increasing
  auto stampOf = [](int step) { return ros::Time(100.0 + step * kDt); };

  // 1. The step service: one persistent connection (made once the service exists), a call a step.
  if (!ros::service::waitForService(contact + "/step", ros::Duration(30.0))) return 1;
  auto step = nh.serviceClient<wrc::Step>(contact + "/step", true);
  for (int end = k + steps; k < end; ++k) {
    wrc::Step s;
    s.request.stamp = stampOf(k);
    s.request.velocity = kV;
    s.request.longitudinal = xiAt(k, 0);
    s.request.lateral = etaAt(k);
    s.request.normal_force = kFz;
    if (!step.call(s)) return 1;
    print("step", contact, k, s.request.stamp, xiAt(k, 0), etaAt(k), kFz, s.response.fx,
          s.response.fy, s.response.mz, s.response.status);
  }

  // 2. The topics: the load and the creepage of a step carry the same stamp.
  wrc::ContactState state;
  auto creepage = nh.advertise<wrc::Creepage>(contact + "/creepage", 10);
  auto load = nh.advertise<wrc::NormalLoad>(contact + "/normal_load", 10);
  auto stateSub = nh.subscribe<wrc::ContactState>(
      contact + "/contact_state", 10, [&](const wrc::ContactState::ConstPtr& m) { state = *m; });
  while (ros::ok() && (creepage.getNumSubscribers() == 0 || load.getNumSubscribers() == 0))
    ros::WallDuration(0.01).sleep();
  if (!wheel_rail_contact_examples::waitForLink(contact + "/contact_state", 30.0)) return 1;
  for (int end = k + steps; k < end; ++k) {
    wrc::NormalLoad l;
    l.header.stamp = stampOf(k);
    l.force = kFz;
    load.publish(l);
    wrc::Creepage c;
    c.header.stamp = stampOf(k);
    c.velocity = kV;
    c.longitudinal = xiAt(k, 0);
    c.lateral = etaAt(k);
    creepage.publish(c);
    if (!waitFor(state, c.header.stamp)) return 1;
    print("topic", contact, k, c.header.stamp, xiAt(k, 0), etaAt(k), kFz, state.fx, state.fy,
          state.mz, state.status);
  }

  // 3. The vehicle: all contacts in one message per tick, the answer in the input's order.
  if (!ros::service::waitForService(vehicle + "/vehicle_step", ros::Duration(30.0))) return 1;
  auto vehicleStep = nh.serviceClient<wrc::VehicleStep>(vehicle + "/vehicle_step", true);
  wrc::VehicleState vstate;
  auto input = nh.advertise<wrc::VehicleInput>(vehicle + "/vehicle_input", 10);
  auto vstateSub = nh.subscribe<wrc::VehicleState>(
      vehicle + "/vehicle_state", 10, [&](const wrc::VehicleState::ConstPtr& m) { vstate = *m; });
  while (ros::ok() && input.getNumSubscribers() == 0) ros::WallDuration(0.01).sleep();
  if (!wheel_rail_contact_examples::waitForLink(vehicle + "/vehicle_state", 30.0)) return 1;
  for (int end = k + 2 * steps; k < end; ++k) {
    wrc::VehicleStep s;
    s.request.input.header.stamp = stampOf(k);
    for (size_t w = 0; w < wheels.size(); ++w) {
      wrc::ContactInput c;
      c.name = wheels[w];
      c.velocity = kV;
      c.longitudinal = xiAt(k, w);
      c.lateral = etaAt(k);
      c.normal_force = fzAt(k, w);
      s.request.input.contacts.push_back(c);
    }
    const bool viaService = k < end - steps;
    if (viaService && !vehicleStep.call(s)) return 1;
    if (!viaService) input.publish(s.request.input);
    if (!viaService && !waitFor(vstate, stampOf(k))) return 1;
    const wrc::VehicleState& out = viaService ? s.response.state : vstate;
    if (out.contacts.size() != wheels.size()) {  // a name the node does not have, or one missing
      ROS_ERROR("vehicle: %zu contacts sent, %zu answered", wheels.size(), out.contacts.size());
      return 1;
    }
    for (size_t w = 0; w < out.contacts.size(); ++w) {
      const auto& c = s.request.input.contacts[w];
      const auto& r = out.contacts[w];
      print(viaService ? "vehicle_step" : "vehicle_topic", out.names[w], k, out.header.stamp,
            c.longitudinal, c.lateral, c.normal_force, r.fx, r.fy, r.mz, r.status);
    }
  }
  return 0;
}
