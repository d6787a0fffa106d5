#include "wheelset_node.hpp"

#include <ros/package.h>

#include <set>
#include <stdexcept>

#include "../cli/config_yaml.hpp"
#include "node_common.hpp"
#include "ros_conversions.hpp"

namespace wheel_rail_contact {

namespace {

const char* const kNodeKeys[] = {"wheelsets",     "wheel_profile",       "rail_profile",
                                 "contact_table", "whole_force_balance", "frame_prefix",
                                 "queue_size",    "publish_queue_size",  "diagnostic_period",
                                 "max_dt",        "time_jump_reset",     "threads"};

uint8_t patchStatus(const PatchResult& p) {
  if (p.creepages.status == CreepageStatus::kInvalidInput)
    return PatchContactState::STATUS_CREEPAGES_INVALID;
  return static_cast<uint8_t>(p.tangential_status);  // StepStatus's order is the message's
}

void fillWrench(const TrackWrench& w, geometry_msgs::Wrench* m) {
  m->force.x = w.fx;
  m->force.y = w.fy;
  m->force.z = w.fz;
  m->torque.x = w.mx;
  m->torque.y = w.my;
  m->torque.z = w.mz;
}

void fillWheel(const WheelAnswer& a, WheelContactState* m) {
  m->status = static_cast<uint8_t>(a.status);
  m->message = a.message;
  m->held = a.held;
  fillWrench(a.result.wrench, &m->wrench);
  m->centre.x = a.result.centre.x();
  m->centre.y = a.result.centre.y();
  m->centre.z = a.result.centre.z();
  m->patches.resize(a.result.patches.size());
  for (size_t k = 0; k < a.result.patches.size(); ++k) {
    const PatchResult& p = a.result.patches[k];
    PatchContactState& s = m->patches[k];
    s.slot = p.slot;
    s.zone = static_cast<uint8_t>(p.zone);
    const ContactCandidate& g = p.geometry;
    s.point.x = g.point.x();
    s.point.y = g.point.y();
    s.point.z = g.point.z();
    s.y_rail = g.rail_file.x();
    s.z_rail = g.rail_file.y();
    s.y_wheel = g.wheel_file.x();
    s.contact_angle = g.contact_angle;
    s.rolling_radius = g.rolling_radius;
    s.fn = p.normal.fn;
    s.a = p.normal.a;
    s.b = p.normal.b;
    s.pmax = p.normal.pmax;
    s.xi = p.creepages.xi;
    s.eta = p.creepages.eta;
    s.phi = p.creepages.phi;
    s.fx = p.fx;
    s.fs = p.fs;
    s.mz = p.mz;
    fillWrench(p.wrench, &s.wrench);
    s.status = patchStatus(p);
    s.message = p.message;
  }
}

}  // namespace

std::string resolveProfilePath(const std::string& parameter, const std::string& value) {
  if (value.empty()) return value;
  const std::string scheme = "package://";
  if (value.compare(0, scheme.size(), scheme) == 0) {
    const std::string rest = value.substr(scheme.size());
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size())
      throw std::invalid_argument(parameter + ": '" + value + "' is not package://PACKAGE/PATH");
    const std::string package = rest.substr(0, slash);
    const std::string dir = ros::package::getPath(package);
    if (dir.empty())
      throw std::invalid_argument(parameter + ": package '" + package + "' not found (in '" +
                                  value + "')");
    return dir + "/" + rest.substr(slash + 1);
  }
  if (value[0] != '/')
    throw std::invalid_argument(parameter + ": '" + value +
                                "' is neither an absolute path nor package://PACKAGE/PATH");
  return value;
}

WheelsetNode::WheelsetNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh) {}

