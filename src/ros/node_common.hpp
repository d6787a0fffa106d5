/// What vehicle_node and wheelset_node share: the private parameters they read alike, the count of
/// inputs lost before the node and the diagnostics' wall timer.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace wheel_rail_contact {

/// `v` with every digit ("%.17g"), for messages.
std::string numberText(double v);

/// `text` as a number; throws std::invalid_argument naming `name` unless all of it is one.
double toNumber(const std::string& name, const std::string& text);

/// ~`key`: a non-empty list of names (a letter, then letters, digits, _); `what` names the items in
/// the message when it is not set ("a list of <what> names"). Throws std::invalid_argument.
std::vector<std::string> readNameList(const ros::NodeHandle& pnh, const std::string& key,
                                      const std::string& what);

/// ~`name`: an integer in [1, 1000000], `value` when not set. Throws std::invalid_argument.
int readCount(const ros::NodeHandle& pnh, const char* name, int value);

/// ~diagnostic_period [s] in (0, 86400] (ros::(Wall)Duration throws beyond 2^31 s; a day is
/// plenty), `value` when not set. Throws std::invalid_argument.
double readDiagnosticPeriod(const ros::NodeHandle& pnh, double value);

/// ~frame_prefix, or else the namespace of `nh`: /train/car1 -> train_car1_, so two vehicles'
/// frames differ.
std::string readFramePrefix(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

/// ROS_INFO of contact_node's keys found (a shared YAML file) and not used by `node`.
void logIgnoredParameters(const char* node, const std::string& ns,
                          const std::set<std::string>& ignored);

/// Inputs dropped before the callback: roscpp numbers each publisher's messages, so a gap in
/// header.seq is a tick the subscriber queue let go.
class LostInputs {
 public:
  /// Notes `seq` from `publisher`; on a gap counts it and warns (throttled) naming `topic`.
  void see(const std::string& publisher, uint32_t seq, const std::string& ns,
           const std::string& topic, int queueSize);
  uint64_t count() const { return lost_; }

 private:
  std::map<std::string, uint32_t> lastSeq_;
  uint64_t lost_ = 0;
};

/// The diagnostic updater, the wall timer that drives it (diagnostics keep coming while sim time
/// is paused) and the node-level report's bookkeeping since the last report.
class NodeDiagnostics {
 public:
  /// Makes the updater (its constructor reads ~diagnostic_period and throws on a value
  /// ros::Duration cannot hold, which readDiagnosticPeriod rules out), lets `addTasks` add the
  /// node's tasks, then starts the timer every `period` s under `mutex`.
  void start(ros::NodeHandle& nh, const ros::NodeHandle& pnh, double period, std::mutex* mutex,
             const std::function<void(diagnostic_updater::Updater&)>& addTasks);

  /// The node-level report's summary: WARN if inputs were lost before the node (`lost`, on
  /// `topic`) or entries named unknown `items` (`unknown`) since the last report, else OK. Returns
  /// the tick rate since the last report [Hz] (`ticks` counted since the start); the next report
  /// counts from now.
  double summarize(diagnostic_updater::DiagnosticStatusWrapper& stat, uint64_t ticks,
                   uint64_t unknown, uint64_t lost, const std::string& topic,
                   const std::string& items);

 private:
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer timer_;
  ros::WallTime lastTime_;
  uint64_t lastTicks_ = 0, lastUnknown_ = 0, lastLost_ = 0;
};

}  // namespace wheel_rail_contact
