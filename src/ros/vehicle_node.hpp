/// vehicle_node: all contacts of a vehicle in one node, one message in and one out per tick
/// (VehicleInput -> VehicleState), a batch step service and one reset for all contacts. A thin
/// ROS wrapper over VehicleStepper; the interface is documented in doc/vehicle_interface.md.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "node_common.hpp"
#include "vehicle_stepper.hpp"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/VehicleInput.h"
#include "wheel_rail_contact/VehicleState.h"
#include "wheel_rail_contact/VehicleStep.h"

namespace wheel_rail_contact {

class VehicleNode {
 public:
  VehicleNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

  /// Reads and validates every private parameter. On an invalid one: ROS_FATAL naming it, false.
  bool readParameters();

  /// Advertises the output and services and subscribes to the input (after readParameters).
  void start();

 private:
  void inputCallback(const ros::MessageEvent<const VehicleInput>& event);
  bool stepService(VehicleStep::Request& req, VehicleStep::Response& res);
  bool resetService(Reset::Request& req, Reset::Response& res);
  /// One tick: steps every contact and fills *state (the caller holds mutex_).
  void tick(const VehicleInput& in, VehicleState* state);
  void report(const VehicleContactResult& r, const std::string& name);
  void diagnoseVehicle(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnoseContact(size_t i, diagnostic_updater::DiagnosticStatusWrapper& stat);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<VehicleStepper> vehicle_;
  int queueSize_ = 100;
  int publishQueueSize_ = 100;
  double diagnosticPeriod_ = 1.0;

  // Callbacks are serialised in the node and on a nodelet's default handle; the lock keeps a tick
  // whole should a host spin this handle's queue from several threads.
  std::mutex mutex_;
  std::vector<VehicleContactInput> inputs_;    // reused every tick
  std::vector<VehicleContactResult> results_;  // reused every tick

  ros::Subscriber inputSub_;
  ros::Publisher statePub_;
  ros::ServiceServer stepSrv_, resetSrv_;
  NodeDiagnostics diagnostics_;  // started in start()
  std::vector<StepperCounters> lastStepper_;
  std::vector<VehicleContactCounters> lastVehicle_;
  LostInputs lostInputs_;
};

}  // namespace wheel_rail_contact
