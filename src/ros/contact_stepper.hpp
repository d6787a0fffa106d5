/// The ROS-free bookkeeping of contact_node: pairing each creepage with its normal load, stamp
/// ordering, time step, time-jump reset, per-step geometry, the held output of rejected steps and
/// counters. One ContactStepper per contact; the node only converts messages and arms a timer.
/// Stamps are integer nanoseconds (ros::Time::toNSec()), so dt is exact to 1 ns; stamp 0 means
/// "unstamped". The wall clock of the load wait is passed in (`nowNs`, any monotonic clock), so
/// the pairing is unit-tested without ROS and without sleeping. doc/ros_interface.md states the
/// rules.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"

namespace wheel_rail_contact {

/// ContactState.status for a StepStatus (STATUS_OK 0, NO_LOAD 1, STANDSTILL 2, REJECTED 3).
uint8_t contactStateStatus(StepStatus s);

/// The default frame_id of a contact under namespace `ns`: "/bogie1/wheelset1/left" ->
/// "bogie1_wheelset1_left_contact"; the root namespace gives "contact".
std::string frameIdForNamespace(const std::string& ns);

/// How a creepage message finds its normal load.
enum class LoadPairing {
  kStamp,   ///< the load with the creepage's stamp, whichever arrives first (bounded wait)
  kLatest,  ///< the latest load received when the creepage arrives (arrival order decides)
};

/// "stamp" / "latest"; parseLoadPairing throws std::invalid_argument naming load_pairing.
const char* toString(LoadPairing p);
LoadPairing parseLoadPairing(const std::string& text);

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
  LoadPairing load_pairing = LoadPairing::kStamp;
  /// Stamp pairing: the longest time a creepage waits for the load with its stamp [s], on the
  /// caller's monotonic clock (wall time: a simulator paused in lock-step still gets an answer);
  /// in [0, 60]. A load with a later stamp ends the wait at once (loads come in stamp order).
  double load_wait = 0.1;
  /// Stamp pairing: most creepages waiting at once, and most loads kept for pairing; >= 1. When
  /// full, the oldest creepage is stepped with the latest load. The node sets it to queue_size.
  int pairing_buffer = 100;
};

/// Throws std::invalid_argument starting with the parameter's name.
void validate(const StepperOptions& o);

/// Principal relative curvatures of the undeformed gap h = A x^2 + B y^2 [1/m] given with one step
/// (geometry/hertz.hpp); both 0 = not given. Given, Hertz makes a, b from the step's paired load.
struct GapCurvatures {
  double A = 0.0;  ///< along x (rolling) [1/m]
  double B = 0.0;  ///< along y (lateral) [1/m]
};

/// What happened to one creepage input, beyond the model's own StepOutput.
enum class StepEvent {
  kStepped = 0,     ///< passed to the model (its StepOutput.status says the rest)
  kNoLoadYet,       ///< no normal load for this step: zero forces, status no load
  kNonFinite,       ///< NaN/Inf field: status rejected, state and time base untouched
  kBadGeometry,     ///< invalid or conflicting a, b, curvatures, mu: rejected, state untouched
  kOutOfOrder,      ///< stamp <= previous: status rejected, state untouched
  kDtTooLarge,      ///< dt > max_dt: status rejected, time base moves to this stamp
  kDroppedByReset,  ///< still waiting for its load when the state was reset: status rejected
};

/// Which load a step used (ContactState.load_match follows these numbers).
enum class LoadMatch {
  kSameStamp = 0,  ///< the load carrying the creepage's stamp (or given with the Step call)
  kLatest = 1,     ///< load_pairing latest (or an unstamped creepage): the latest load
  kUnmatched = 2,  ///< stamp pairing found no load with this stamp: the latest load at this stamp
  kNone = 3,       ///< no load at all (status no load)
};

struct StepResult {
  /// Forces and status, never non-finite. For a rejected step the force fields are held: the
  /// last accepted step's (held = true), or zero forces with fz = this step's load (0 if none)
  /// before any accepted step since start or reset.
  StepOutput out;
  /// Why the step is not a plain OK step: out.message, or the stepper's own reason (stamps, dt,
  /// pairing), which may carry numbers and so is built here rather than in the model.
  std::string message;
  int64_t stampNs = 0;      ///< the creepage's stamp (results may come later than their input)
  double dt = 0.0;          ///< time step used [s] (0 for the first step after start or reset)
  double solverTime = 0.0;  ///< wall time of model->step [s]
  StepEvent event = StepEvent::kStepped;
  LoadMatch loadMatch = LoadMatch::kNone;
  int64_t loadStampNs = 0;     ///< stamp of the load used (0: unstamped or none)
  bool held = false;           ///< out's forces are the last accepted step's (status rejected)
  bool timeJumpReset = false;  ///< the state was reset before this step (backwards time jump)
  bool staleLoad = false;      ///< the load used is older than max_load_age
  double loadAge = 0.0;        ///< creepage stamp - load stamp [s] (0 for an unstamped load)
};

