// contact_benchmark: latency and throughput of running contact_nodes (a measurement, not a test).
// Private parameters: contacts (namespaces, comma-separated or a list, default "bench/c0"),
// round_trips (per contact, default 1000), messages (per contact for the rate, default 10000),
// window (messages in flight per contact, default 200). Prints one line: p50/p99 round trip and the
// sustained rate. Round trip: publish one creepage to every contact at once, wait for each
// contact_state.
#include <ros/ros.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "wheel_rail_contact/ContactState.h"
#include "wheel_rail_contact/Creepage.h"
#include "wheel_rail_contact/NormalLoad.h"

namespace {

struct Contact {
  ros::Publisher creep, load;
  ros::Subscriber state;
  size_t received = 0;
  ros::WallTime sent, answered;
  uint64_t next = 0;  // stamp counter
};

/// One simulator tick: the load and the creepage with the same stamp (the node pairs them).
void publish(Contact& c) {
  wheel_rail_contact::Creepage m;
  m.header.stamp = ros::Time(1.0) + ros::Duration(1e-4 * static_cast<double>(++c.next));
  wheel_rail_contact::NormalLoad l;
  l.header.stamp = m.header.stamp;
  l.force = 8e4;
  c.load.publish(l);
  m.longitudinal = 1e-3;
  m.lateral = -5e-4;
  m.spin = 0.5;
  m.velocity = 20.0;
  c.creep.publish(m);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "contact_benchmark");
  ros::NodeHandle nh, pnh("~");
  std::vector<std::string> names{"bench/c0"};
  int roundTrips = 1000, messages = 10000, window = 50;
  std::string list;  // "a,b,c" (rosrun's _contacts:= gives a string) or a YAML list
  if (pnh.getParam("contacts", list)) {
    names.clear();
    for (size_t p = 0; p <= list.size();) {
      const size_t q = std::min(list.find(',', p), list.size());
      if (q > p) names.push_back(list.substr(p, q - p));
      p = q + 1;
    }
  } else {
    pnh.param("contacts", names, names);
  }
  pnh.param("round_trips", roundTrips, roundTrips);
  pnh.param("messages", messages, messages);
  pnh.param("window", window, window);
  std::vector<std::unique_ptr<Contact>> cs;
  for (const auto& n : names) {
    auto c = std::make_unique<Contact>();
    Contact* raw = c.get();
    c->creep = nh.advertise<wheel_rail_contact::Creepage>(n + "/creepage", 100000);
    c->load = nh.advertise<wheel_rail_contact::NormalLoad>(n + "/normal_load", 10, true);
    c->state = nh.subscribe<wheel_rail_contact::ContactState>(
        n + "/contact_state", 100000,
        [raw](const wheel_rail_contact::ContactState::ConstPtr&) {
          ++raw->received;
          raw->answered = ros::WallTime::now();
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
    cs.push_back(std::move(c));
  }
  auto spinUntil = [](auto pred, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && !pred() && ros::WallTime::now() < end) ros::spinOnce();
    return pred();
  };
  const bool up = spinUntil(
      [&] {
        for (auto& c : cs)
          if (c->creep.getNumSubscribers() == 0 || c->state.getNumPublishers() == 0 ||
              c->load.getNumSubscribers() == 0)
            return false;
        return true;
      },
      30.0);
  if (!up) {
    ROS_FATAL("contact_benchmark: contacts not reachable");
    return 1;
  }
  for (auto& c : cs) {
    wheel_rail_contact::NormalLoad l;
    l.header.stamp = ros::Time(1.0);
    l.force = 8e4;
    c->load.publish(l);
  }
  ros::WallDuration(0.5).sleep();

  // Round trips (after 50 warm-up ones).
  std::vector<double> rtt;
  for (int k = -50; k < roundTrips && ros::ok(); ++k) {
    std::vector<size_t> before;
    const ros::WallTime t0 = ros::WallTime::now();
    for (auto& c : cs) {
      before.push_back(c->received);
      publish(*c);
    }
    for (size_t i = 0; i < cs.size(); ++i) {
      if (!spinUntil([&] { return cs[i]->received > before[i]; }, 5.0)) {
        ROS_FATAL("contact_benchmark: lost a message");
        return 1;
      }
      if (k >= 0) rtt.push_back((cs[i]->answered - t0).toSec());
    }
  }
  std::sort(rtt.begin(), rtt.end());
  const double p50 = rtt[rtt.size() / 2], p99 = rtt[rtt.size() * 99 / 100];

  // Sustained rate: keep `window` messages in flight per contact.
  std::vector<size_t> start;
  for (auto& c : cs) start.push_back(c->received);
  const ros::WallTime t0 = ros::WallTime::now();
  std::vector<int> sent(cs.size(), 0);
  bool done = false;
  while (ros::ok() && !done) {
    done = true;
    for (size_t i = 0; i < cs.size(); ++i) {
      const size_t got = cs[i]->received - start[i];
      while (sent[i] < messages && sent[i] - static_cast<int>(got) < window) {
        publish(*cs[i]);
        ++sent[i];
      }
      if (got < static_cast<size_t>(messages)) done = false;
    }
    ros::spinOnce();
    if ((ros::WallTime::now() - t0).toSec() > 60.0) break;  // messages lost: reported below
  }
  const double span = (ros::WallTime::now() - t0).toSec();
  size_t total = 0;
  for (size_t i = 0; i < cs.size(); ++i) total += cs[i]->received - start[i];
  std::printf(
      "contacts %zu: round trip p50 %.3f ms, p99 %.3f ms (%zu samples); sustained %.0f "
      "messages/s in total (%zu of %zu answered in %.2f s, window %d)\n",
      cs.size(), 1e3 * p50, 1e3 * p99, rtt.size(), static_cast<double>(total) / span, total,
      static_cast<size_t>(messages) * cs.size(), span, window);
  return total == static_cast<size_t>(messages) * cs.size() ? 0 : 1;
}
