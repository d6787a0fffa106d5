#include "wheelset_stepper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace wheel_rail_contact {

const char* toString(WheelsetEvent e) {
  switch (e) {
    case WheelsetEvent::kStepped:
      return "stepped";
    case WheelsetEvent::kUnknownName:
      return "unknown_name";
    case WheelsetEvent::kDuplicate:
      return "duplicate";
    case WheelsetEvent::kMissing:
      return "missing";
    case WheelsetEvent::kNonFinite:
      return "non_finite";
    case WheelsetEvent::kOutOfOrder:
      return "out_of_order";
    case WheelsetEvent::kDtTooLarge:
      return "dt_too_large";
  }
  return "unknown";
}

namespace {

std::string seconds(int64_t ns) {
  std::ostringstream s;
  s.precision(9);
  s << std::fixed << static_cast<double>(ns) * 1e-9 << " s";
  return s.str();
}

bool finiteEntry(const WheelsetEntry& e) {
  const WheelsetPose& p = e.state.pose;
  const WheelsetMotion& m = e.state.motion;
  for (double v : {p.y, p.yaw, p.roll, m.V, m.omega, m.vy, m.yaw_rate, m.curvature, m.cant, m.vz,
                   m.roll_rate, e.state.fz_left, e.state.fz_right})
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

WheelsetStepper::WheelsetStepper(WheelsetStepperConfig config) : config_(std::move(config)) {
  if (config_.names.empty()) throw std::invalid_argument("wheelsets: the list is empty");
  if (!(config_.max_dt > 0.0) || !std::isfinite(config_.max_dt))
    throw std::invalid_argument("max_dt: must be a finite number > 0 s");
  if (!(config_.threads >= 1 && config_.threads <= 16))
    throw std::invalid_argument("threads: must be in [1, 16], got " +
                                std::to_string(config_.threads));
  if (!(config_.time_jump_reset >= 0.0) || !std::isfinite(config_.time_jump_reset))
    throw std::invalid_argument("time_jump_reset: must be a finite number >= 0 s (0 = off)");
  for (const auto& n : config_.names) {
    if (n.empty()) throw std::invalid_argument("wheelsets: an empty name");
    if (index_.count(n)) throw std::invalid_argument("wheelsets: '" + n + "' is listed twice");
    index_[n] = static_cast<int>(index_.size());
  }
  config_.track.validate();
  validate(config_.parameters);
  WheelsetContactOptions options = config_.options;
  if (!options.contact_table && options.use_contact_table)
    options.contact_table = std::make_shared<const ContactTable>(
        ContactSearch(config_.track, options.search), options.table);
  table_ = options.contact_table;
  for (size_t i = 0; i < config_.names.size(); ++i) {
    Wheelset w;
    w.contact = std::make_unique<WheelsetContact>(config_.track, config_.parameters, options);
    w.accepted[0].side = WheelSide::kLeft;
    w.accepted[1].side = WheelSide::kRight;
    wheelsets_.push_back(std::move(w));
  }
  seen_.assign(wheelsets_.size(), 0);
}

int WheelsetStepper::find(const std::string& name) const {
  const auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

void WheelsetStepper::refuse(Wheelset* w, WheelsetEvent event, std::string message,
                             WheelsetAnswer* a) {
  a->event = event;
  a->message = message;
  for (int side = 0; side < 2; ++side) {
    WheelAnswer& wa = side == 0 ? a->left : a->right;
    wa.status = WheelAnswerStatus::kRejected;
    wa.message = message;
    wa.held = true;
    wa.result = w->accepted[side];
    ++w->counters.held;
  }
}

void WheelsetStepper::answerWheel(Wheelset* w, int side, WheelResult result, WheelAnswer* a) {
  WheelsetCounters& c = w->counters;
  switch (result.status) {
    case WheelStatus::kOk:
      a->status = WheelAnswerStatus::kOk;
      break;
    case WheelStatus::kNoLoad:
      a->status = WheelAnswerStatus::kNoLoad;
      ++c.no_load;
      break;
    case WheelStatus::kNoContact:
      a->status = WheelAnswerStatus::kNoContact;
      ++c.no_contact;
      break;
    case WheelStatus::kInvalidInput:
      a->status = WheelAnswerStatus::kInvalidInput;
      ++c.invalid_input;
      break;
    case WheelStatus::kNormalFailed:
      a->status = WheelAnswerStatus::kNormalFailed;
      ++c.normal_failed;
      break;
  }
  a->message = result.message;
  // A patch without tangential forces (its model refused the step, or no creepages) would give the
  // wheel a made-up total: the wheel is held instead, naming the patch.
  if (a->status == WheelAnswerStatus::kOk)
    for (const PatchResult& p : result.patches) {
      if (p.tangential_status != StepStatus::kRejected &&
          p.creepages.status != CreepageStatus::kInvalidInput)
        continue;
      a->status = WheelAnswerStatus::kPatchRejected;
      a->message = p.slot + ": " + p.message;
      ++c.patch_rejected;
      break;
    }
  if (a->status == WheelAnswerStatus::kOk && a->message.empty())
    for (const PatchResult& p : result.patches)
      if (!p.message.empty()) {  // an ok step's note (the fixed mesh grew, a coarse patch)
        a->message = p.slot + ": " + p.message;
        break;
      }
  const bool accepted =
      a->status == WheelAnswerStatus::kOk || a->status == WheelAnswerStatus::kNoLoad;
  a->held = !accepted;
  if (accepted) {
    w->accepted[side] = result;
    a->result = std::move(result);
  } else {
    a->result = w->accepted[side];
    ++c.held;
  }
}

void WheelsetStepper::step(int64_t stamp_ns, const std::vector<WheelsetEntry>& in,
                           std::vector<WheelsetAnswer>* out) {
  ++counters_.ticks;
  out->clear();
  pending_.clear();
  std::fill(seen_.begin(), seen_.end(), 0);
  for (const auto& e : in) {
    const int i = find(e.name);
    if (i >= 0) ++seen_[i];
  }
  for (const auto& e : in) {
    WheelsetAnswer a;
    a.wheelset = find(e.name);
    if (a.wheelset < 0) {
      a.event = WheelsetEvent::kUnknownName;
      a.message = "unknown wheelset '" + e.name + "'";
      for (WheelAnswer* wa : {&a.left, &a.right}) {
        wa->status = WheelAnswerStatus::kRejected;
        wa->message = a.message;
      }
      a.left.result.side = WheelSide::kLeft;
      ++counters_.unknown_names;
      out->push_back(std::move(a));
      continue;
    }
    Wheelset& w = wheelsets_[a.wheelset];
    WheelsetCounters& c = w.counters;
    if (seen_[a.wheelset] > 1) {
      refuse(&w, WheelsetEvent::kDuplicate,
             "wheelset '" + e.name + "' appears " + std::to_string(seen_[a.wheelset]) +
                 " times in the input: not stepped",
             &a);
      ++c.duplicate;
      out->push_back(std::move(a));
      continue;
    }
    if (!finiteEntry(e)) {
      refuse(&w, WheelsetEvent::kNonFinite, "a value of the wheelset's state is not finite", &a);
      ++c.non_finite;
      out->push_back(std::move(a));
      continue;
    }
    if (w.has_stamp && stamp_ns <= w.last_stamp_ns) {
      const double back = static_cast<double>(w.last_stamp_ns - stamp_ns) * 1e-9;
      if (config_.time_jump_reset > 0.0 && back > config_.time_jump_reset) {
        // A backwards jump (simulator restarted, bag looped): start again from this entry.
        w.contact->reset();
        w.has_stamp = false;
        a.time_jump_reset = true;
        ++c.time_jump_resets;
      } else {
        refuse(&w, WheelsetEvent::kOutOfOrder,
               "stamp " + seconds(stamp_ns) + " is not after the previous one (" +
                   seconds(w.last_stamp_ns) + ")",
               &a);
        ++c.out_of_order;
        out->push_back(std::move(a));
        continue;
      }
    }
    const double dt = w.has_stamp ? static_cast<double>(stamp_ns - w.last_stamp_ns) * 1e-9 : 0.0;
    w.has_stamp = true;
    w.last_stamp_ns = stamp_ns;
    if (dt > config_.max_dt) {
      std::ostringstream m;
      m << "dt = " << dt << " s exceeds max_dt = " << config_.max_dt
        << " s; the time base restarts at this stamp";
      refuse(&w, WheelsetEvent::kDtTooLarge, m.str(), &a);
      ++c.dt_too_large;
      out->push_back(std::move(a));
      continue;
    }
    a.dt = dt;
    pending_.push_back({out->size(), a.wheelset, &e.state, dt, {}, 0.0});
    out->push_back(std::move(a));
  }
  stepPending();
  for (Pending& p : pending_) {
    Wheelset& w = wheelsets_[p.wheelset];
    WheelsetCounters& c = w.counters;
    WheelsetAnswer& a = (*out)[p.out];
    a.solver_time = p.time;
    ++c.steps;
    c.solver_time_sum += p.time;
    c.solver_time_max = std::max(c.solver_time_max, p.time);
    answerWheel(&w, 0, std::move(p.result.left), &a.left);
    answerWheel(&w, 1, std::move(p.result.right), &a.right);
  }
  for (size_t i = 0; i < wheelsets_.size(); ++i) {
    if (seen_[i] > 0) continue;
    Wheelset& w = wheelsets_[i];
    WheelsetAnswer a;
    a.wheelset = static_cast<int>(i);
    refuse(&w, WheelsetEvent::kMissing,
           "wheelset '" + config_.names[i] + "' is missing from the input", &a);
    ++w.counters.missing;
    out->push_back(std::move(a));
  }
}

void WheelsetStepper::stepPending() {
  const auto run = [this](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      Pending& p = pending_[k];
      const auto t0 = std::chrono::steady_clock::now();
      p.result = wheelsets_[p.wheelset].contact->step(*p.state, p.dt);
      p.time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  };
  const size_t n = pending_.size();
  const size_t chunks = std::min(n, static_cast<size_t>(config_.threads));
  if (chunks <= 1) {
    run(0, n);
    return;
  }
  // Each wheelset once at most among the pending (a repeated name is refused), so no two threads
  // share a WheelsetContact; the contact table is only read.
  std::vector<std::future<void>> others;
  for (size_t t = 1; t < chunks; ++t)
    others.push_back(std::async(std::launch::async, run, t * n / chunks, (t + 1) * n / chunks));
  run(0, n / chunks);
  for (auto& f : others) f.get();
}

void WheelsetStepper::reset() {
  for (auto& w : wheelsets_) {
    w.contact->reset();
    w.has_stamp = false;
    w.last_stamp_ns = 0;
    w.accepted[0] = WheelResult{};
    w.accepted[0].side = WheelSide::kLeft;
    w.accepted[1] = WheelResult{};
    w.accepted[1].side = WheelSide::kRight;
    ++w.counters.resets;
  }
}

}  // namespace wheel_rail_contact
