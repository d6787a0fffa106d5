#include "contact_stepper.hpp"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

std::string seconds(int64_t ns) {
  std::ostringstream s;
  s.precision(12);
  s << static_cast<double>(ns) * 1e-9 << " s";
  return s.str();
}

bool finiteOutput(const StepOutput& o) {
  return std::isfinite(o.fx) && std::isfinite(o.fy) && std::isfinite(o.mz) && std::isfinite(o.fz) &&
         std::isfinite(o.a) && std::isfinite(o.b) && std::isfinite(o.adhesionFraction);
}

}  // namespace

uint8_t contactStateStatus(StepStatus s) {
  switch (s) {
    case StepStatus::kOk:
      return 0;
    case StepStatus::kNoLoad:
      return 1;
    case StepStatus::kStandstill:
      return 2;
    case StepStatus::kRejected:
      return 3;
    case StepStatus::kNotConverged:
      return 4;
  }
  return 3;
}

void validate(const StepperOptions& o) {
  auto got = [](double v) {
    std::ostringstream s;
    s << ", got " << v;
    return s.str();
  };
  if (!(o.max_dt > 0.0) || !std::isfinite(o.max_dt))
    throw std::invalid_argument("max_dt: must be a finite number > 0 s" + got(o.max_dt));
  if (!(o.time_jump_reset >= 0.0) || !std::isfinite(o.time_jump_reset))
    throw std::invalid_argument("time_jump_reset: must be a finite number >= 0 s (0 = off)" +
                                got(o.time_jump_reset));
  if (!(o.max_load_age >= 0.0) || !std::isfinite(o.max_load_age))
    throw std::invalid_argument("max_load_age: must be a finite number >= 0 s (0 = off)" +
                                got(o.max_load_age));
}

ContactStepper::ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options)
    : model_(std::move(model)), options_(options) {
  validate(options_);
  if (!model_) throw std::invalid_argument("model: no model given");
}

std::string ContactStepper::setLoad(int64_t stampNs, double fz) {
  if (!std::isfinite(fz)) {
    ++counters_.loadsRejected;
    return "normal load is not finite";
  }
  if (hasLoad_ && stampNs < loadStampNs_) {
    const double back = static_cast<double>(loadStampNs_ - stampNs) * 1e-9;
    const bool jump = options_.time_jump_reset > 0.0 && back > options_.time_jump_reset;
    if (!jump) {
      ++counters_.loadsRejected;
      ++counters_.loadsOutOfOrder;
      return "normal load stamp " + seconds(stampNs) + " is older than the latest load's (" +
             seconds(loadStampNs_) + ")";
    }
  }
  load_ = fz;
  loadStampNs_ = stampNs;
  hasLoad_ = true;
  ++counters_.loads;
  return {};
}

StepResult ContactStepper::step(int64_t stampNs, double V, double xi, double eta, double phi) {
  return stepImpl(stampNs, {0.0, V, xi, eta, phi, 0.0}, false);
}

StepResult ContactStepper::stepWithLoad(int64_t stampNs, double V, double xi, double eta,
                                        double phi, double fz) {
  return stepImpl(stampNs, {0.0, V, xi, eta, phi, fz}, true);
}

StepResult ContactStepper::stepWithLoad(int64_t stampNs, const StepInput& in) {
  return stepImpl(stampNs, in, true);
}

StepResult ContactStepper::stepImpl(int64_t stampNs, const StepInput& input, bool loadGiven) {
  ++counters_.creepages;
  StepResult r;
  StepInput in = input;
  const char* bad = checkStepInput(in);
  if (*bad) {
    r.event = StepEvent::kNonFinite;
    r.out.status = StepStatus::kRejected;
    r.out.message = bad;
    ++counters_.nonFinite;
    return finish(r);
  }
  int64_t diff = 0;
  if (hasStamp_) {
    diff = stampNs - lastStampNs_;
    if (diff <= 0) {
      const double back = static_cast<double>(-diff) * 1e-9;
      if (options_.time_jump_reset > 0.0 && back > options_.time_jump_reset) {
        // A backwards jump (simulator restarted, bag looped): start again from this message.
        const bool keepLoad = hasLoad_ && loadStampNs_ <= stampNs;
        const double load = load_;
        const int64_t loadStamp = loadStampNs_;
        resetState();
        ++counters_.timeJumpResets;
        r.timeJumpReset = true;
        if (keepLoad) {
          hasLoad_ = true;
          load_ = load;
          loadStampNs_ = loadStamp;
        }
      } else {
        r.event = StepEvent::kOutOfOrder;
        r.out.status = StepStatus::kRejected;
        r.message = "stamp " + seconds(stampNs) + " is not after the previous one (" +
                    seconds(lastStampNs_) + ")";
        ++counters_.outOfOrder;
        return finish(r);
      }
    }
  }
  r.dt = hasStamp_ ? static_cast<double>(diff) * 1e-9 : 0.0;
  if (r.dt > options_.max_dt) {
    r.event = StepEvent::kDtTooLarge;
    r.out.status = StepStatus::kRejected;
    std::ostringstream m;
    m << "dt = " << r.dt << " s exceeds max_dt = " << options_.max_dt
      << " s; the time base restarts at this message";
    r.message = m.str();
    lastStampNs_ = stampNs;
    ++counters_.dtTooLarge;
    return finish(r);
  }
  hasStamp_ = true;
  lastStampNs_ = stampNs;
  if (loadGiven) {
    load_ = in.fz;
    loadStampNs_ = stampNs;
    hasLoad_ = true;
  }
  in.dt = r.dt;
  in.fz = hasLoad_ ? load_ : 0.0;
  if (hasLoad_) {
    r.loadAge = static_cast<double>(stampNs - loadStampNs_) * 1e-9;
    r.staleLoad = options_.max_load_age > 0.0 && r.loadAge > options_.max_load_age;
    if (r.staleLoad) ++counters_.staleLoad;
  }
  const auto t0 = std::chrono::steady_clock::now();
  r.out = model_->step(in);
  r.solverTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!hasLoad_) {
    r.event = StepEvent::kNoLoadYet;
    r.out.message = "no normal load received yet";
  } else if (r.out.status == StepStatus::kRejected) {
    ++counters_.rejectedByModel;
  }
  return finish(r);
}

StepResult ContactStepper::finish(StepResult r) {
  if (!finiteOutput(r.out)) {  // defensive: the model contract forbids it, the node never sends NaN
    r.out = StepOutput{};
    r.out.status = StepStatus::kRejected;
    r.out.message = "model returned a non-finite result";
    ++counters_.rejectedByModel;
  }
  if (r.message.empty()) r.message = r.out.message;
  switch (r.out.status) {
    case StepStatus::kOk:
      ++counters_.ok;
      break;
    case StepStatus::kNoLoad:
      ++counters_.noLoad;
      break;
    case StepStatus::kStandstill:
      ++counters_.standstill;
      break;
    case StepStatus::kRejected:
      ++counters_.rejected;
      break;
    case StepStatus::kNotConverged:
      ++counters_.notConverged;
      break;
  }
  counters_.solverTimeLast = r.solverTime;
  counters_.solverTimeSum += r.solverTime;
  if (r.solverTime > counters_.solverTimeMax) counters_.solverTimeMax = r.solverTime;
  return r;
}

void ContactStepper::reset() {
  resetState();
  ++counters_.resets;
}

void ContactStepper::resetState() {
  model_->reset();
  hasStamp_ = false;
  lastStampNs_ = 0;
  hasLoad_ = false;
  loadStampNs_ = 0;
  load_ = 0.0;
}

}  // namespace wheel_rail_contact
