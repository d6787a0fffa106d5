#include "contact_stepper.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

namespace {

constexpr int64_t kNoForce = std::numeric_limits<int64_t>::min();

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

/// "" if the optional per-step geometry and friction are usable, else why (rules in
/// doc/ros_interface.md): each >= 0 and finite (0 = not given), a with b, A with B, never both.
std::string checkGeometry(const StepInput& in, const GapCurvatures& k) {
  const struct {
    const char* name;
    double v;
  } fields[] = {
      {"a", in.a}, {"b", in.b}, {"curvature_x", k.A}, {"curvature_y", k.B}, {"mu", in.mu}};
  for (const auto& f : fields) {
    if (!std::isfinite(f.v)) return std::string(f.name) + " is not finite";
    if (f.v < 0.0) return std::string(f.name) + " is negative (0 = not given)";
    if (f.v > kMaxInputMagnitude) return std::string(f.name) + " exceeds 1e12 in magnitude";
  }
  if ((in.a > 0.0) != (in.b > 0.0)) return "a and b must be given together (or both 0)";
  if ((k.A > 0.0) != (k.B > 0.0))
    return "curvature_x and curvature_y must be given together (or both 0)";
  if (in.a > 0.0 && k.A > 0.0)
    return "both a, b and curvature_x, curvature_y given: give the semi-axes or the curvatures";
  return {};
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

std::string frameIdForNamespace(const std::string& ns) {
  std::string id;
  for (char c : ns) {
    if (c != '/')
      id += c;
    else if (!id.empty() && id.back() != '_')
      id += '_';
  }
  if (!id.empty() && id.back() != '_') id += '_';
  return id + "contact";
}

const char* toString(LoadPairing p) {
  return p == LoadPairing::kStamp ? "stamp" : "latest";
}

LoadPairing parseLoadPairing(const std::string& text) {
  if (text == "stamp") return LoadPairing::kStamp;
  if (text == "latest") return LoadPairing::kLatest;
  throw std::invalid_argument("load_pairing: must be stamp or latest, got '" + text + "'");
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
  if (!(o.load_wait >= 0.0 && o.load_wait <= 60.0))
    throw std::invalid_argument("load_wait: must be in [0, 60] s" + got(o.load_wait));
  if (o.pairing_buffer < 1)
    throw std::invalid_argument("pairing_buffer: must be >= 1" + got(o.pairing_buffer));
}

ContactStepper::ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options)
    : model_(std::move(model)), options_(options) {
  validate(options_);
  if (!model_) throw std::invalid_argument("model: no model given");
}

ContactStepper::ContactStepper(std::unique_ptr<ContactModel> model, const StepperOptions& options,
                               const ContactParameters& material)
    : ContactStepper(std::move(model), options) {
  validate(material);
  hasMaterial_ = true;
  G_ = material.G;
  nu_ = material.nu;
}

// ---- loads --------------------------------------------------------------------------------------

bool ContactStepper::sameTimeLine(int64_t laterNs, int64_t earlierNs) const {
  // With time_jump_reset on, stamps further apart than it belong to different runs.
  return options_.time_jump_reset <= 0.0 ||
         static_cast<double>(laterNs - earlierNs) * 1e-9 <= options_.time_jump_reset;
}

bool ContactStepper::storeLoad(int64_t stampNs, double fz) {
  Load l{true, fz, stampNs, ++seq_};
  if (stampNs == 0) {
    unstamped_ = l;
    latest_ = l;
    return true;
  }
  if (hasStampedLoad_ && stampNs < newestLoadStampNs_) {
    if (sameTimeLine(newestLoadStampNs_, stampNs)) return false;
    // A backwards jump (simulator restarted, bag looped): the old run's loads pair with nothing
    // of the new one. Its creepages still waiting are answered from the old loads first.
    if (options_.load_pairing == LoadPairing::kStamp) {
      while (!pending_.empty() && !sameTimeLine(pending_.front().stampNs, stampNs)) {
        Choice c = fallback(pending_.front().stampNs);
        c.why = "the loads jumped back in time";
        ++counters_.unmatchedLaterLoad;
        stepFront(c);
      }
      loads_.clear();
    }
  }
  if (options_.load_pairing == LoadPairing::kStamp) {
    if (!loads_.empty() && loads_.back().stampNs == stampNs)
      loads_.back() = l;  // equal stamp: the later message replaces
    else
      loads_.push_back(l);
    while (loads_.size() > static_cast<size_t>(options_.pairing_buffer) + 1) loads_.pop_front();
  }
  hasStampedLoad_ = true;
  newestLoadStampNs_ = stampNs;
  latest_ = l;
  return true;
}

std::string ContactStepper::addLoad(int64_t stampNs, double fz, int64_t nowNs) {
  if (!std::isfinite(fz)) {
    ++counters_.loadsRejected;
    return "normal load is not finite";
  }
  const int64_t newest = newestLoadStampNs_;
  if (!storeLoad(stampNs, fz)) {
    ++counters_.loadsRejected;
    ++counters_.loadsOutOfOrder;
    return "normal load stamp " + seconds(stampNs) + " is older than the latest load's (" +
           seconds(newest) + ")";
  }
  ++counters_.loads;
  if (stampNs == 0) ++counters_.loadsUnstamped;
  releaseReady(nowNs, true, kNoForce);
  return {};
}

// ---- pairing ------------------------------------------------------------------------------------

const ContactStepper::Load* ContactStepper::exactLoad(int64_t stampNs) const {
  for (auto it = loads_.rbegin(); it != loads_.rend(); ++it) {
    if (it->stampNs == stampNs) return &*it;
    if (it->stampNs < stampNs) break;
  }
  return nullptr;
}

ContactStepper::Choice ContactStepper::fallback(int64_t stampNs) const {
  // The latest load at this stamp: the newest stamped load not after it, or the unstamped load
  // if that came later. Never a load stamped after the creepage.
  Choice c;
  const Load* stamped = nullptr;
  for (auto it = loads_.rbegin(); it != loads_.rend() && !stamped; ++it)
    if (it->stampNs <= stampNs) stamped = &*it;
  if (stamped && (!unstamped_.valid || stamped->seq > unstamped_.seq))
    c.load = *stamped;
  else if (unstamped_.valid)
    c.load = unstamped_;
  c.match = c.load.valid ? LoadMatch::kUnmatched : LoadMatch::kNone;
  return c;
}

void ContactStepper::addCreepage(int64_t stampNs, const StepInput& in, int64_t nowNs,
                                 const GapCurvatures& curvatures) {
  if (options_.load_pairing == LoadPairing::kLatest || stampNs == 0) {
    // Stepped at once; an unstamped creepage has no stamp to wait for.
    releaseReady(nowNs, true, stampNs == 0 ? std::numeric_limits<int64_t>::max() : kNoForce);
    Choice c;
    c.load = latest_;
    c.match = latest_.valid ? LoadMatch::kLatest : LoadMatch::kNone;
    ready_.push_back(stepImpl(stampNs, in, curvatures, c));
    return;
  }
  const int64_t wait = static_cast<int64_t>(std::llround(options_.load_wait * 1e9));
  pending_.push_back({stampNs, in, curvatures, nowNs + wait});
  if (pending_.size() > counters_.pendingMax) counters_.pendingMax = pending_.size();
  releaseReady(nowNs, true, kNoForce);
}

void ContactStepper::release(int64_t nowNs) {
  releaseReady(nowNs, true, kNoForce);
}

void ContactStepper::releaseReady(int64_t nowNs, bool useDeadline, int64_t forceUpToNs) {
  while (!pending_.empty()) {
    const Pending& p = pending_.front();
    if (const Load* l = exactLoad(p.stampNs)) {
      Choice c;
      c.load = *l;
      c.match = LoadMatch::kSameStamp;
      stepFront(c);
      continue;
    }
    const char* why = nullptr;
    if (hasStampedLoad_ && newestLoadStampNs_ > p.stampNs &&
        sameTimeLine(newestLoadStampNs_, p.stampNs)) {
      why = "a load with a later stamp came first";
      ++counters_.unmatchedLaterLoad;
    } else if (pending_.size() > static_cast<size_t>(options_.pairing_buffer)) {
      why = "pairing buffer full";
      ++counters_.unmatchedBufferFull;
    } else if (useDeadline && nowNs >= p.deadlineNs) {
      why = "none within load_wait";
      ++counters_.unmatchedWaitExpired;
    } else if (p.stampNs <= forceUpToNs) {
      why = "a later input came first";
      ++counters_.unmatchedLaterLoad;
    } else {
      break;
    }
    Choice c = fallback(p.stampNs);
    c.why = why;
    stepFront(c);
  }
}

void ContactStepper::stepFront(Choice c) {
  const Pending p = pending_.front();
  pending_.pop_front();
  if (c.match == LoadMatch::kUnmatched || (c.match == LoadMatch::kNone && !c.why.empty()))
    ++counters_.unmatched;
  ready_.push_back(stepImpl(p.stampNs, p.in, p.curvatures, c));
  // Loads older than the newest one not after this stamp can no longer pair with anything.
  while (loads_.size() >= 2 && loads_[1].stampNs <= p.stampNs) loads_.pop_front();
}

bool ContactStepper::nextDeadline(int64_t* nowNs) const {
  if (pending_.empty()) return false;
  *nowNs = pending_.front().deadlineNs;
  return true;
}

std::vector<StepResult> ContactStepper::takeReady() {
  std::vector<StepResult> out;
  out.swap(ready_);
  return out;
}

// ---- stepping -----------------------------------------------------------------------------------

StepResult ContactStepper::stepWithLoad(int64_t stampNs, const StepInput& in,
                                        const GapCurvatures& curvatures) {
  if (std::isfinite(in.fz)) {
    storeLoad(stampNs, in.fz);
    // Creepages still waiting with an older stamp belong before this step.
    releaseReady(0, false, stampNs);
  }
  Choice c;  // a non-finite fz is kept here so that the step is rejected for it
  c.load = Load{true, in.fz, stampNs, seq_};
  c.match = LoadMatch::kSameStamp;
  return stepImpl(stampNs, in, curvatures, c);
}

StepResult ContactStepper::stepWithLoad(int64_t stampNs, double V, double xi, double eta,
                                        double phi, double fz) {
  StepInput in;
  in.V = V;
  in.xi = xi;
  in.eta = eta;
  in.phi = phi;
  in.fz = fz;
  return stepWithLoad(stampNs, in);
}

StepResult ContactStepper::refuse(std::string why, double load) {
  StepResult r;
  r.out.status = StepStatus::kRejected;
  r.message = std::move(why);
  return finish(r, load);
}

StepResult ContactStepper::stepImpl(int64_t stampNs, const StepInput& input, const GapCurvatures& k,
                                    const Choice& paired) {
  ++counters_.creepages;
  Choice choice = paired;
  StepResult r;
  r.stampNs = stampNs;
  StepInput in = input;
  in.dt = 0.0;
  in.fz = choice.load.valid ? choice.load.fz : 0.0;
  r.loadMatch = choice.match;
  r.loadStampNs = choice.load.valid ? choice.load.stampNs : 0;
  const std::string geometry = checkGeometry(in, k);
  if (!geometry.empty() || (k.A > 0.0 && !hasMaterial_)) {
    r.event = StepEvent::kBadGeometry;
    r.out.status = StepStatus::kRejected;
    r.message = !geometry.empty() ? geometry
                                  : "curvature_x, curvature_y: this stepper has no material (G, "
                                    "nu) for Hertz";
    ++counters_.badGeometry;
    return finish(r, in.fz);
  }
  // The geometry's own reasons (pairs, curvatures) first; the core screens the motion fields here
  // and the geometry's ranges in the model.
  StepInput motion = in;
  motion.a = motion.b = motion.mu = 0.0;
  const char* bad = checkStepInput(motion);
  if (*bad) {
    r.event = StepEvent::kNonFinite;
    r.out.status = StepStatus::kRejected;
    r.out.message = bad;
    ++counters_.nonFinite;
    return finish(r, in.fz);
  }
  int64_t diff = 0;
  if (hasStamp_) {
    diff = stampNs - lastStampNs_;
    if (diff <= 0) {
      const double back = static_cast<double>(-diff) * 1e-9;
      if (options_.time_jump_reset > 0.0 && back > options_.time_jump_reset) {
        // A backwards jump (simulator restarted, bag looped): start again from this message.
        resetState();
        ++counters_.timeJumpResets;
        r.timeJumpReset = true;
        // load_pairing latest: a load from the old run (stamped after this message) is dropped.
        if (latest_.valid && latest_.stampNs > stampNs) latest_ = Load{};
        if (choice.load.valid && choice.load.stampNs > stampNs) {
          choice.load = Load{};
          choice.match = LoadMatch::kNone;
          in.fz = 0.0;
          r.loadMatch = LoadMatch::kNone;
          r.loadStampNs = 0;
        }
      } else {
        r.event = StepEvent::kOutOfOrder;
        r.out.status = StepStatus::kRejected;
        r.message = "stamp " + seconds(stampNs) + " is not after the previous one (" +
                    seconds(lastStampNs_) + ")";
        ++counters_.outOfOrder;
        return finish(r, in.fz);
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
    return finish(r, in.fz);
  }
  hasStamp_ = true;
  lastStampNs_ = stampNs;
  in.dt = r.dt;
  if (k.A > 0.0 && in.fz >= kMinLoad) {
    // The patch of this step's load; below kMinLoad the model answers "no load" by itself.
    const HertzEllipse e = hertzFromCurvatures(in.fz, k.A, k.B, G_, nu_);
    in.a = e.a;
    in.b = e.b;
  }
  if (choice.load.valid && choice.load.stampNs != 0) {
    r.loadAge = static_cast<double>(stampNs - choice.load.stampNs) * 1e-9;
    r.staleLoad = options_.max_load_age > 0.0 && r.loadAge > options_.max_load_age;
    if (r.staleLoad) ++counters_.staleLoad;
  }
  const auto t0 = std::chrono::steady_clock::now();
  r.out = model_->step(in);
  r.solverTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!choice.load.valid) {
    r.event = StepEvent::kNoLoadYet;
    r.out.message = "no normal load for this step";
  } else if (r.out.status == StepStatus::kRejected) {
    ++counters_.rejectedByModel;
  }
  if (choice.match == LoadMatch::kUnmatched || (!choice.load.valid && !choice.why.empty())) {
    std::string note = "no normal load stamped " + seconds(stampNs) + " (" + choice.why + "): ";
    note += choice.load.valid ? (choice.load.stampNs != 0
                                     ? "the latest load, stamped " + seconds(choice.load.stampNs)
                                     : std::string("the latest (unstamped) load")) +
                                    ", used"
                              : std::string("no load at all");
    r.message = *r.out.message ? note + "; " + r.out.message : note;
  }
  return finish(r, in.fz);
}

StepResult ContactStepper::finish(StepResult r, double pairedLoad) {
  if (!finiteOutput(r.out)) {  // defensive: the model contract forbids it, the node never sends NaN
    r.out = StepOutput{};
    r.out.status = StepStatus::kRejected;
    r.out.message = "model returned a non-finite result";
    ++counters_.rejectedByModel;
  }
  if (r.message.empty()) r.message = r.out.message;
  if (r.out.status == StepStatus::kRejected) {
    // Never a force the simulator would apply by mistake: the last accepted answer, or before
    // any, no creep force on the load the simulator itself gave.
    const char* message = r.out.message;
    if (hasAccepted_) {
      r.out = accepted_;
      r.held = true;
    } else {
      r.out = StepOutput{};
      r.out.fz = std::isfinite(pairedLoad) && pairedLoad > 0.0 ? pairedLoad : 0.0;
    }
    r.out.status = StepStatus::kRejected;
    r.out.message = message;
  } else {
    hasAccepted_ = true;
    accepted_ = r.out;
  }
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
  // Every input gets its answer: what still waits for its load belongs to the run being reset.
  while (!pending_.empty()) {
    const Pending p = pending_.front();
    pending_.pop_front();
    ++counters_.creepages;
    StepResult r;
    r.stampNs = p.stampNs;
    r.event = StepEvent::kDroppedByReset;
    r.out.status = StepStatus::kRejected;
    r.message = "reset before the normal load stamped " + seconds(p.stampNs) + " arrived";
    ++counters_.droppedByReset;
    ready_.push_back(finish(r, 0.0));
  }
  resetState();
  clearLoads();
  ++counters_.resets;
}

void ContactStepper::resetState() {
  model_->reset();
  hasStamp_ = false;
  lastStampNs_ = 0;
  hasAccepted_ = false;
  accepted_ = StepOutput{};
}

void ContactStepper::clearLoads() {
  latest_ = Load{};
  unstamped_ = Load{};
  hasStampedLoad_ = false;
  newestLoadStampNs_ = 0;
  loads_.clear();
}

}  // namespace wheel_rail_contact
