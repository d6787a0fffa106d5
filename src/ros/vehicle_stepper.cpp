#include "vehicle_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

VehicleStepper::VehicleStepper(const std::vector<VehicleContactConfig>& contacts) {
  if (contacts.empty()) throw std::invalid_argument("contacts: the list is empty");
  for (const auto& config : contacts) {
    if (config.name.empty()) throw std::invalid_argument("contacts: an empty name");
    if (index_.count(config.name))
      throw std::invalid_argument("contacts: '" + config.name + "' is listed twice");
    Contact c;
    c.config = config;
    try {
      c.stepper = std::make_unique<ContactStepper>(makeContactModel(config.parameters),
                                                   config.options, config.parameters);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(config.name + "/" + e.what());
    }
    index_[config.name] = static_cast<int>(contacts_.size());
    contacts_.push_back(std::move(c));
  }
  seen_.assign(contacts_.size(), 0);
}

int VehicleStepper::find(const std::string& name) const {
  const auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

void VehicleStepper::countHeld(Contact* c, VehicleContactResult* r) {
  r->held = r->step.held;
  if (r->held) ++c->counters.held;
}

void VehicleStepper::step(int64_t stampNs, const std::vector<VehicleContactInput>& in,
                          std::vector<VehicleContactResult>* out) {
  ++counters_.ticks;
  out->clear();
  std::fill(seen_.begin(), seen_.end(), 0);
  for (const auto& entry : in) {
    const int i = find(entry.name);
    if (i >= 0) ++seen_[i];
  }
  for (const auto& entry : in) {
    VehicleContactResult r;
    r.contact = find(entry.name);
    StepResult& s = r.step;
    if (r.contact < 0) {
      r.event = VehicleEvent::kUnknownName;
      s.out.status = StepStatus::kRejected;
      s.message = "unknown contact '" + entry.name + "'";
      ++counters_.unknownNames;
      out->push_back(std::move(r));
      continue;
    }
    Contact& c = contacts_[r.contact];
    if (seen_[r.contact] > 1) {
      r.event = VehicleEvent::kDuplicate;
      s = c.stepper->refuse("contact '" + entry.name + "' appears " +
                                std::to_string(seen_[r.contact]) +
                                " times in the input: not stepped",
                            entry.in.fz);
      ++c.counters.duplicate;
    } else {
      s = c.stepper->stepWithLoad(stampNs, entry.in, {entry.curvatureX, entry.curvatureY});
      if (s.event == StepEvent::kBadGeometry) {
        r.event = VehicleEvent::kBadGeometry;
        ++c.counters.badGeometry;
      }
    }
    countHeld(&c, &r);
    out->push_back(std::move(r));
  }
  for (size_t i = 0; i < contacts_.size(); ++i) {
    if (seen_[i] > 0) continue;
    Contact& c = contacts_[i];
    VehicleContactResult r;
    r.contact = static_cast<int>(i);
    r.event = VehicleEvent::kMissing;
    r.step = c.stepper->refuse("contact '" + c.config.name + "' is missing from the input", 0.0);
    ++c.counters.missing;
    countHeld(&c, &r);
    out->push_back(std::move(r));
  }
}

void VehicleStepper::reset() {
  for (auto& c : contacts_) c.stepper->reset();
}

}  // namespace wheel_rail_contact
