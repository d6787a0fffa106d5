/// contact_node: a thin ROS wrapper over one ContactModel (via ContactStepper). Topics, services,
/// parameters and rules: doc/ros_interface.md. Every name is relative, so several contacts run side
/// by side under namespaces.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <map>
#include <memory>
#include <string>

#include "contact_stepper.hpp"
#include "wheel_rail_contact/Creepage.h"
#include "wheel_rail_contact/NormalLoad.h"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/Step.h"

namespace wheel_rail_contact {

class ContactNode {
 public:
  ContactNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Reads and validates every private parameter. On an invalid one: ROS_FATAL naming it, false.
  bool readParameters();

  /// Advertises the outputs and services and subscribes to the inputs (after readParameters).
  void start();

  /// Clears every piece of state (model, time base, latest load); counters are kept.
  void reset();

 private:
  void creepageCallback(const ros::MessageEvent<const Creepage>& event);
  void loadCallback(const NormalLoadConstPtr& msg);
  bool resetService(Reset::Request& req, Reset::Response& res);
  bool stepService(Step::Request& req, Step::Response& res);
  void onLoadWait(const ros::SteadyTimerEvent&);
  /// Publishes what the stepper has released and arms the load-wait timer for what still waits.
  void flush();
  void report(const StepResult& r);
  void publish(const StepResult& r);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<ContactStepper> stepper_;
  std::string frameId_;  // default: from the namespace (frameIdForNamespace)
  int queueSize_ = 100;
  int publishQueueSize_ = 100;
  double diagnosticPeriod_ = 1.0;

  ros::Subscriber creepageSub_, loadSub_;
  ros::Publisher forcePub_, statePub_;
  ros::ServiceServer resetSrv_, stepSrv_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;  // made in start()
  ros::WallTimer diagnosticTimer_;
  /// Load pairing: fires when the oldest waiting creepage's load_wait expires (steady clock: it
  /// runs while sim time is paused, so a lock-step simulator is always answered).
  ros::SteadyTimer loadWaitTimer_;
  bool loadWaitArmed_ = false;
  int64_t loadWaitDeadlineNs_ = 0;
  StepperCounters lastDiag_;
  ros::WallTime lastDiagTime_;
  /// Creepage header.seq per publisher: a gap means the subscriber queue (queue_size) overflowed.
  std::map<std::string, uint32_t> lastSeq_;
  uint64_t lostCreepages_ = 0, lastLost_ = 0;
};

}  // namespace wheel_rail_contact
