#include "vehicle_node.hpp"

#include <set>
#include <stdexcept>

#include "../cli/config_yaml.hpp"
#include "node_common.hpp"
#include "ros_conversions.hpp"

namespace wheel_rail_contact {

namespace {

const char* const kStepperKeys[] = {"max_dt", "time_jump_reset", "max_load_age"};
const char* const kVehicleKeys[] = {"contacts", "frame_prefix", "queue_size", "publish_queue_size",
                                    "diagnostic_period"};

}  // namespace

VehicleNode::VehicleNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh), pnh_(pnh) {}

bool VehicleNode::readParameters() {
  try {
    const std::vector<std::string> names = readNameList(pnh_, "contacts", "contact");

    // Unknown private keys fail, as in contact_node; a contact's overrides live under ~NAME/.
    std::set<std::string> contactKeys(std::begin(kStepperKeys), std::end(kStepperKeys));
    contactKeys.insert("frame_id");
    for (const auto& d : parameterDocs()) contactKeys.insert(d.name);
    std::set<std::string> vehicleKeys(contactKeys);
    vehicleKeys.erase("frame_id");
    vehicleKeys.insert(std::begin(kVehicleKeys), std::end(kVehicleKeys));
    std::set<std::string> ignored;  // contact_node's own keys (a shared YAML file) not used here
    const std::set<std::string> named(names.begin(), names.end());
    for (const auto& n : names)  // ~NAME/ holds a contact's overrides: it cannot be a key too
      if (vehicleKeys.count(n) || isNodeOnlyParameter(n))
        throw std::invalid_argument("contacts: '" + n + "' is a parameter's name");
    std::vector<std::string> all;
    ros::param::getParamNames(all);
    const std::string prefix = pnh_.getNamespace() + "/";
    for (const auto& full : all) {
      if (full.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string key = full.substr(prefix.size());
      const size_t slash = key.find('/');
      const std::string first = key.substr(0, slash);
      if (slash == std::string::npos) {
        if (vehicleKeys.count(first)) continue;
        if (isNodeOnlyParameter(first)) {
          ignored.insert(first);
          continue;
        }
        throw std::invalid_argument(key + ": unknown parameter");
      }
      if (!named.count(first))
        throw std::invalid_argument(key + ": unknown parameter (" + first +
                                    " is not in ~contacts)");
      if (!contactKeys.count(key.substr(slash + 1)))
        throw std::invalid_argument(key + ": unknown parameter");
    }

    XmlRpc::XmlRpcValue v;
    queueSize_ = readCount(pnh_, "queue_size", 100);
    publishQueueSize_ = readCount(pnh_, "publish_queue_size", 100);
    diagnosticPeriod_ = readDiagnosticPeriod(pnh_, diagnosticPeriod_);
    const std::string framePrefix = readFramePrefix(nh_, pnh_);

    std::vector<VehicleContactConfig> configs;
    for (const auto& n : names) {
      VehicleContactConfig c;
      c.name = n;
      // A contact's own value (~NAME/key) wins over the shared one (~key).
      auto lookup = [&](const std::string& key, XmlRpc::XmlRpcValue* x, std::string* where) {
        *where = n + "/" + key;
        if (pnh_.getParam(*where, *x)) return true;
        *where = key;
        return pnh_.getParam(key, *x);
      };
      std::string where;
      for (const auto& d : parameterDocs())
        if (lookup(d.name, &v, &where)) {
          try {
            setParameter(&c.parameters, d.name, parameterText(where, v));
          } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(where == d.name ? e.what() : n + "/" + e.what());
          }
        }
      double* options[] = {&c.options.max_dt, &c.options.time_jump_reset, &c.options.max_load_age};
      for (size_t k = 0; k < 3; ++k)
        if (lookup(kStepperKeys[k], &v, &where))
          *options[k] = toNumber(where, parameterText(where, v));
      c.frameId = framePrefix + n;
      if (pnh_.getParam(n + "/frame_id", v)) c.frameId = parameterText(n + "/frame_id", v);
      configs.push_back(c);
    }
    vehicle_ = std::make_unique<VehicleStepper>(configs);

    for (size_t i = 0; i < vehicle_->size(); ++i) {
      const VehicleContactConfig& c = vehicle_->config(i);
      const ContactParameters& p = c.parameters;
      ROS_INFO(
          "vehicle_node %s: contact %s: model %s (%s), G %g Pa, nu %g, mu %g, a0 %g m, b0 %g "
          "m, fz0 %g N, mesh %s %dx%d, frame '%s'",
          nh_.getNamespace().c_str(), c.name.c_str(), p.model.c_str(), fastsimVariantName(p), p.G,
          p.nu, p.mu, p.a0, p.b0, p.fz0, p.mesh.c_str(), p.nx, p.ny, c.frameId.c_str());
      const std::string chosen = vehicle_->stepper(i).modelChoices();
      if (!chosen.empty())
        ROS_INFO("vehicle_node %s: contact %s: %s", nh_.getNamespace().c_str(), c.name.c_str(),
                 chosen.c_str());
    }
    logIgnoredParameters("vehicle_node", nh_.getNamespace(), ignored);
    lastStepper_.assign(vehicle_->size(), StepperCounters{});
    lastVehicle_.assign(vehicle_->size(), VehicleContactCounters{});
    return true;
  } catch (const std::exception& e) {
    ROS_FATAL("vehicle_node: invalid parameter %s", e.what());
    return false;
  }
}

