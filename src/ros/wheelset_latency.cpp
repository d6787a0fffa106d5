// wheelset_latency: round trip of a running wheelset_node from a C++ client (a measurement, not a
// test; doc/wheelset_interface.md). One WheelsetInput per tick with every wheelset, at a wall-clock
// rate: `topic` publishes each tick on schedule whatever the answers do (answers collected as they
// come on another thread); `service` calls wheelset_step on schedule (a late call delays the next).
// Round trip: from just before the publish or call to the answer's arrival. Private parameters:
// ns (default /wheelsets), wheelsets (names, default wheelset1..4), seconds (10), rate (1000 Hz),
// mode (topic | service), stall (20 ms: a round trip longer counts as a stall), sway (3e-3 m: the
// lateral amplitude) and offset (0 m: the lateral centre of the sway; offset 2e-3 with sway 1e-3
// keeps every wheel on its tread clear of the centred pose). Prints one line:
// the round trip, the node's WheelsetContact steps per tick (its answers' solver_time) and what is
// left of each round trip without them (the transport: both ends' messages and sockets, the
// node's callback and the answer's fill). Exit code 1 if a tick was lost or a wheel's answer was
// not ok. One untimed call and a reset come first (the connection, a fresh time base). In `service`
// mode the client does not subscribe to wheelset_forces: a service client does not need the node's
// published copy, and receiving it would cost the node a second message send per call and the
// client a second decode.
#include <ros/ros.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "../../examples/wait_for_link.hpp"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/WheelsetForces.h"
#include "wheel_rail_contact/WheelsetInput.h"
#include "wheel_rail_contact/WheelsetStep.h"

using wheel_rail_contact::WheelContactState;
using wheel_rail_contact::WheelsetForces;
using wheel_rail_contact::WheelsetInput;
using Clock = std::chrono::steady_clock;

namespace {

/// Wheelset i's state at tick k: a sway on the treads (lateral offset + sway sin(w)) at 30 m/s,
/// 60 kN per wheel.
WheelsetInput tick(const std::vector<std::string>& names, int64_t stampNs, int k, double sway,
                   double offset) {
  WheelsetInput in;
  in.header.stamp.fromNSec(static_cast<uint64_t>(stampNs));
  for (size_t i = 0; i < names.size(); ++i) {
    wheel_rail_contact::WheelsetKinematics s;
    s.name = names[i];
    const double w = 2.0 * M_PI * 1.5 * 1e-3 * k + static_cast<double>(i);
    s.lateral = offset + sway * std::sin(w);
    s.yaw = 1e-3 * std::cos(w);
    s.velocity = 30.0;
    s.pitch_rate = 30.0 / 0.46;
    s.lateral_velocity = sway * 2.0 * M_PI * 1.5 * std::cos(w);
    s.yaw_rate = -1e-3 * 2.0 * M_PI * 1.5 * std::sin(w);
    s.load_left = 6e4 + 2e3 * std::sin(w);
    s.load_right = 6e4 - 2e3 * std::sin(w);
    in.wheelsets.push_back(s);
  }
  return in;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t i = static_cast<size_t>(std::ceil(q / 100.0 * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, i > 0 ? i - 1 : 0)];
}

/// The node's compute for one tick: its wheelsets' WheelsetContact steps [s].
double solverTime(const WheelsetForces& f) {
  double t = 0.0;
  for (const auto& w : f.wheelsets) t += w.solver_time;
  return t;
}

bool allOk(const WheelsetForces& f, size_t n) {
  if (f.wheelsets.size() != n) return false;
  for (const auto& w : f.wheelsets)
    if (w.left.status != WheelContactState::STATUS_OK ||
        w.right.status != WheelContactState::STATUS_OK)
      return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "wheelset_latency", ros::init_options::AnonymousName);
  ros::NodeHandle nh, pnh("~");
  const std::string ns = pnh.param<std::string>("ns", "/wheelsets");
  std::vector<std::string> names;
  if (!pnh.getParam("wheelsets", names))
    names = {"wheelset1", "wheelset2", "wheelset3", "wheelset4"};
  const double seconds = pnh.param("seconds", 10.0), rate = pnh.param("rate", 1000.0);
  const double stall = pnh.param("stall", 0.02);
  const double sway = pnh.param("sway", 3e-3), offset = pnh.param("offset", 0.0);
  const std::string mode = pnh.param<std::string>("mode", "topic");
  const int n = static_cast<int>(std::lround(seconds * rate));
  const int64_t periodNs = static_cast<int64_t>(std::llround(1e9 / rate));