bool WheelsetNode::readParameters() {
  try {
    WheelsetStepperConfig config;
    config.names = readNameList(pnh_, "wheelsets", "wheelset");

    // Every private key is known: the node's, the model's (ContactParameters) and the wheelset's
    // (contact_cli wheelset's --config keys); contact_node's own keys of a shared file are
    // accepted and not used; anything else fails, so a typo does not go unnoticed.
    std::set<std::string> known(std::begin(kNodeKeys), std::end(kNodeKeys));
    for (const auto& d : parameterDocs()) known.insert(d.name);
    for (const auto& d : wheelsetParameterDocs()) known.insert(d.name);
    // contact_cli wheelset's cant is the cant of a scenario without a cant column; here every
    // tick gives its own (WheelsetKinematics.cant), so a ~cant would be a value never used.
    known.erase("cant");
    if (pnh_.hasParam("cant"))
      throw std::invalid_argument(
          "cant: not a parameter of wheelset_node: each tick's WheelsetKinematics.cant gives the "
          "track's cant under its wheelset");
    std::set<std::string> ignored;
    std::vector<std::string> all;
    ros::param::getParamNames(all);
    const std::string prefix = pnh_.getNamespace() + "/";
    for (const auto& full : all) {
      if (full.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string key = full.substr(prefix.size());
      if (known.count(key)) continue;
      if (isNodeOnlyParameter(key)) {
        ignored.insert(key);
        continue;
      }
      throw std::invalid_argument(key + ": unknown parameter");
    }

    XmlRpc::XmlRpcValue v;
    for (const auto& d : parameterDocs())
      if (pnh_.getParam(d.name, v))
        setParameter(&config.parameters, d.name, parameterText(d.name, v));
    WheelsetConfig wheelset;
    for (const auto& d : wheelsetParameterDocs())
      if (pnh_.getParam(d.name, v))
        setWheelsetParameter(&wheelset, d.name, parameterText(d.name, v));
    config.track = wheelset.track;

    std::string profiles;
    for (const char* key : {"wheel_profile", "rail_profile"}) {
      std::string file;
      if (pnh_.getParam(key, v)) {
        if (v.getType() != XmlRpc::XmlRpcValue::TypeString)
          throw std::invalid_argument(std::string(key) + ": expected a file name, got " +
                                      v.toXml());
        file = resolveProfilePath(key, static_cast<std::string>(v));
      }
      const bool wheel = std::string(key) == "wheel_profile";
      profiles += std::string(" ") + key + " " + (file.empty() ? "standard" : file);
      if (file.empty()) continue;  // the compiled-in S1002 / UIC60 1:40
      try {
        auto p = std::make_shared<const Profile>(Profile::read(
            file, wheel ? ProfileKind::kWheel : ProfileKind::kRail, wheelset.profile_read));
        (wheel ? config.track.wheel_right : config.track.rail_right) = std::move(p);
      } catch (const std::exception& e) {
        throw std::invalid_argument(std::string(key) + ": " + e.what());
      }
    }

    config.options.use_contact_table = true;
    if (pnh_.getParam("contact_table", v)) {
      if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean)
        throw std::invalid_argument("contact_table: expected true or false, got " + v.toXml());
      config.options.use_contact_table = static_cast<bool>(v);
    }
    if (pnh_.getParam("whole_force_balance", v)) {
      if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean)
        throw std::invalid_argument("whole_force_balance: expected true or false, got " +
                                    v.toXml());
      config.options.whole_force_balance = static_cast<bool>(v);
    }
    if (pnh_.getParam("max_dt", v)) config.max_dt = toNumber("max_dt", parameterText("max_dt", v));
    if (pnh_.getParam("time_jump_reset", v))
      config.time_jump_reset = toNumber("time_jump_reset", parameterText("time_jump_reset", v));

    queueSize_ = readCount(pnh_, "queue_size", 100);
    config.threads = readCount(pnh_, "threads", 1);
    publishQueueSize_ = readCount(pnh_, "publish_queue_size", 100);
    diagnosticPeriod_ = readDiagnosticPeriod(pnh_, diagnosticPeriod_);
    const std::string framePrefix = readFramePrefix(nh_, pnh_);

    stepper_ = std::make_unique<WheelsetStepper>(config);
    frameIds_.clear();
    for (const auto& n : config.names) frameIds_.push_back(framePrefix + n + "_track");
    const ContactParameters& p = stepper_->config().parameters;
    ROS_INFO(
        "wheelset_node %s: %zu wheelsets, model %s (%s), G %g Pa, nu %g, mu %g, mesh %s %dx%d;"
        "%s; contact table %s",
        nh_.getNamespace().c_str(), stepper_->size(), p.model.c_str(), fastsimVariantName(p), p.G,
        p.nu, p.mu, p.mesh.c_str(), p.nx, p.ny, profiles.c_str(),
        stepper_->contactTable() ? "on (one for all wheelsets)" : "off (direct search)");
    logIgnoredParameters("wheelset_node", nh_.getNamespace(), ignored);
    lastCounters_.assign(stepper_->size(), WheelsetCounters{});
    return true;
  } catch (const std::exception& e) {
    ROS_FATAL("wheelset_node: invalid parameter %s", e.what());
    return false;
  }
}

