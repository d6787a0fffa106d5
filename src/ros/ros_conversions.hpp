/// Conversions shared by the ROS wrappers: parameter values as the text the core's setParameter()
/// parses, and a StepResult into ContactState-like messages.
#pragma once

#include <ros/ros.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "contact_stepper.hpp"

namespace wheel_rail_contact {

/// A parameter value as the text setParameter() parses (the rule contact_cli's options and YAML
/// follow), so one file configures every tool. Throws std::invalid_argument naming `name`.
inline std::string parameterText(const std::string& name, XmlRpc::XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeDouble: {
      char text[64];
      std::snprintf(text, sizeof text, "%.17g", static_cast<double>(v));
      return text;
    }
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(v);
    default:
      throw std::invalid_argument(name + ": expected a number or a name, got " + v.toXml());
  }
}

/// ContactState and Step's response carry the same state fields under the same names (model and
/// header are the caller's).
template <class State>
void fillState(const StepResult& r, State* m) {
  m->fx = r.out.fx;
  m->fy = r.out.fy;
  m->fz = r.out.fz;
  m->mz = r.out.mz;
  m->a = r.out.a;
  m->b = r.out.b;
  m->adhesion_fraction = r.out.adhesionFraction;
  m->dt = r.dt;
  m->solver_time = r.solverTime;
  m->status = contactStateStatus(r.out.status);
  m->message = r.message;
  m->load_match = static_cast<uint8_t>(r.loadMatch);
  m->load_stamp.fromNSec(static_cast<uint64_t>(r.loadStampNs));
  m->held = r.held;
}

}  // namespace wheel_rail_contact
