#include "contact_node.hpp"

#include <geometry_msgs/WrenchStamped.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <vector>

#include "../cli/config_yaml.hpp"
#include "ros_conversions.hpp"
#include "wheel_rail_contact/ContactState.h"

namespace wheel_rail_contact {

static_assert(ContactState::STATUS_OK == 0 && ContactState::STATUS_NO_LOAD == 1 &&
                  ContactState::STATUS_STANDSTILL == 2 && ContactState::STATUS_REJECTED == 3,
              "contactStateStatus() follows ContactState.msg");
static_assert(ContactState::LOAD_SAME_STAMP == static_cast<int>(LoadMatch::kSameStamp) &&
                  ContactState::LOAD_LATEST == static_cast<int>(LoadMatch::kLatest) &&
                  ContactState::LOAD_UNMATCHED == static_cast<int>(LoadMatch::kUnmatched) &&
                  ContactState::LOAD_NONE == static_cast<int>(LoadMatch::kNone),
              "LoadMatch follows ContactState.msg");

namespace {

int64_t steadyNowNs() {
  return static_cast<int64_t>(ros::SteadyTime::now().toNSec());
}

/// A header stamp in ns; 0 (unstamped) stays 0.
int64_t stampNs(const ros::Time& t) {
  return static_cast<int64_t>(t.toNSec());
}

double numberParameter(const ros::NodeHandle& pnh, const std::string& name, double value) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return value;
  const std::string text = parameterText(name, v);
  char* end = nullptr;
  const double d = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw std::invalid_argument(name + ": expected a number, got '" + text + "'");
  return d;
}

int countParameter(const ros::NodeHandle& pnh, const std::string& name, int value) {
  const double d = numberParameter(pnh, name, value);
  char v[64];
  std::snprintf(v, sizeof v, "%g", d);
  if (!(d >= 1.0 && d <= 1e6) || d != static_cast<int>(d))
    throw std::invalid_argument(name + ": must be an integer in [1, 1000000], got " + v);
  return static_cast<int>(d);
}

}  // namespace

ContactNode::ContactNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh) {}

bool ContactNode::readParameters() {
  try {
    // Unknown private keys fail, as unknown options and YAML keys do in contact_cli.
    std::set<std::string> known;
    for (const auto& d : parameterDocs()) known.insert(d.name);
    for (const auto& d : nodeParameterDocs()) known.insert(d.name);
    std::vector<std::string> all;
    ros::param::getParamNames(all);
    const std::string prefix = pnh_.getNamespace() + "/";
    for (const auto& name : all) {
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string key =
          name.substr(prefix.size(), name.find('/', prefix.size()) - prefix.size());
      if (!known.count(key)) throw std::invalid_argument(key + ": unknown parameter");
    }

    ContactParameters p;
    for (const auto& d : parameterDocs()) {
      XmlRpc::XmlRpcValue v;
      if (pnh_.getParam(d.name, v)) setParameter(&p, d.name, parameterText(d.name, v));
    }
    validate(p);

    StepperOptions o;
    o.max_dt = numberParameter(pnh_, "max_dt", o.max_dt);
    o.time_jump_reset = numberParameter(pnh_, "time_jump_reset", o.time_jump_reset);
    o.max_load_age = numberParameter(pnh_, "max_load_age", o.max_load_age);
    o.load_wait = numberParameter(pnh_, "load_wait", o.load_wait);
    XmlRpc::XmlRpcValue pairing;
    if (pnh_.getParam("load_pairing", pairing))
      o.load_pairing = parseLoadPairing(parameterText("load_pairing", pairing));
    XmlRpc::XmlRpcValue frame;
    frameId_ = frameIdForNamespace(nh_.getNamespace());
    if (pnh_.getParam("frame_id", frame)) frameId_ = parameterText("frame_id", frame);
    if (frameId_.empty()) throw std::invalid_argument("frame_id: must not be empty");
    queueSize_ = countParameter(pnh_, "queue_size", queueSize_);
    o.pairing_buffer = queueSize_;
    validate(o);
    publishQueueSize_ = countParameter(pnh_, "publish_queue_size", publishQueueSize_);
    diagnosticPeriod_ = numberParameter(pnh_, "diagnostic_period", diagnosticPeriod_);
    // ros::(Wall)Duration throws beyond 2^31 s (see start()); a day is plenty.
    if (!(diagnosticPeriod_ > 0.0 && diagnosticPeriod_ <= 86400.0)) {
      char v[64];
      std::snprintf(v, sizeof v, "%g", diagnosticPeriod_);
      throw std::invalid_argument(std::string("diagnostic_period: must be in (0, 86400] s, got ") +
                                  v);
    }

    stepper_ = std::make_unique<ContactStepper>(makeContactModel(p), o, p);
    ROS_INFO(
        "contact_node %s: model %s (%s), G %g Pa, nu %g, mu %g, a0 %g m, b0 %g m, fz0 %g N, "
        "mesh %s %dx%d, frame '%s', load pairing %s (load_wait %g s)",
        nh_.getNamespace().c_str(), p.model.c_str(), fastsimVariantName(p), p.G, p.nu, p.mu, p.a0,
        p.b0, p.fz0, p.mesh.c_str(), p.nx, p.ny, frameId_.c_str(), toString(o.load_pairing),
        o.load_wait);
    const std::string chosen = stepper_->modelChoices();
    if (!chosen.empty())
      ROS_INFO("contact_node %s: %s", nh_.getNamespace().c_str(), chosen.c_str());
    return true;
  } catch (const std::exception& e) {
    ROS_FATAL("contact_node: invalid parameter %s", e.what());
    return false;
  }
}

