// wheelset_sim: the closed-loop demo's vehicle simulator (doc/wheelset_demo.md). One wheelset on
// tangent track (src/demo/wheelset_model.hpp) whose two contacts are real contact_nodes, driven in
// lock-step through their `step` services: at every step it computes the left and right creepages
// from the wheelset's state, calls <left>/step and <right>/step with stamp = sim time and the wheel
// load, and integrates the equations of motion with the returned creep forces held over the step.
// No /clock is needed: the service request carries the stamp, from which the contact takes its dt.
//
// It runs a list of cases (private parameter `cases`), resetting both contacts before each, writes
// one CSV per case and a summary CSV into output_dir (if set), prints one `result` line per case on
// stdout and exits (0, or 1 on any error: a parameter, a missing service, a refused step).
//
// Private parameters (vehicle; defaults and sources in doc/wheelset_demo.md): r0, l0, conicity,
// mass, yaw_inertia, lateral_stiffness, yaw_stiffness, wheel_load, contact_angle. Run: dt [s]
// (default 0.0005), left (default "left"), right (default "right"): the contacts' namespaces,
// relative to this node's; service_timeout [wall s] (default 30); output_dir (default "": no
// files); cases: a list of {name, speed [m/s], duration [s], y0 [m], amplitude [m], wavelength [m],
// fit_from [fraction of duration, default 0.5]}. A case with amplitude 0 is a free decay from y0:
// its result is the kinematic oscillation's frequency, wavelength and damping ratio (fitDecay of
// y). A case with an irregularity gives the amplitude and phase of the left wheel's Fx, of y and of
// psi at the forcing frequency V / wavelength (fitHarmonic over t >= fit_from duration).
#include <ros/ros.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "../demo/wheelset_model.hpp"
#include "wheel_rail_contact/Reset.h"
#include "wheel_rail_contact/Step.h"

namespace {

using namespace wheel_rail_contact;
using namespace wheel_rail_contact::demo;

struct Case {
  std::string name;
  double speed = 20.0, duration = 1.0, y0 = 0.0, amplitude = 0.0, wavelength = 1.0;
  double fitFrom = 0.5;
};

struct Settings {
  WheelsetParameters vehicle;
  double dt = 0.0005;
  std::string left = "left", right = "right", outputDir;
  double serviceTimeout = 30.0;
  std::vector<Case> cases;
};

double number(XmlRpc::XmlRpcValue& v, const std::string& name) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw std::invalid_argument(name + ": expected a number, got " + v.toXml());
}