void WheelsetNode::start() {
  forcesPub_ = nh_.advertise<WheelsetForces>("wheelset_forces", publishQueueSize_);
  stepSrv_ = nh_.advertiseService("wheelset_step", &WheelsetNode::stepService, this);
  resetSrv_ = nh_.advertiseService("reset", &WheelsetNode::resetService, this);
  inputSub_ = nh_.subscribe("wheelset_input", queueSize_, &WheelsetNode::inputCallback, this,
                            ros::TransportHints().tcpNoDelay());

  diagnostics_.start(nh_, pnh_, diagnosticPeriod_, &mutex_, [this](diagnostic_updater::Updater& u) {
    u.add("wheelsets " + nh_.getNamespace(), this, &WheelsetNode::diagnoseNode);
    for (size_t i = 0; i < stepper_->size(); ++i)
      u.add("wheelset " + nh_.getNamespace() + " " + stepper_->name(i),
            [this, i](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnoseWheelset(i, s); });
  });
}

void WheelsetNode::tick(const WheelsetInput& in, WheelsetForces* out) {
  entries_.resize(in.wheelsets.size());
  for (size_t k = 0; k < in.wheelsets.size(); ++k) {
    const WheelsetKinematics& m = in.wheelsets[k];
    WheelsetEntry& e = entries_[k];
    e.name = m.name;
    e.state = WheelsetState{};
    e.state.pose.y = m.lateral;
    e.state.pose.yaw = m.yaw;
    e.state.pose.roll = m.roll;
    e.state.motion.V = m.velocity;
    e.state.motion.omega = m.pitch_rate;
    e.state.motion.vy = m.lateral_velocity;
    e.state.motion.yaw_rate = m.yaw_rate;
    e.state.motion.vz = m.vertical_velocity;
    e.state.motion.roll_rate = m.roll_rate;
    e.state.motion.curvature = m.curvature;
    e.state.fz_left = m.load_left;
    e.state.motion.cant = m.cant;
    e.state.fz_right = m.load_right;
  }
  stepper_->step(static_cast<int64_t>(in.header.stamp.toNSec()), entries_, &answers_);

  out->header.stamp = in.header.stamp;
  out->header.frame_id = in.header.frame_id;
  out->wheelsets.resize(answers_.size());
  for (size_t k = 0; k < answers_.size(); ++k) {
    const WheelsetAnswer& a = answers_[k];
    WheelsetContactState& s = out->wheelsets[k];
    const bool known = a.wheelset >= 0;
    s.name = k < in.wheelsets.size() ? in.wheelsets[k].name : stepper_->name(a.wheelset);
    s.header.stamp = in.header.stamp;
    s.header.frame_id = known ? frameIds_[a.wheelset] : "";
    s.dt = a.dt;
    s.solver_time = a.solver_time;
    fillWheel(a.left, &s.left);
    fillWheel(a.right, &s.right);
    report(a, s.name);
  }
}

void WheelsetNode::inputCallback(const ros::MessageEvent<const WheelsetInput>& event) {
  const WheelsetInputConstPtr& msg = event.getConstMessage();
  auto out = boost::make_shared<WheelsetForces>();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    lostInputs_.see(event.getPublisherName(), msg->header.seq, nh_.getNamespace(), "wheelset_input",
                    queueSize_);
    tick(*msg, out.get());
  }
  forcesPub_.publish(out);
}