void ContactNode::start() {
  forcePub_ = nh_.advertise<geometry_msgs::WrenchStamped>("creep_force", publishQueueSize_);
  statePub_ = nh_.advertise<ContactState>("contact_state", publishQueueSize_);
  resetSrv_ = nh_.advertiseService("reset", &ContactNode::resetService, this);
  stepSrv_ = nh_.advertiseService("step", &ContactNode::stepService, this);
  const auto hints = ros::TransportHints().tcpNoDelay();
  loadSub_ = nh_.subscribe("normal_load", queueSize_, &ContactNode::loadCallback, this, hints);
  creepageSub_ = nh_.subscribe("creepage", queueSize_, &ContactNode::creepageCallback, this, hints);
  loadWaitTimer_ = nh_.createSteadyTimer(ros::WallDuration(1.0), &ContactNode::onLoadWait, this,
                                         true /*oneshot*/, false /*autostart*/);

  // Made only now: its constructor reads ~diagnostic_period itself and throws (uncaught: abort)
  // on a value ros::Duration cannot hold, so readParameters() must have checked it first.
  updater_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_);
  updater_->setHardwareID("wheel_rail_contact" + nh_.getNamespace());
  updater_->add("contact " + nh_.getNamespace(), this, &ContactNode::diagnose);
  lastDiagTime_ = ros::WallTime::now();
  // A wall timer: diagnostics keep coming while sim time is paused.
  diagnosticTimer_ =
      nh_.createWallTimer(ros::WallDuration(diagnosticPeriod_),
                          [this](const ros::WallTimerEvent&) { updater_->force_update(); });
}

void ContactNode::reset() {
  stepper_->reset();
  flush();  // the creepages that were still waiting for their load, answered rejected
}

void ContactNode::flush() {
  for (const StepResult& r : stepper_->takeReady()) {
    report(r);
    publish(r);
  }
  int64_t deadline = 0;
  if (!stepper_->nextDeadline(&deadline)) {
    if (loadWaitArmed_) loadWaitTimer_.stop();
    loadWaitArmed_ = false;
    return;
  }
  if (loadWaitArmed_ && deadline == loadWaitDeadlineNs_) return;
  // At least 1 us: a zero period would make the timer fire in a loop.
  const int64_t wait = std::max<int64_t>(deadline - steadyNowNs(), 1000);
  loadWaitTimer_.stop();
  loadWaitTimer_.setPeriod(ros::WallDuration(static_cast<double>(wait) * 1e-9));
  loadWaitTimer_.start();
  loadWaitArmed_ = true;
  loadWaitDeadlineNs_ = deadline;
}

void ContactNode::onLoadWait(const ros::SteadyTimerEvent&) {
  loadWaitArmed_ = false;
  stepper_->release(steadyNowNs());
  flush();
}