void VehicleNode::start() {
  statePub_ = nh_.advertise<VehicleState>("vehicle_state", publishQueueSize_);
  stepSrv_ = nh_.advertiseService("vehicle_step", &VehicleNode::stepService, this);
  resetSrv_ = nh_.advertiseService("reset", &VehicleNode::resetService, this);
  inputSub_ = nh_.subscribe("vehicle_input", queueSize_, &VehicleNode::inputCallback, this,
                            ros::TransportHints().tcpNoDelay());

  diagnostics_.start(nh_, pnh_, diagnosticPeriod_, &mutex_, [this](diagnostic_updater::Updater& u) {
    u.add("vehicle " + nh_.getNamespace(), this, &VehicleNode::diagnoseVehicle);
    for (size_t i = 0; i < vehicle_->size(); ++i)
      u.add("contact " + nh_.getNamespace() + " " + vehicle_->config(i).name,
            [this, i](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnoseContact(i, s); });
  });
}

void VehicleNode::tick(const VehicleInput& in, VehicleState* state) {
  inputs_.resize(in.contacts.size());
  for (size_t k = 0; k < in.contacts.size(); ++k) {
    const ContactInput& c = in.contacts[k];
    VehicleContactInput& e = inputs_[k];
    e.name = c.name;
    e.in = StepInput{};
    e.in.V = c.velocity;
    e.in.xi = c.longitudinal;
    e.in.eta = c.lateral;
    e.in.phi = c.spin;
    e.in.fz = c.normal_force;
    e.in.a = c.a;
    e.in.b = c.b;
    e.in.mu = c.mu;
    e.curvatureX = c.curvature_x;
    e.curvatureY = c.curvature_y;
  }
  vehicle_->step(static_cast<int64_t>(in.header.stamp.toNSec()), inputs_, &results_);

  state->header.stamp = in.header.stamp;
  state->header.frame_id = in.header.frame_id;
  state->names.resize(results_.size());
  state->contacts.resize(results_.size());
  for (size_t k = 0; k < results_.size(); ++k) {
    const VehicleContactResult& r = results_[k];
    ContactState& s = state->contacts[k];
    const bool known = r.contact >= 0;
    state->names[k] =
        k < in.contacts.size() ? in.contacts[k].name : vehicle_->config(r.contact).name;
    s.header.stamp = in.header.stamp;
    s.header.frame_id = known ? vehicle_->config(r.contact).frameId : "";
    s.model = known ? vehicle_->stepper(r.contact).modelName() : "";
    fillState(r.step, &s);
    report(r, state->names[k]);
  }
}

void VehicleNode::inputCallback(const ros::MessageEvent<const VehicleInput>& event) {
  const VehicleInputConstPtr& msg = event.getConstMessage();
  auto state = boost::make_shared<VehicleState>();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    lostInputs_.see(event.getPublisherName(), msg->header.seq, nh_.getNamespace(), "vehicle_input",
                    queueSize_);
    tick(*msg, state.get());
  }
  statePub_.publish(state);
}

bool VehicleNode::stepService(VehicleStep::Request& req, VehicleStep::Response& res) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tick(req.input, &res.state);
  }
  statePub_.publish(res.state);
  return true;
}