  std::mutex m;
  std::condition_variable cv;
  std::unordered_map<uint64_t, Clock::time_point> sentAt;
  std::vector<double> trips, compute, transport;
  trips.reserve(n);
  compute.reserve(n);
  transport.reserve(n);
  int bad = 0;
  std::atomic<int> answered{0};
  auto onForces = [&](const WheelsetForces::ConstPtr& f) {
    const Clock::time_point now = Clock::now();
    std::lock_guard<std::mutex> lock(m);
    const auto it = sentAt.find(f->header.stamp.toNSec());
    if (it == sentAt.end()) return;  // not ours (a run before)
    trips.push_back(std::chrono::duration<double>(now - it->second).count());
    compute.push_back(solverTime(*f));
    transport.push_back(trips.back() - compute.back());
    if (!allOk(*f, names.size())) ++bad;
    sentAt.erase(it);
    ++answered;
    cv.notify_all();
  };
  const bool service = mode == "service";
  ros::Subscriber sub;
  if (!service)
    sub = nh.subscribe<WheelsetForces>(
        ns + "/wheelset_forces", 100000,
        boost::function<void(const WheelsetForces::ConstPtr&)>(onForces), ros::VoidConstPtr(),
        ros::TransportHints().tcpNoDelay());
  ros::Publisher pub;
  if (!service) pub = nh.advertise<WheelsetInput>(ns + "/wheelset_input", 100000);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  if (!ros::service::waitForService(ns + "/wheelset_step", ros::Duration(120.0))) {
    std::fprintf(stderr, "wheelset_latency: %s/wheelset_step not available\n", ns.c_str());
    return 1;
  }
  ros::ServiceClient step =
      nh.serviceClient<wheel_rail_contact::WheelsetStep>(ns + "/wheelset_step", true);
  // An untimed call opens the persistent connection (roscpp opens it on the first call, with a
  // master lookup); the reset then gives a fresh time base and histories.
  wheel_rail_contact::WheelsetStep warmUp;
  warmUp.request.input =
      tick(names, static_cast<int64_t>(ros::WallTime::now().toNSec()) - periodNs, 0, sway, offset);
  wheel_rail_contact::Reset reset;
  if (!step.call(warmUp) || !ros::service::call(ns + "/reset", reset)) {
    std::fprintf(stderr, "wheelset_latency: %s/wheelset_step or reset failed\n", ns.c_str());
    return 1;
  }
  const Clock::time_point wait = Clock::now() + std::chrono::seconds(30);
  while (!service && pub.getNumSubscribers() == 0 && Clock::now() < wait)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // poll the graph
  if (!service && !wheel_rail_contact_examples::waitForLink(
                      ros::names::resolve(ns + "/wheelset_forces"), 30.0)) {
    std::fprintf(stderr, "wheelset_latency: not connected to %s\n", ns.c_str());
    return 1;
  }

  // Stamps continue from the wall clock so that a second run needs no reset.
  const int64_t t0 = static_cast<int64_t>(ros::WallTime::now().toNSec());
  const Clock::time_point start = Clock::now();
  int late = 0, failedCalls = 0;
  for (int k = 0; k < n; ++k) {
    const Clock::time_point due = start + std::chrono::nanoseconds(periodNs * k);
    if (Clock::now() < due)
      std::this_thread::sleep_until(due);
    else if (Clock::now() - due > std::chrono::nanoseconds(periodNs))
      ++late;
    const WheelsetInput in = tick(names, t0 + periodNs * k, k, sway, offset);
    if (service) {
      wheel_rail_contact::WheelsetStep srv;
      srv.request.input = in;
      const Clock::time_point sent = Clock::now();
      const bool ok = step.call(srv);
      const double trip = std::chrono::duration<double>(Clock::now() - sent).count();
      std::lock_guard<std::mutex> lock(m);
      if (!ok) {
        ++failedCalls;
        continue;
      }
      trips.push_back(trip);
      compute.push_back(solverTime(srv.response.forces));
      transport.push_back(trip - compute.back());
      if (!allOk(srv.response.forces, names.size())) ++bad;
    } else {
      {
        std::lock_guard<std::mutex> lock(m);
        sentAt[in.header.stamp.toNSec()] = Clock::now();
      }
      pub.publish(in);
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  if (!service) {  // the last answers: 2 s at most
    std::unique_lock<std::mutex> lock(m);
    cv.wait_for(lock, std::chrono::seconds(2), [&] { return answered.load() >= n; });
  }
  spinner.stop();  // no callback from here on (one blocked on m would keep stop() waiting)
  std::lock_guard<std::mutex> lock(m);
  const int lost = n - static_cast<int>(trips.size());
  const long stalls =
      std::count_if(trips.begin(), trips.end(), [&](double t) { return t > stall; });
  std::printf(
      "wheelset_latency %s: %zu wheelsets, %d ticks at %.0f Hz in %.2f s wall: round trip p50 "
      "%.3f ms, p99 %.3f ms, max %.3f ms; lost %d, not ok %d, stalls > %.0f ms %ld, late sends "
      "%d; the node's WheelsetContact steps per tick p50 %.3f ms, p99 %.3f ms, max %.3f ms; the "
      "transport (round trip less the node's steps) p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
      mode.c_str(), names.size(), n, rate, wall, 1e3 * percentile(trips, 50),
      1e3 * percentile(trips, 99), 1e3 * percentile(trips, 100), lost, bad, 1e3 * stall, stalls,
      late, 1e3 * percentile(compute, 50), 1e3 * percentile(compute, 99),
      1e3 * percentile(compute, 100), 1e3 * percentile(transport, 50),
      1e3 * percentile(transport, 99), 1e3 * percentile(transport, 100));
  return lost == 0 && bad == 0 && failedCalls == 0 ? 0 : 1;
}