Case readCase(XmlRpc::XmlRpcValue& c, size_t index) {
  const std::string where = "cases[" + std::to_string(index) + "]";
  if (c.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    throw std::invalid_argument(where + ": expected a map {name: ..., speed: ..., ...}");
  Case k;
  const std::map<std::string, double*> numbers = {
      {"speed", &k.speed},         {"duration", &k.duration},     {"y0", &k.y0},
      {"amplitude", &k.amplitude}, {"wavelength", &k.wavelength}, {"fit_from", &k.fitFrom}};
  for (auto& field : c) {
    const std::string& key = field.first;
    const std::string name = where + "." + key;
    if (key == "name") {
      if (field.second.getType() != XmlRpc::XmlRpcValue::TypeString)
        throw std::invalid_argument(name + ": expected a string");
      k.name = static_cast<std::string>(field.second);
    } else if (numbers.count(key)) {
      *numbers.at(key) = number(field.second, name);
    } else {
      throw std::invalid_argument(name +
                                  ": unknown key (name, speed, duration, y0, amplitude, "
                                  "wavelength, fit_from)");
    }
  }
  if (k.name.empty() || k.name.find_first_of("/, \t") != std::string::npos)
    throw std::invalid_argument(where + ".name: required, without '/', ',' or blanks");
  if (!(k.speed > 0.0 && k.speed < 200.0))
    throw std::invalid_argument(where + ".speed: must be in (0, 200) m/s");
  if (!(k.duration > 0.0 && k.duration <= 600.0))
    throw std::invalid_argument(where + ".duration: must be in (0, 600] s");
  if (!(std::fabs(k.y0) <= 0.01)) throw std::invalid_argument(where + ".y0: |y0| <= 0.01 m");
  if (!(std::fabs(k.amplitude) <= 0.01))
    throw std::invalid_argument(where + ".amplitude: |amplitude| <= 0.01 m");
  if (!(k.wavelength > 0.0 && std::isfinite(k.wavelength)))
    throw std::invalid_argument(where + ".wavelength: must be > 0");
  if (!(k.fitFrom >= 0.0 && k.fitFrom < 1.0))
    throw std::invalid_argument(where + ".fit_from: must be in [0, 1)");
  return k;
}

Settings readSettings(const ros::NodeHandle& pnh) {
  static const std::set<std::string> known = {"r0",
                                              "l0",
                                              "conicity",
                                              "mass",
                                              "yaw_inertia",
                                              "lateral_stiffness",
                                              "yaw_stiffness",
                                              "wheel_load",
                                              "contact_angle",
                                              "dt",
                                              "left",
                                              "right",
                                              "service_timeout",
                                              "output_dir",
                                              "cases"};
  std::vector<std::string> all;
  ros::param::getParamNames(all);
  const std::string prefix = pnh.getNamespace() + "/";
  for (const auto& name : all) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string key =
        name.substr(prefix.size(), name.find('/', prefix.size()) - prefix.size());
    if (!known.count(key)) throw std::invalid_argument(key + ": unknown parameter");
  }
  Settings s;
  auto get = [&](const std::string& name, double* value) {
    XmlRpc::XmlRpcValue v;
    if (pnh.getParam(name, v)) *value = number(v, name);
  };
  WheelsetParameters& p = s.vehicle;
  get("r0", &p.r0);
  get("l0", &p.l0);
  get("conicity", &p.conicity);
  get("mass", &p.mass);
  get("yaw_inertia", &p.yawInertia);
  get("lateral_stiffness", &p.lateralStiffness);
  get("yaw_stiffness", &p.yawStiffness);
  get("wheel_load", &p.wheelLoad);
  get("contact_angle", &p.contactAngle);
  validate(p);
  get("dt", &s.dt);
  // Whole microseconds: stamps are integer nanoseconds, so every step's dt is exactly s.dt.
  if (!(s.dt >= 1e-5 && s.dt <= 0.01) || std::fabs(s.dt * 1e6 - std::round(s.dt * 1e6)) > 1e-6)
    throw std::invalid_argument("dt: must be a whole number of microseconds in [1e-5, 0.01] s");
  get("service_timeout", &s.serviceTimeout);
  if (!(s.serviceTimeout > 0.0 && s.serviceTimeout <= 3600.0))
    throw std::invalid_argument("service_timeout: must be in (0, 3600] s");
  pnh.getParam("left", s.left);
  pnh.getParam("right", s.right);
  pnh.getParam("output_dir", s.outputDir);
  XmlRpc::XmlRpcValue cases;
  if (!pnh.getParam("cases", cases) || cases.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      cases.size() == 0)
    throw std::invalid_argument("cases: required, a non-empty list of cases");
  std::set<std::string> names;
  for (int i = 0; i < cases.size(); ++i) {
    s.cases.push_back(readCase(cases[i], static_cast<size_t>(i)));
    if (!names.insert(s.cases.back().name).second)
      throw std::invalid_argument("cases: name '" + s.cases.back().name + "' used twice");
  }
  return s;
}

/// One contact_node seen through its services.
class Contact {
 public:
  Contact(ros::NodeHandle& nh, const std::string& ns) : nh_(nh), ns_(nh.resolveName(ns)) {}

  /// Waits for both services (the event itself, bounded by the timeout), then connects. The
  /// persistent step client is made only now: made before its server exists, its first call
  /// failed.
  bool connect(double timeout) {
    if (!ros::service::waitForService(ns_ + "/step", ros::Duration(timeout)) ||
        !ros::service::waitForService(ns_ + "/reset", ros::Duration(timeout)))
      return false;
    step_ = nh_.serviceClient<Step>(ns_ + "/step", true);
    reset_ = nh_.serviceClient<Reset>(ns_ + "/reset");
    return true;
  }

