#include "vehicle_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

namespace {

/// "" if an optional field (0 = not given) is usable, else why not.
std::string checkOptional(const char* field, double v) {
  if (!std::isfinite(v)) return std::string(field) + " is not finite";
  if (v < 0.0) return std::string(field) + " is negative (0 = not given)";
  if (v > kMaxInputMagnitude) return std::string(field) + " exceeds 1e12 in magnitude (SI units)";
  return {};
}

}  // namespace

std::string resolveGeometry(const VehicleContactInput& entry, const ContactParameters& p,
                            StepInput* in) {
  const struct {
    const char* field;
    double value;
  } optional[] = {{"a", entry.in.a},
                  {"b", entry.in.b},
                  {"mu", entry.in.mu},
                  {"curvature_x", entry.curvatureX},
                  {"curvature_y", entry.curvatureY}};
  for (const auto& o : optional) {
    std::string why = checkOptional(o.field, o.value);
    if (!why.empty()) return why;
  }
  const bool ab = entry.in.a > 0.0 || entry.in.b > 0.0;
  const bool curvatures = entry.curvatureX > 0.0 || entry.curvatureY > 0.0;
  if (ab && !(entry.in.a > 0.0 && entry.in.b > 0.0))
    return "a and b are given together (one of them is 0)";
  if (curvatures && !(entry.curvatureX > 0.0 && entry.curvatureY > 0.0))
    return "curvature_x and curvature_y are given together (one of them is 0)";
  if (ab && curvatures) return "give the patch as a, b or as curvature_x, curvature_y, not both";
  *in = entry.in;
  if (curvatures && std::isfinite(in->fz) && in->fz >= kMinLoad) {
    try {
      const HertzEllipse h =
          hertzFromCurvatures(in->fz, entry.curvatureX, entry.curvatureY, p.G, p.nu);
      in->a = h.a;
      in->b = h.b;
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    if (!(std::isfinite(in->a) && std::isfinite(in->b) && in->a > 0.0 && in->b > 0.0))
      return "curvature_x, curvature_y give no finite Hertz patch";
  }
  return {};
}

VehicleStepper::VehicleStepper(const std::vector<VehicleContactConfig>& contacts) {
  if (contacts.empty()) throw std::invalid_argument("contacts: the list is empty");
  for (const auto& config : contacts) {
    if (config.name.empty()) throw std::invalid_argument("contacts: an empty name");
    if (index_.count(config.name))
      throw std::invalid_argument("contacts: '" + config.name + "' is listed twice");
    Contact c;
    c.config = config;
    try {
      c.stepper =
          std::make_unique<ContactStepper>(makeContactModel(config.parameters), config.options);
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

void VehicleStepper::settle(Contact* c, VehicleContactResult* r) {
  StepOutput& out = r->step.out;
  if (out.status != StepStatus::kRejected) {
    c->lastAccepted = out;
    return;
  }
  // Not zero: a simulator applying the wrench directly would see a force spike.
  const StepOutput& h = c->lastAccepted;
  out.fx = h.fx;
  out.fy = h.fy;
  out.fz = h.fz;
  out.mz = h.mz;
  out.a = h.a;
  out.b = h.b;
  out.adhesionFraction = h.adhesionFraction;
  r->held = true;
  ++c->counters.held;
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
    StepInput stepIn;
    std::string why;
    if (seen_[r.contact] > 1) {
      r.event = VehicleEvent::kDuplicate;
      why = "contact '" + entry.name + "' appears " + std::to_string(seen_[r.contact]) +
            " times in the input: not stepped";
      ++c.counters.duplicate;
    } else {
      why = resolveGeometry(entry, c.config.parameters, &stepIn);
      if (!why.empty()) {
        r.event = VehicleEvent::kBadGeometry;
        ++c.counters.badGeometry;
      }
    }
    if (r.event == VehicleEvent::kStepped) {
      s = c.stepper->stepWithLoad(stampNs, stepIn);
    } else {
      s.out.status = StepStatus::kRejected;
      s.message = std::move(why);
    }
    settle(&c, &r);
    out->push_back(std::move(r));
  }
  for (size_t i = 0; i < contacts_.size(); ++i) {
    if (seen_[i] > 0) continue;
    VehicleContactResult r;
    r.contact = static_cast<int>(i);
    r.event = VehicleEvent::kMissing;
    r.step.out.status = StepStatus::kRejected;
    r.step.message = "contact '" + contacts_[i].config.name + "' is missing from the input";
    ++contacts_[i].counters.missing;
    settle(&contacts_[i], &r);
    out->push_back(std::move(r));
  }
}

void VehicleStepper::reset() {
  for (auto& c : contacts_) {
    c.stepper->reset();
    c.lastAccepted = StepOutput{};
  }
}

}  // namespace wheel_rail_contact
