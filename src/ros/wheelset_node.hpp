/// wheelset_node: every wheelset of a vehicle on real wheel and rail profiles in one node, one
/// message in and one out per tick (WheelsetInput -> WheelsetForces), a batch step service and one
/// reset. A thin ROS wrapper over WheelsetStepper (WheelsetContact per wheelset, one shared contact
/// table); the interface is documented in doc/wheelset_interface.md.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "node_common.hpp"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/WheelsetForces.h"
#include "wheel_rail_contact/WheelsetInput.h"
#include "wheel_rail_contact/WheelsetStep.h"
#include "wheelset_stepper.hpp"

namespace wheel_rail_contact {

/// A profile parameter's file: "package://PKG/path" (resolved through the package's path) or an
/// absolute path; "" = the standard profile. Throws std::invalid_argument naming `parameter`.
std::string resolveProfilePath(const std::string& parameter, const std::string& value);

class WheelsetNode {
 public:
  WheelsetNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Reads and validates every private parameter, reads the profiles and builds the contact
  /// table. On an invalid one: ROS_FATAL naming it, false.
  bool readParameters();

  /// Advertises the output and services and subscribes to the input (after readParameters).
  void start();

 private:
  void inputCallback(const ros::MessageEvent<const WheelsetInput>& event);
  bool stepService(WheelsetStep::Request& req, WheelsetStep::Response& res);
  bool resetService(Reset::Request& req, Reset::Response& res);
  /// One tick: steps every wheelset and fills *out (the caller holds mutex_).
  void tick(const WheelsetInput& in, WheelsetForces* out);
  void report(const WheelsetAnswer& a, const std::string& name);
  void diagnoseNode(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnoseWheelset(size_t i, diagnostic_updater::DiagnosticStatusWrapper& stat);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<WheelsetStepper> stepper_;
  std::vector<std::string> frameIds_;
  int queueSize_ = 100;
  int publishQueueSize_ = 100;
  double diagnosticPeriod_ = 1.0;

  // Callbacks are serialised in the node and on a nodelet's default handle; the lock keeps a tick
  // whole should a host spin this handle's queue from several threads.
  std::mutex mutex_;
  std::vector<WheelsetEntry> entries_;   // reused every tick
  std::vector<WheelsetAnswer> answers_;  // reused every tick

  ros::Subscriber inputSub_;
  ros::Publisher forcesPub_;
  ros::ServiceServer stepSrv_, resetSrv_;
  NodeDiagnostics diagnostics_;  // started in start()
  std::vector<WheelsetCounters> lastCounters_;
  LostInputs lostInputs_;
};

}  // namespace wheel_rail_contact