struct StepperCounters {
  uint64_t creepages = 0;  ///< creepage inputs (topic and service)
  uint64_t ok = 0, noLoad = 0, standstill = 0, rejected = 0, notConverged = 0;  ///< by status
  uint64_t nonFinite = 0, badGeometry = 0, outOfOrder = 0, dtTooLarge = 0, rejectedByModel = 0;
  uint64_t droppedByReset = 0;
  uint64_t timeJumpResets = 0, resets = 0, staleLoad = 0;
  uint64_t loads = 0, loadsUnstamped = 0, loadsRejected = 0, loadsOutOfOrder = 0;
  /// Stamp pairing: steps without the load of their stamp, in all and by why the wait ended.
  uint64_t unmatched = 0, unmatchedLaterLoad = 0, unmatchedWaitExpired = 0, unmatchedBufferFull = 0;
  uint64_t pendingMax = 0;  ///< most creepages waiting for their load at once
  double solverTimeLast = 0.0, solverTimeMax = 0.0, solverTimeSum = 0.0;  ///< [s]
};

class ContactStepper {
 public:
  /// Curvature input is refused (no material for Hertz); use the constructor below to accept it.
  ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options);
  /// `material` gives G and nu for Hertz from per-step curvatures (the model's own parameters).
  ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options,
                 const ContactParameters& material);

  // ---- Topic inputs: results come out through takeReady(), one per creepage, in input order.

  /// A normal-load message (stampNs 0 = unstamped). Returns "" if accepted, else why it was
  /// rejected (non-finite, or a stamp older than the newest stamped load's). May release waiting
  /// creepages.
  std::string addLoad(int64_t stampNs, double fz, int64_t nowNs);

  /// A creepage message; in.fz and in.dt are ignored (the load is paired here, dt comes from the
  /// stamps). Stamp pairing queues it until its load is there (see StepperOptions).
  void addCreepage(int64_t stampNs, const StepInput& in, int64_t nowNs,
                   const GapCurvatures& curvatures = {});

  /// Steps the creepages whose load wait has expired at nowNs (the node's timer).
  void release(int64_t nowNs);

  /// When the oldest waiting creepage's wait expires; false if none is waiting.
  bool nextDeadline(int64_t* nowNs) const;

  /// The results produced since the last call, in input order.
  std::vector<StepResult> takeReady();

  size_t pending() const { return pending_.size(); }

  // ---- Call inputs (Step service, vehicle interface): the result at once.

  /// One step with its own load: in.fz is this step's load (it also becomes the load for stamp
  /// stampNs and the latest load), in.a, in.b, in.mu and `curvatures` the optional geometry and
  /// friction; in.dt is ignored. Creepages still waiting with a stamp <= stampNs are stepped first
  /// (their results go to takeReady()).
  StepResult stepWithLoad(int64_t stampNs, const StepInput& in,
                          const GapCurvatures& curvatures = {});
  StepResult stepWithLoad(int64_t stampNs, double V, double xi, double eta, double phi, double fz);
  /// A step its caller refuses without stepping (the vehicle interface: a contact named twice in a
  /// tick or missing from it): rejected with `why` and held like every rejected step; the model,
  /// the time base and the loads are untouched. `load` is the caller's load for it (0 if none).
  StepResult refuse(std::string why, double load);

  /// Clears everything a fresh stepper does not have: model state, time base, loads, held
  /// output. Creepages still waiting for their load are answered first, rejected (takeReady()).
  /// Counters are kept (resets is incremented).
  void reset();

  const StepperCounters& counters() const { return counters_; }
  std::string modelName() const { return model_->name(); }
  std::string modelChoices() const { return model_->choices(); }
  const StepperOptions& options() const { return options_; }
  bool hasLoad() const { return latest_.valid; }
  double load() const { return latest_.fz; }  ///< the latest accepted load [N]

 private:
  struct Load {
    bool valid = false;
    double fz = 0.0;
    int64_t stampNs = 0;  ///< 0: unstamped
    uint64_t seq = 0;     ///< arrival number: the larger, the later received
  };
  struct Pending {
    int64_t stampNs;
    StepInput in;
    GapCurvatures curvatures;
    int64_t deadlineNs;
  };
  struct Choice {
    Load load;
    LoadMatch match = LoadMatch::kNone;
    std::string why;  ///< for an unmatched step: why its wait ended
  };

  bool storeLoad(int64_t stampNs, double fz);
  void releaseReady(int64_t nowNs, bool useDeadline, int64_t forceUpToNs);
  void stepFront(Choice c);
  Choice fallback(int64_t stampNs) const;
  const Load* exactLoad(int64_t stampNs) const;
  bool sameTimeLine(int64_t laterNs, int64_t earlierNs) const;
  StepResult stepImpl(int64_t stampNs, const StepInput& in, const GapCurvatures& k,
                      const Choice& c);
  StepResult finish(StepResult r, double pairedLoad);
  void resetState();
  void clearLoads();

  std::unique_ptr<ContactModel> model_;
  StepperOptions options_;
  bool hasMaterial_ = false;
  double G_ = 0.0, nu_ = 0.0;

  bool hasStamp_ = false;
  int64_t lastStampNs_ = 0;

  uint64_t seq_ = 0;
  Load latest_;     ///< latest accepted load, stamped or not
  Load unstamped_;  ///< latest unstamped load
  bool hasStampedLoad_ = false;
  int64_t newestLoadStampNs_ = 0;
  std::deque<Load> loads_;  ///< stamp pairing: recent stamped loads, increasing stamps
  std::deque<Pending> pending_;
  std::vector<StepResult> ready_;

  bool hasAccepted_ = false;
  StepOutput accepted_;  ///< the last accepted (not rejected) step's output, held on rejection

  StepperCounters counters_;
};

}  // namespace wheel_rail_contact