bool WheelsetNode::stepService(WheelsetStep::Request& req, WheelsetStep::Response& res) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tick(req.input, &res.forces);
  }
  forcesPub_.publish(res.forces);
  return true;
}

bool WheelsetNode::resetService(Reset::Request&, Reset::Response& res) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stepper_->reset();
  }
  res.success = true;
  res.message = "all " + std::to_string(stepper_->size()) +
                " wheelsets reset (patch histories, time base, held answers)";
  ROS_INFO("%s: %s", nh_.getNamespace().c_str(), res.message.c_str());
  return true;
}

void WheelsetNode::report(const WheelsetAnswer& a, const std::string& name) {
  const char* ns = nh_.getNamespace().c_str();
  if (a.time_jump_reset) ROS_WARN("%s: %s: stamps jumped backwards: state reset", ns, name.c_str());
  if (a.event != WheelsetEvent::kStepped) {
    ROS_WARN_THROTTLE(1.0, "%s: %s rejected%s: %s", ns, name.c_str(),
                      a.wheelset >= 0 ? " (last accepted answers held)" : "", a.message.c_str());
    return;
  }
  for (const WheelAnswer* w : {&a.left, &a.right}) {
    const char* side = w == &a.left ? "left" : "right";
    if (w->held)
      ROS_WARN_THROTTLE(1.0, "%s: %s %s wheel held (last accepted answer): %s", ns, name.c_str(),
                        side, w->message.c_str());
    else if (!w->message.empty())
      ROS_WARN_THROTTLE(5.0, "%s: %s %s wheel: %s", ns, name.c_str(), side, w->message.c_str());
  }
}

void WheelsetNode::diagnoseNode(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const WheelsetStepperCounters& c = stepper_->counters();
  const double rate = diagnostics_.summarize(stat, c.ticks, c.unknown_names, lostInputs_.count(),
                                             "wheelset_input", "wheelsets");
  stat.add("wheelsets", stepper_->size());
  stat.add("model", stepper_->config().parameters.model);
  stat.add("contact table", stepper_->contactTable() ? "shared" : "off");
  stat.addf("tick rate [Hz]", "%.1f", rate);
  stat.add("ticks", c.ticks);
  stat.add("entries with an unknown wheelset name", c.unknown_names);
  stat.add("wheelset_input lost before the node (queue_size)", lostInputs_.count());
}

void WheelsetNode::diagnoseWheelset(size_t i, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const WheelsetCounters& c = stepper_->counters(i);
  const WheelsetCounters& c0 = lastCounters_[i];
  if (c.held > c0.held)
    stat.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                  "%lu wheel answers held (rejected) since the last report",
                  static_cast<unsigned long>(c.held - c0.held));
  else if (c.steps == 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "no input yet");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  stat.add("frame_id", frameIds_[i]);
  stat.add("steps", c.steps);
  stat.add("held wheel answers", c.held);
  stat.add("rejected: missing from the input", c.missing);
  stat.add("rejected: name repeated in the input", c.duplicate);
  stat.add("rejected: non-finite", c.non_finite);
  stat.add("rejected: stamp out of order", c.out_of_order);
  stat.add("rejected: dt > max_dt", c.dt_too_large);
  stat.add("wheels: no load", c.no_load);
  stat.add("wheels held: no contact", c.no_contact);
  stat.add("wheels held: invalid input (beyond the profiles, |cant| > 0.2 rad)", c.invalid_input);
  stat.add("wheels held: normal problem failed", c.normal_failed);
  stat.add("wheels held: a patch's model refused", c.patch_rejected);
  stat.add("resets", c.resets);
  stat.add("time-jump resets", c.time_jump_resets);
  stat.addf("step time mean [ms]", "%.4f",
            c.steps > 0 ? 1e3 * c.solver_time_sum / static_cast<double>(c.steps) : 0.0);
  stat.addf("step time max [ms]", "%.4f", 1e3 * c.solver_time_max);
  lastCounters_[i] = c;
}

}  // namespace wheel_rail_contact