  void reset() {
    Reset srv;
    if (!reset_.call(srv) || !srv.response.success)
      throw std::runtime_error(ns_ + "/reset: call failed");
  }

  /// One lock-step contact step. Any status but OK stops the run: a refused or rejected step has no
  /// force a simulator should integrate.
  ContactForces step(const ros::Time& stamp, double V, const ContactKinematics& k) {
    Step srv;  // fields this code does not set (e.g. optional geometry) stay 0: not given
    srv.request.stamp = stamp;
    srv.request.velocity = V;
    srv.request.longitudinal = k.xi;
    srv.request.lateral = k.eta;
    srv.request.spin = k.phi;
    srv.request.normal_force = k.fz;
    if (!step_.call(srv)) throw std::runtime_error(ns_ + "/step: call failed");
    const auto& r = srv.response;
    if (r.status != 0)
      throw std::runtime_error(ns_ + "/step at t = " + std::to_string(stamp.toSec()) +
                               " s: status " + std::to_string(r.status) + ": " + r.message);
    model_ = r.model;
    return {r.fx, r.fy, r.mz};
  }

  const std::string& model() const { return model_; }

 private:
  ros::NodeHandle nh_;
  std::string ns_;
  ros::ServiceClient step_, reset_;
  std::string model_;
};

struct Sample {
  double t;
  WheelsetState s;
  double yTrack;
  ContactKinematics kl, kr;
  ContactForces fl, fr;
};

/// The figures of one case, as printed and written to the summary.
std::string runCase(const Settings& set, const Case& c, size_t index, Contact& left,
                    Contact& right) {
  left.reset();
  right.reset();
  const WheelsetParameters& p = set.vehicle;
  Irregularity track;
  track.amplitude = c.amplitude;
  track.wavelength = c.wavelength;
  WheelsetState s;
  s.y = c.y0;
  const int64_t dtNs = std::llround(set.dt * 1e9);
  const double dt = static_cast<double>(dtNs) * 1e-9;
  const int64_t steps = std::llround(c.duration / dt);
  // Each case on its own stretch of sim time (after the reset the contacts accept any stamp; the
  // offset keeps stamps increasing across cases anyway, for anyone recording the outputs).
  const int64_t base = (1000 + 1000 * static_cast<int64_t>(index)) * 1000000000LL;
  std::vector<Sample> history;
  history.reserve(static_cast<size_t>(steps) + 1);
  for (int64_t k = 0; k <= steps; ++k) {
    const ros::Time stamp = ros::Time().fromNSec(static_cast<uint64_t>(base + k * dtNs));
    Sample h;
    h.t = static_cast<double>(k) * dt;
    h.s = s;
    h.yTrack = track.lateral(s.x);
    wheelsetCreepages(p, track, s, c.speed, &h.kl, &h.kr);
    h.fl = left.step(stamp, c.speed, h.kl);
    h.fr = right.step(stamp, c.speed, h.kr);
    history.push_back(h);
    advanceWheelset(p, h.fl, h.fr, c.speed, dt, &s);
    // Flange contact is not modelled: beyond 10 mm the linearised geometry means nothing.
    if (!(std::fabs(s.y) < 0.01 && std::fabs(s.psi) < 0.05))
      throw std::runtime_error("case " + c.name + ": the wheelset left the linear range at t = " +
                               std::to_string(h.t) + " s (|y| >= 10 mm or |psi| >= 0.05 rad)");
    if (!ros::ok()) throw std::runtime_error("interrupted");
  }
  const std::string model = left.model();
  if (!set.outputDir.empty()) {
    const std::string file = set.outputDir + "/wheelset_" + model + "_" + c.name + ".csv";
    std::ofstream out(file);
    out.precision(10);
    out << "t,x,y,psi,vy,vpsi,y_track,xi_left,xi_right,eta,phi_left,phi_right,fx_left,fy_left,"
           "mz_left,fx_right,fy_right,mz_right\n";
    for (const auto& h : history)
      out << h.t << ',' << h.s.x << ',' << h.s.y << ',' << h.s.psi << ',' << h.s.vy << ','
          << h.s.vpsi << ',' << h.yTrack << ',' << h.kl.xi << ',' << h.kr.xi << ',' << h.kl.eta
          << ',' << h.kl.phi << ',' << h.kr.phi << ',' << h.fl.fx << ',' << h.fl.fy << ','
          << h.fl.mz << ',' << h.fr.fx << ',' << h.fr.fy << ',' << h.fr.mz << '\n';
    if (!out) throw std::runtime_error("output_dir: cannot write " + file);
  }
  std::vector<double> t, y, psi, fx;
  for (const auto& h : history) {
    t.push_back(h.t);
    y.push_back(h.s.y);
    psi.push_back(h.s.psi);
    fx.push_back(h.fl.fx);
  }
  char line[512];
  if (c.amplitude == 0.0) {
    const DecayFit f = fitDecay(t, y);
    if (!f.ok) throw std::runtime_error("case " + c.name + ": no decay fit: " + f.why);
    std::snprintf(line, sizeof line, "%s,%s,decay,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,,,,,,",
                  model.c_str(), c.name.c_str(), c.speed, c.y0, f.frequency, c.speed / f.frequency,
                  f.dampingRatio, klingelWavelength(p));
  } else {
    const double fr = c.speed / c.wavelength, t0 = c.fitFrom * c.duration;
    const HarmonicFit hf = fitHarmonic(t, fx, fr, t0), hy = fitHarmonic(t, y, fr, t0),
                      hp = fitHarmonic(t, psi, fr, t0);
    if (!hf.ok || !hy.ok || !hp.ok)
      throw std::runtime_error("case " + c.name + ": no harmonic fit (too few samples?)");
    const double A = std::fabs(c.amplitude);
    std::snprintf(line, sizeof line, "%s,%s,irregularity,%.6g,,,,,,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g",
                  model.c_str(), c.name.c_str(), c.speed, c.wavelength, fr, hf.amplitude / A,
                  hf.phase * 180.0 / M_PI, hy.amplitude / A, hp.amplitude / A);
  }
  return line;
}