void ContactNode::creepageCallback(const ros::MessageEvent<const Creepage>& event) {
  const CreepageConstPtr& msg = event.getConstMessage();
  // roscpp numbers each publisher's messages: a gap is a message dropped before this callback.
  auto seen = lastSeq_.find(event.getPublisherName());
  if (seen != lastSeq_.end() && msg->header.seq > seen->second + 1) {
    lostCreepages_ += msg->header.seq - seen->second - 1;
    ROS_WARN_THROTTLE(1.0,
                      "%s: %lu creepage messages lost before the node (subscriber queue_size %d "
                      "too small for the bursts?)",
                      nh_.getNamespace().c_str(), static_cast<unsigned long>(lostCreepages_),
                      queueSize_);
  }
  lastSeq_[event.getPublisherName()] = msg->header.seq;
  StepInput in;
  in.V = msg->velocity;
  in.xi = msg->longitudinal;
  in.eta = msg->lateral;
  in.phi = msg->spin;
  in.a = msg->a;
  in.b = msg->b;
  in.mu = msg->mu;
  stepper_->addCreepage(stampNs(msg->header.stamp), in, steadyNowNs(),
                        {msg->curvature_x, msg->curvature_y});
  flush();
}

void ContactNode::loadCallback(const NormalLoadConstPtr& msg) {
  // Stamp 0 = unstamped: it never pairs by stamp, and never stands for "now" (that would make
  // every later stamped load look out of order under sim time).
  const std::string why = stepper_->addLoad(stampNs(msg->header.stamp), msg->force, steadyNowNs());
  if (!why.empty())
    ROS_WARN_THROTTLE(1.0, "%s: normal_load rejected: %s", nh_.getNamespace().c_str(), why.c_str());
  flush();
}

bool ContactNode::resetService(Reset::Request&, Reset::Response& res) {
  reset();
  res.success = true;
  res.message = "state reset (traction history, filter state, time base, loads, held output)";
  ROS_INFO("%s: %s", nh_.getNamespace().c_str(), res.message.c_str());
  return true;
}

bool ContactNode::stepService(Step::Request& req, Step::Response& res) {
  StepInput in;
  in.V = req.velocity;
  in.xi = req.longitudinal;
  in.eta = req.lateral;
  in.phi = req.spin;
  in.fz = req.normal_force;
  in.a = req.a;
  in.b = req.b;
  in.mu = req.mu;
  const StepResult r =
      stepper_->stepWithLoad(stampNs(req.stamp), in, {req.curvature_x, req.curvature_y});
  flush();  // older creepages this call released come out first
  report(r);
  fillState(r, &res);
  res.model = stepper_->modelName();
  publish(r);
  return true;
}

void ContactNode::report(const StepResult& r) {
  const char* ns = nh_.getNamespace().c_str();
  if (r.timeJumpReset) ROS_WARN("%s: stamps jumped backwards: state reset", ns);
  switch (r.event) {
    case StepEvent::kNonFinite:
      ROS_WARN_THROTTLE(1.0, "%s: creepage rejected (non-finite input): %s", ns, r.message.c_str());
      return;
    case StepEvent::kOutOfOrder:
      ROS_WARN_THROTTLE(1.0, "%s: creepage rejected (out of order): %s", ns, r.message.c_str());
      return;
    case StepEvent::kDtTooLarge:
      ROS_WARN_THROTTLE(1.0, "%s: creepage rejected: %s", ns, r.message.c_str());
      return;
    case StepEvent::kBadGeometry:
      ROS_WARN_THROTTLE(1.0, "%s: creepage rejected (geometry): %s", ns, r.message.c_str());
      return;
    case StepEvent::kDroppedByReset:
      ROS_WARN_THROTTLE(1.0, "%s: creepage rejected: %s", ns, r.message.c_str());
      return;
    case StepEvent::kNoLoadYet:
      ROS_WARN_THROTTLE(5.0, "%s: no normal_load for this step: zero forces", ns);
      return;
    case StepEvent::kStepped:
      break;
  }
  if (r.out.status == StepStatus::kRejected)
    ROS_WARN_THROTTLE(1.0, "%s: model refused the step: %s", ns, r.message.c_str());
  else if (r.loadMatch == LoadMatch::kUnmatched)
    ROS_WARN_THROTTLE(5.0, "%s: %s", ns, r.message.c_str());
  else if (r.out.status == StepStatus::kOk &&
           !r.message.empty())  // the fixed mesh grew, or a coarse patch
    ROS_WARN_THROTTLE(5.0, "%s: %s", ns, r.message.c_str());
  if (r.staleLoad)
    ROS_WARN_THROTTLE(5.0, "%s: the latest normal_load is %.3f s old (max_load_age)", ns,
                      r.loadAge);
}

