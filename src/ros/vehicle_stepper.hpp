/// The ROS-free bookkeeping of vehicle_node: N named contacts (one ContactStepper each) stepped
/// together once per tick. It matches the tick's entries to the contacts by name, turns principal
/// curvatures into Hertz semi-axes, and makes every rejection a defined output: a rejected contact
/// repeats its last accepted forces (never a zero or made-up force a simulator would apply), and
/// every input entry and every configured contact missing from the input get exactly one result.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact_stepper.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"

namespace wheel_rail_contact {

/// One contact's configuration (the shared parameters with its own overrides applied).
struct VehicleContactConfig {
  std::string name;
  std::string frameId;
  ContactParameters parameters;
  StepperOptions options;
};

/// One contact's entry of a tick. StepInput's dt is ignored (the stepper takes it from the stamps).
struct VehicleContactInput {
  std::string name;
  StepInput in;             ///< V, xi, eta, phi, fz (this tick's load), optional a, b, mu
  double curvatureX = 0.0;  ///< A of the gap h = A x^2 + B y^2 [1/m]; 0 = not given
  double curvatureY = 0.0;  ///< B [1/m]; 0 = not given
};

/// Why an entry was not handed to its contact's stepper (kStepped: it was, see StepResult).
enum class VehicleEvent {
  kStepped = 0,
  kUnknownName,  ///< no configured contact has this name: zero forces, no contact touched
  kDuplicate,    ///< the name appears more than once: every occurrence rejected, contact held
  kMissing,      ///< a configured contact absent from the tick: appended, rejected, held
  kBadGeometry,  ///< a, b, curvature_x, curvature_y or mu malformed: rejected, held
};

struct VehicleContactResult {
  int contact = -1;  ///< index into contacts(), -1 for an unknown name
  VehicleEvent event = VehicleEvent::kStepped;
  bool held = false;  ///< status rejected: the forces are the contact's last accepted ones
  StepResult step;    ///< status, message (always set when status != ok), forces
};

struct VehicleContactCounters {
  uint64_t held = 0;         ///< rejected results that repeated the last accepted forces
  uint64_t duplicate = 0;    ///< entries rejected for a repeated name
  uint64_t missing = 0;      ///< ticks without this contact
  uint64_t badGeometry = 0;  ///< entries rejected for their optional geometry or friction
};

struct VehicleCounters {
  uint64_t ticks = 0;         ///< calls of step()
  uint64_t unknownNames = 0;  ///< entries whose name no contact has
};

class VehicleStepper {
 public:
  /// Throws std::invalid_argument naming the offending contact (empty list, empty or repeated
  /// name, invalid parameters).
  explicit VehicleStepper(const std::vector<VehicleContactConfig>& contacts);

  /// One tick at `stampNs` for every contact: fills *out with one result per entry of `in`, in
  /// its order, then one per configured contact missing from `in`, in configuration order.
  void step(int64_t stampNs, const std::vector<VehicleContactInput>& in,
            std::vector<VehicleContactResult>* out);

  /// Resets every contact (model, time base, load, held forces); counters are kept.
  void reset();

  size_t size() const { return contacts_.size(); }
  const VehicleContactConfig& config(size_t i) const { return contacts_[i].config; }
  const ContactStepper& stepper(size_t i) const { return *contacts_[i].stepper; }
  const VehicleContactCounters& counters(size_t i) const { return contacts_[i].counters; }
  const VehicleCounters& counters() const { return counters_; }
  /// Index of the contact named `name`, -1 if none.
  int find(const std::string& name) const;

 private:
  struct Contact {
    VehicleContactConfig config;
    std::unique_ptr<ContactStepper> stepper;
    VehicleContactCounters counters;
  };
  /// Records the hold of a result of contact `c` (ContactStepper holds every rejected step).
  static void countHeld(Contact* c, VehicleContactResult* r);

  std::vector<Contact> contacts_;
  std::map<std::string, int> index_;
  std::vector<int> seen_;  ///< entries per contact in the current tick
  VehicleCounters counters_;
};

}  // namespace wheel_rail_contact