bool VehicleNode::resetService(Reset::Request&, Reset::Response& res) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    vehicle_->reset();
  }
  res.success = true;
  res.message = "all " + std::to_string(vehicle_->size()) +
                " contacts reset (traction history, filter state, time base, load, held forces)";
  ROS_INFO("%s: %s", nh_.getNamespace().c_str(), res.message.c_str());
  return true;
}

void VehicleNode::report(const VehicleContactResult& r, const std::string& name) {
  const char* ns = nh_.getNamespace().c_str();
  const char* msg = r.step.message.c_str();
  if (r.step.timeJumpReset)
    ROS_WARN("%s: %s: stamps jumped backwards: state reset", ns, name.c_str());
  if (r.held) {
    ROS_WARN_THROTTLE(1.0, "%s: %s rejected (last accepted forces held): %s", ns, name.c_str(),
                      msg);
  } else if (r.contact < 0) {
    ROS_WARN_THROTTLE(1.0, "%s: %s", ns, msg);
  } else if (r.step.event == StepEvent::kNoLoadYet) {
    ROS_WARN_THROTTLE(5.0, "%s: %s: no normal load yet: zero forces", ns, name.c_str());
  } else if (r.step.out.status == StepStatus::kOk && !r.step.message.empty()) {
    ROS_WARN_THROTTLE(5.0, "%s: %s: %s", ns, name.c_str(),
                      msg);  // the fixed mesh grew, or a coarse patch
  }
  if (r.step.staleLoad)
    ROS_WARN_THROTTLE(5.0, "%s: %s: the load is %.3f s old (max_load_age)", ns, name.c_str(),
                      r.step.loadAge);
}

void VehicleNode::diagnoseVehicle(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const VehicleCounters& c = vehicle_->counters();
  const double rate = diagnostics_.summarize(stat, c.ticks, c.unknownNames, lostInputs_.count(),
                                             "vehicle_input", "contacts");
  stat.add("contacts", vehicle_->size());
  stat.addf("tick rate [Hz]", "%.1f", rate);
  stat.add("ticks", c.ticks);
  stat.add("entries with an unknown contact name", c.unknownNames);
  stat.add("vehicle_input lost before the node (queue_size)", lostInputs_.count());
}

void VehicleNode::diagnoseContact(size_t i, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const StepperCounters& c = vehicle_->stepper(i).counters();
  const VehicleContactCounters& v = vehicle_->counters(i);
  const StepperCounters& c0 = lastStepper_[i];
  const VehicleContactCounters& v0 = lastVehicle_[i];
  const uint64_t newHeld = v.held - v0.held;
  if (newHeld > 0)
    stat.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                  "%lu steps rejected (forces held) since the last report",
                  static_cast<unsigned long>(newHeld));
  else if (c.staleLoad > c0.staleLoad)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "load older than max_load_age");
  else if (!vehicle_->stepper(i).hasLoad())
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "no normal load yet");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  stat.add("model", vehicle_->stepper(i).modelName());
  stat.add("frame_id", vehicle_->config(i).frameId);
  stat.add("steps", c.creepages);
  stat.add("ok", c.ok);
  stat.add("no load", c.noLoad);
  stat.add("standstill", c.standstill);
  stat.add("solver not converged (exact model)", c.notConverged);
  stat.add("rejected, forces held", v.held);
  stat.add("rejected: missing from the input", v.missing);
  stat.add("rejected: name repeated in the input", v.duplicate);
  stat.add("rejected: a, b, curvatures or mu malformed", v.badGeometry);
  stat.add("rejected: non-finite", c.nonFinite);
  stat.add("rejected: stamp out of order", c.outOfOrder);
  stat.add("rejected: dt > max_dt", c.dtTooLarge);
  stat.add("rejected: by the model", c.rejectedByModel);
  stat.add("stale load steps", c.staleLoad);
  stat.add("latest load [N]", vehicle_->stepper(i).load());
  stat.add("resets", c.resets);
  stat.add("time-jump resets", c.timeJumpResets);
  stat.addf("solver time mean [ms]", "%.4f",
            c.creepages > 0 ? 1e3 * c.solverTimeSum / static_cast<double>(c.creepages) : 0.0);
  stat.addf("solver time max [ms]", "%.4f", 1e3 * c.solverTimeMax);
  lastStepper_[i] = c;
  lastVehicle_[i] = v;
}

}  // namespace wheel_rail_contact