void ContactNode::publish(const StepResult& r) {
  geometry_msgs::WrenchStamped w;
  w.header.stamp.fromNSec(static_cast<uint64_t>(r.stampNs));
  w.header.frame_id = frameId_;
  w.wrench.force.x = r.out.fx;
  w.wrench.force.y = r.out.fy;
  w.wrench.force.z = r.out.fz;
  w.wrench.torque.z = r.out.mz;
  ContactState s;
  s.header = w.header;
  fillState(r, &s);
  s.model = stepper_->modelName();
  forcePub_.publish(w);
  statePub_.publish(s);
}

void ContactNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const StepperCounters& c = stepper_->counters();
  const ros::WallTime now = ros::WallTime::now();
  const double span = (now - lastDiagTime_).toSec();
  const double rate =
      span > 0.0 ? static_cast<double>(c.creepages - lastDiag_.creepages) / span : 0;
  const uint64_t newRejected = c.rejected - lastDiag_.rejected;
  const uint64_t newLoadRejected = c.loadsRejected - lastDiag_.loadsRejected;
  const uint64_t newStale = c.staleLoad - lastDiag_.staleLoad;
  const uint64_t newUnmatched = c.unmatched - lastDiag_.unmatched;
  const bool newLost = lostCreepages_ > lastLost_;
  lastLost_ = lostCreepages_;
  if (newLost)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 "creepage messages lost before the node: raise queue_size");
  else if (newRejected + newLoadRejected > 0)
    stat.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%lu inputs rejected in the last %.1f s",
                  static_cast<unsigned long>(newRejected + newLoadRejected), span);
  else if (newUnmatched > 0)
    stat.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                  "%lu steps without the load of their stamp in the last %.1f s",
                  static_cast<unsigned long>(newUnmatched), span);
  else if (newStale > 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "normal load older than max_load_age");
  else if (!stepper_->hasLoad())
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "no normal load yet");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  stat.add("model", stepper_->modelName());
  stat.addf("input rate [Hz]", "%.1f", rate);
  stat.add("creepage messages", c.creepages);
  stat.add("ok", c.ok);
  stat.add("no load", c.noLoad);
  stat.add("standstill", c.standstill);
  stat.add("solver not converged (exact model)", c.notConverged);
  stat.add("rejected", c.rejected);
  stat.add("rejected: non-finite", c.nonFinite);
  stat.add("rejected: geometry", c.badGeometry);
  stat.add("rejected: creepage stamp out of order", c.outOfOrder);
  stat.add("rejected: dt > max_dt", c.dtTooLarge);
  stat.add("rejected: by the model", c.rejectedByModel);
  stat.add("rejected: reset while waiting for the load", c.droppedByReset);
  stat.add("creepage lost before the node (queue_size)", lostCreepages_);
  stat.add("normal_load messages", c.loads);
  stat.add("normal_load rejected", c.loadsRejected);
  stat.add("normal_load stamp out of order", c.loadsOutOfOrder);
  stat.add("normal_load unstamped", c.loadsUnstamped);
  stat.add("load pairing", toString(stepper_->options().load_pairing));
  stat.add("unmatched load steps", c.unmatched);
  stat.add("unmatched: a later load came first", c.unmatchedLaterLoad);
  stat.add("unmatched: load_wait expired", c.unmatchedWaitExpired);
  stat.add("unmatched: pairing buffer full", c.unmatchedBufferFull);
  stat.add("waiting for their load now", stepper_->pending());
  stat.add("waiting for their load, most", c.pendingMax);
  stat.add("stale load steps", c.staleLoad);
  stat.add("latest load [N]", stepper_->load());
  stat.add("resets", c.resets);
  stat.add("time-jump resets", c.timeJumpResets);
  stat.addf("solver time last [ms]", "%.4f", 1e3 * c.solverTimeLast);
  stat.addf("solver time mean [ms]", "%.4f",
            c.creepages > 0 ? 1e3 * c.solverTimeSum / static_cast<double>(c.creepages) : 0.0);
  stat.addf("solver time max [ms]", "%.4f", 1e3 * c.solverTimeMax);
  lastDiag_ = c;
  lastDiagTime_ = now;
}

}  // namespace wheel_rail_contact
