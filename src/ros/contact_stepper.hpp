/// The ROS-free bookkeeping of contact_node: stamp ordering, time step, time-jump reset, latest
/// normal load and its age, counters. One ContactStepper per contact; the node only converts
/// messages. Stamps are integer nanoseconds (ros::Time::toNSec()), so dt is exact to 1 ns.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "wheel_rail_contact/contact_model.hpp"

namespace wheel_rail_contact {

/// ContactState.status for a StepStatus (STATUS_OK 0, NO_LOAD 1, STANDSTILL 2, REJECTED 3).
uint8_t contactStateStatus(StepStatus s);

/// The node-only parameters (private ~NAME, also accepted and ignored by contact_cli --config).
struct StepperOptions {
  /// A creepage stamp more than max_dt after the previous one is rejected (the time base moves to
  /// it, so the next message is stepped normally) [s]; > 0.
  double max_dt = 1.0;
  /// A creepage stamp this far behind the previous one resets the state (like robot_localization's
  /// reset_on_time_jump) [s]; 0 = off: such a message is rejected as out of order.
  double time_jump_reset = 0.0;
  /// A normal load older than this (creepage stamp - load stamp) gives a warning [s]; 0 = off.
  double max_load_age = 1.0;
};

/// Throws std::invalid_argument starting with the parameter's name.
void validate(const StepperOptions& o);

/// What happened to one creepage input, beyond the model's own StepOutput.
enum class StepEvent {
  kStepped = 0,  ///< passed to the model (its StepOutput.status says the rest)
  kNoLoadYet,    ///< no normal load received since start or reset: zero forces, status no load
  kNonFinite,    ///< NaN/Inf field: zero forces, status rejected, state and time base untouched
  kOutOfOrder,   ///< stamp <= previous: zero forces, status rejected, state untouched
  kDtTooLarge,   ///< dt > max_dt: zero forces, status rejected, time base moves to this stamp
};

struct StepResult {
  StepOutput out;  ///< forces and status, never non-finite
  /// Why the step is not a plain OK step: out.message, or the stepper's own reason (stamps, dt),
  /// which may carry numbers and so is built here rather than in the model.
  std::string message;
  double dt = 0.0;          ///< time step used [s] (0 for the first step after start or reset)
  double solverTime = 0.0;  ///< wall time of model->step [s]
  StepEvent event = StepEvent::kStepped;
  bool timeJumpReset = false;  ///< the state was reset before this step (backwards time jump)
  bool staleLoad = false;      ///< the load used is older than max_load_age
  double loadAge = 0.0;        ///< creepage stamp - load stamp [s]
};

struct StepperCounters {
  uint64_t creepages = 0;  ///< creepage inputs (topic and service)
  uint64_t ok = 0, noLoad = 0, standstill = 0, rejected = 0, notConverged = 0;  ///< by status
  uint64_t nonFinite = 0, outOfOrder = 0, dtTooLarge = 0, rejectedByModel = 0;
  uint64_t timeJumpResets = 0, resets = 0, staleLoad = 0;
  uint64_t loads = 0, loadsRejected = 0, loadsOutOfOrder = 0;
  double solverTimeLast = 0.0, solverTimeMax = 0.0, solverTimeSum = 0.0;  ///< [s]
};

class ContactStepper {
 public:
  ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options);

  /// A normal-load message. Returns "" if accepted, else why it was rejected (non-finite, or a
  /// stamp older than the latest load's); a rejected load leaves the latest load as it was.
  std::string setLoad(int64_t stampNs, double fz);

  /// One creepage message: exactly one result, whatever the input.
  StepResult step(int64_t stampNs, double V, double xi, double eta, double phi);

  /// The Step service: `fz` becomes the latest load (stamp = stampNs) and is used for this step.
  StepResult stepWithLoad(int64_t stampNs, double V, double xi, double eta, double phi, double fz);

  /// The same with the whole input: in.fz is this step's load (it becomes the latest load, stamp
  /// stampNs), in.a, in.b, in.mu the optional per-step geometry and friction; in.dt is ignored.
  StepResult stepWithLoad(int64_t stampNs, const StepInput& in);

  /// Clears everything a fresh stepper does not have: model state, time base, latest load.
  /// Counters are kept (resets is incremented).
  void reset();

  const StepperCounters& counters() const { return counters_; }
  std::string modelName() const { return model_->name(); }
  std::string modelChoices() const { return model_->choices(); }
  bool hasLoad() const { return hasLoad_; }
  double load() const { return load_; }

 private:
  StepResult stepImpl(int64_t stampNs, const StepInput& in, bool loadGiven);
  StepResult finish(StepResult r);
  void resetState();

  std::unique_ptr<ContactModel> model_;
  StepperOptions options_;
  bool hasStamp_ = false;
  int64_t lastStampNs_ = 0;
  bool hasLoad_ = false;
  int64_t loadStampNs_ = 0;
  double load_ = 0.0;
  StepperCounters counters_;
};

}  // namespace wheel_rail_contact