const char* kSummaryHeader =
    "model,case,kind,speed,y0,frequency,wavelength,damping_ratio,klingel_wavelength,"
    "irregularity_wavelength,frequency_forced,fx_per_m,fx_phase_deg,y_per_m,psi_per_m";

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "wheelset_sim");
  ros::NodeHandle nh, pnh("~");
  Settings set;
  try {
    set = readSettings(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("wheelset_sim: invalid parameter %s", e.what());
    return 1;
  }
  Contact left(nh, set.left), right(nh, set.right);
  if (!left.connect(set.serviceTimeout) || !right.connect(set.serviceTimeout)) {
    ROS_FATAL(
        "wheelset_sim: the contacts' step/reset services (%s, %s) did not appear within "
        "service_timeout = %g s",
        nh.resolveName(set.left).c_str(), nh.resolveName(set.right).c_str(), set.serviceTimeout);
    return 1;
  }
  std::printf("wheelset_sim: columns %s\n", kSummaryHeader);
  std::vector<std::string> rows;
  try {
    for (size_t i = 0; i < set.cases.size(); ++i) {
      const ros::WallTime start = ros::WallTime::now();
      rows.push_back(runCase(set, set.cases[i], i, left, right));
      std::printf("wheelset_sim: result %s  (%.1f s wall)\n", rows.back().c_str(),
                  (ros::WallTime::now() - start).toSec());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    ROS_FATAL("wheelset_sim: %s", e.what());
    return 1;
  }
  if (!set.outputDir.empty()) {
    const std::string file = set.outputDir + "/wheelset_" + left.model() + "_summary.csv";
    std::ofstream out(file);
    out << kSummaryHeader << '\n';
    for (const auto& r : rows) out << r << '\n';
    if (!out) {
      ROS_FATAL("wheelset_sim: output_dir: cannot write %s", file.c_str());
      return 1;
    }
  }
  return 0;
}
