/// The ROS-free bookkeeping of wheelset_node: N named wheelsets (one WheelsetContact each, sharing
/// one contact table) stepped together once per tick. It keeps each wheelset's time line (dt from
/// the stamps), matches the tick's entries to the wheelsets by name, and makes every rejection a
/// defined output: a rejected wheel repeats its last accepted answer (never a zero or made-up force
/// a simulator would apply), and every input entry and every configured wheelset missing from the
/// input get exactly one answer.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

namespace wheel_rail_contact {

/// Everything the wheelsets share: they run on the same profiles, track data and model.
struct WheelsetStepperConfig {
  std::vector<std::string> names;  ///< the wheelsets, in the order of the missing entries
  WheelsetTrackData track;         ///< profiles null: the standard S1002 / UIC60
  ContactParameters parameters;
  /// With use_contact_table (and no contact_table given) one table is built for all wheelsets.
  WheelsetContactOptions options;
  /// A stamp more than max_dt after the wheelset's previous one is rejected and restarts its time
  /// base there [s]; > 0.
  double max_dt = 1.0;
  /// A stamp this far behind the previous one resets the wheelset [s]; 0 = off (rejected as out
  /// of order instead).
  double time_jump_reset = 0.0;
  /// The wheelsets of a tick are stepped on this many threads (the caller's and threads - 1 more,
  /// each a contiguous share of the tick's entries); the answers are the same for any number.
  int threads = 1;
};

/// One wheelset's entry of a tick.
struct WheelsetEntry {
  std::string name;
  /// pose.z is not used; motion.cant is the track's cant under the wheelset this tick (beyond
  /// kMaxCant: WheelsetContact's kInvalidInput, held).
  WheelsetState state;
};

/// Why an entry was not stepped (kStepped: it was; each wheel's answer says how).
enum class WheelsetEvent {
  kStepped = 0,
  kUnknownName,  ///< no configured wheelset has this name: no wheelset touched
  kDuplicate,    ///< the name appears more than once: every occurrence rejected, held
  kMissing,      ///< a configured wheelset absent from the tick: appended, rejected, held
  kNonFinite,    ///< a value of the entry not finite: rejected, held, time base unchanged
  kOutOfOrder,   ///< the stamp is not after the previous one: rejected, held
  kDtTooLarge,   ///< dt > max_dt: rejected, held; the time base restarts at this stamp
};
const char* toString(WheelsetEvent e);

/// A wheel's answer (WheelContactState.status).
enum class WheelAnswerStatus {
  kOk = 0,
  kNoLoad = 1,         ///< accepted: zero forces, no patch
  kNoContact = 2,      ///< held
  kInvalidInput = 3,   ///< held
  kNormalFailed = 4,   ///< held
  kRejected = 5,       ///< the entry was refused (WheelsetEvent): held
  kPatchRejected = 6,  ///< a patch's tangential model refused its step: held
};

struct WheelAnswer {
  WheelAnswerStatus status = WheelAnswerStatus::kOk;
  std::string message;  ///< why, when status != kOk, or a patch's note
  bool held = false;    ///< `result` is the last accepted answer's (empty before any)
  /// The wheel's result: this step's when accepted, the last accepted one's when held (its status
  /// and message are that step's; status and message above are this one's).
  WheelResult result;
};

struct WheelsetAnswer {
  int wheelset = -1;  ///< index into the configuration's names, -1 for an unknown name
  WheelsetEvent event = WheelsetEvent::kStepped;
  std::string message;           ///< the event's reason ("" when stepped)
  double dt = 0.0;               ///< the step's dt [s] (0 when not stepped)
  double solver_time = 0.0;      ///< wall time of WheelsetContact::step [s]
  bool time_jump_reset = false;  ///< the stamp jumped back beyond time_jump_reset: reset first
  WheelAnswer left, right;
};

struct WheelsetCounters {
  uint64_t steps = 0;  ///< entries handed to WheelsetContact
  uint64_t duplicate = 0, missing = 0, non_finite = 0, out_of_order = 0, dt_too_large = 0;
  uint64_t held = 0;  ///< held wheel answers (two per rejected entry)
  uint64_t no_load = 0, no_contact = 0, invalid_input = 0, normal_failed = 0,
           patch_rejected = 0;  ///< wheel answers with that status
  uint64_t resets = 0, time_jump_resets = 0;
  double solver_time_sum = 0.0, solver_time_max = 0.0;  ///< [s]
};

struct WheelsetStepperCounters {
  uint64_t ticks = 0;
  uint64_t unknown_names = 0;
};

class WheelsetStepper {
 public:
  /// Throws std::invalid_argument naming the parameter (wheelsets: an empty list, an empty or
  /// repeated name; max_dt, time_jump_reset; WheelsetContact's own: track data, model).
  explicit WheelsetStepper(WheelsetStepperConfig config);

  /// One tick at `stamp_ns` for every wheelset: fills *out with one answer per entry of `in`, in
  /// its order, then one per configured wheelset missing from `in`, in configuration order.
  void step(int64_t stamp_ns, const std::vector<WheelsetEntry>& in,
            std::vector<WheelsetAnswer>* out);

  /// Resets every wheelset (patch histories, time base, held answers); counters are kept.
  void reset();

  size_t size() const { return wheelsets_.size(); }
  const std::string& name(size_t i) const { return config_.names[i]; }
  const WheelsetStepperConfig& config() const { return config_; }
  const WheelsetCounters& counters(size_t i) const { return wheelsets_[i].counters; }
  const WheelsetStepperCounters& counters() const { return counters_; }
  /// The table the wheelsets share, null without one.
  const std::shared_ptr<const ContactTable>& contactTable() const { return table_; }
  int find(const std::string& name) const;

 private:
  struct Wheelset {
    std::unique_ptr<WheelsetContact> contact;
    bool has_stamp = false;
    int64_t last_stamp_ns = 0;
    WheelResult accepted[2];  ///< the last accepted answer per wheel ([0] left)
    WheelsetCounters counters;
  };
  /// The answers of an entry that was not stepped: both wheels held, status kRejected.
  void refuse(Wheelset* w, WheelsetEvent event, std::string message, WheelsetAnswer* a);
  void answerWheel(Wheelset* w, int side, WheelResult result, WheelAnswer* a);
  /// Steps pending_ (on config_.threads threads), filling each one's result and time.
  void stepPending();

  /// An entry of this tick to be stepped: its answer's index in the output.
  struct Pending {
    size_t out;
    int wheelset;
    const WheelsetState* state;
    double dt;
    WheelsetResult result;
    double time;  ///< [s]
  };
  std::vector<Pending> pending_;

  WheelsetStepperConfig config_;
  std::shared_ptr<const ContactTable> table_;
  std::vector<Wheelset> wheelsets_;
  std::map<std::string, int> index_;
  std::vector<int> seen_;
  WheelsetStepperCounters counters_;
};

}  // namespace wheel_rail_contact
