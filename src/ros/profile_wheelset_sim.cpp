// profile_wheelset_sim: the closed-loop demo on real profiles (doc/wheelset_demo.md). One wheelset
// on tangent track (src/demo/profile_wheelset.hpp) whose wheels run on S1002 on UIC60 1:40 through
// WheelsetContact in this process: every step the wheelset's pose and motion go in, each wheel's
// patches and forces come out, their sum in the track frame drives the lateral and yaw equations.
// One contact table, built at start-up, serves every model and case.
//
// It runs every case with every model (private parameter `models`), writes one CSV per model and
// case, a summary CSV and the profiles' kinematics into output_dir (if set), prints one `result`
// line per model and case on stdout and exits (0, or 1 on any error: a parameter, a wheel's
// status that is not ok, the wheelset beyond the kinematics' range).
//
// Private parameters (defaults and sources in doc/wheelset_demo.md): mass, yaw_inertia,
// lateral_stiffness, yaw_stiffness, wheel_load; mu (friction, default 0.3); models (default
// [steady, nss]); dt [s] (default 0.001); output_dir (default "": no files); cases: a list of
// {name, speed [m/s], duration [s], y0 [m], impact_force [N], impact_start [s], impact_duration
// [s], amplitude [m], wavelength [m], fit_from [fraction of duration, default 0.5]}. Each case's
// figures: the sustained oscillation of y after fit_from (amplitude, wavelength; the equivalent
// conicity at that amplitude and Klingel's wavelength with it), the largest |y|, and the steps
// with a flange patch, with two patches on one wheel and with a patch the creep-force model refused
// (its tangential forces zero: an elliptic-patch model takes a/b up to 10, a flange patch can be
// longer), the largest lateral force of a wheel on its rail and its ratio to the wheel load.
#include <ros/ros.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "../demo/profile_wheelset.hpp"

namespace {

using namespace wheel_rail_contact;
namespace demo = wheel_rail_contact::demo;

struct Case {
  std::string name;
  double speed = 40.0, duration = 1.0, y0 = 0.0, fitFrom = 0.5;
  demo::LateralImpulse impulse;
  demo::Irregularity track;
};

struct Settings {
  demo::ProfileWheelsetParameters vehicle;
  double mu = 0.3, dt = 0.001;
  std::vector<std::string> models = {"steady", "nss"};
  std::string outputDir;
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
  const std::map<std::string, double*> numbers = {{"speed", &k.speed},
                                                  {"duration", &k.duration},
                                                  {"y0", &k.y0},
                                                  {"fit_from", &k.fitFrom},
                                                  {"impact_force", &k.impulse.force},
                                                  {"impact_start", &k.impulse.start},
                                                  {"impact_duration", &k.impulse.duration},
                                                  {"amplitude", &k.track.amplitude},
                                                  {"wavelength", &k.track.wavelength}};
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
                                  ": unknown key (name, speed, duration, y0, fit_from, "
                                  "impact_force, impact_start, impact_duration, amplitude, "
                                  "wavelength)");
    }
  }
  if (k.name.empty() || k.name.find_first_of("/, \t") != std::string::npos)
    throw std::invalid_argument(where + ".name: required, without '/', ',' or blanks");
  if (!(k.speed >= 5.0 && k.speed < 200.0))
    throw std::invalid_argument(where + ".speed: must be in [5, 200) m/s");
  if (!(k.duration > 0.0 && k.duration <= 60.0))
    throw std::invalid_argument(where + ".duration: must be in (0, 60] s");
  if (!(std::fabs(k.y0) <= 0.006)) throw std::invalid_argument(where + ".y0: |y0| <= 0.006 m");
  if (!(k.fitFrom >= 0.0 && k.fitFrom < 1.0))
    throw std::invalid_argument(where + ".fit_from: must be in [0, 1)");
  if (!(std::fabs(k.impulse.force) <= 5e5))
    throw std::invalid_argument(where + ".impact_force: |impact_force| <= 5e5 N");
  if (!(k.impulse.start >= 0.0 && std::isfinite(k.impulse.start)))
    throw std::invalid_argument(where + ".impact_start: must be >= 0");
  if (!(k.impulse.duration >= 0.0 && k.impulse.duration <= 1.0))
    throw std::invalid_argument(where + ".impact_duration: must be in [0, 1] s");
  if (!(std::fabs(k.track.amplitude) <= 0.006))
    throw std::invalid_argument(where + ".amplitude: |amplitude| <= 0.006 m");
  if (!(k.track.wavelength >= 1.0 && std::isfinite(k.track.wavelength)))
    throw std::invalid_argument(where + ".wavelength: must be >= 1 m");
  return k;
}

Settings readSettings(const ros::NodeHandle& pnh) {
  static const std::set<std::string> known = {
      "mass",   "yaw_inertia", "lateral_stiffness", "yaw_stiffness", "wheel_load", "mu",
      "models", "dt",          "output_dir",        "cases"};
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
  demo::ProfileWheelsetParameters& p = s.vehicle;
  get("mass", &p.mass);
  get("yaw_inertia", &p.yawInertia);
  get("lateral_stiffness", &p.lateralStiffness);
  get("yaw_stiffness", &p.yawStiffness);
  get("wheel_load", &p.wheelLoad);
  demo::validate(p);
  get("mu", &s.mu);
  get("dt", &s.dt);
  // Whole microseconds, as wheelset_sim's: a step's dt is exact.
  if (!(s.dt >= 1e-5 && s.dt <= 0.002) || std::fabs(s.dt * 1e6 - std::round(s.dt * 1e6)) > 1e-6)
    throw std::invalid_argument("dt: must be a whole number of microseconds in [1e-5, 0.002] s");
  pnh.getParam("output_dir", s.outputDir);
  if (pnh.hasParam("models")) {
    s.models.clear();
    if (!pnh.getParam("models", s.models) || s.models.empty())
      throw std::invalid_argument("models: expected a non-empty list of model names");
    std::set<std::string> seen;
    for (const auto& m : s.models) {
      if (!seen.insert(m).second) throw std::invalid_argument("models: '" + m + "' listed twice");
      ContactParameters c;
      c.model = m;
      validate(c);  // names the parameter: "model: ..."
    }
  }
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

const char* zoneName(ContactZone z) {
  return z == ContactZone::kTread ? "tread" : z == ContactZone::kFlange ? "flange" : "gauge_corner";
}

/// The figures of one model and case, as printed and written to the summary.
std::string runCase(const Settings& set, const Case& c, const std::string& model,
                    demo::ProfileWheelset* ws) {
  demo::WheelsetState s;
  s.y = c.y0;
  ws->reset(s);
  const long steps = std::lround(c.duration / set.dt);
  std::vector<double> t, y;
  std::ofstream out;
  if (!set.outputDir.empty()) {
    const std::string file = set.outputDir + "/profile_" + model + "_" + c.name + ".csv";
    out.open(file);
    if (!out) throw std::runtime_error("output_dir: cannot write " + file);
    out.precision(9);
    out << "t,x,y,psi,vy,vpsi,y_track,roll,z,impulse,fy,mz";
    for (const char* w : {"left", "right"}) {
      out << ",fy_" << w << ",fz_" << w << ",patches_" << w;
      for (int k = 1; k <= 2; ++k)
        out << ",zone" << k << '_' << w << ",rail_y" << k << '_' << w << ",wheel_y" << k << '_' << w
            << ",angle" << k << '_' << w << ",fn" << k << '_' << w << ",fx" << k << '_' << w
            << ",fs" << k << '_' << w;
    }
    out << '\n';
  }
  long flangeSteps = 0, twoPointSteps = 0, rejectedSteps = 0;
  double maxY = 0.0, maxFy = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k <= steps; ++k) {
    demo::ProfileStep st;
    std::string why;
    if (!ws->step(c.speed, set.dt, c.track, c.impulse, static_cast<double>(k) * set.dt, &st, &why))
      throw std::runtime_error("model " + model + ", case " + c.name + " at t = " +
                               std::to_string(static_cast<double>(k) * set.dt) + " s: " + why);
    t.push_back(st.t);
    y.push_back(st.s.y);
    maxY = std::max(maxY, std::fabs(st.s.y));
    bool flange = false, twoPoint = false, rejected = false;
    for (const WheelResult* w : {&st.contact.left, &st.contact.right}) {
      twoPoint = twoPoint || w->patches.size() >= 2;
      for (const PatchResult& p : w->patches) {
        flange = flange || p.zone == ContactZone::kFlange;
        rejected = rejected || p.tangential_status != StepStatus::kOk;
      }
    }
    flangeSteps += flange;
    twoPointSteps += twoPoint;
    rejectedSteps += rejected;
    maxFy = std::max({maxFy, std::fabs(st.left.force.y()), std::fabs(st.right.force.y())});
    if (out.is_open()) {
      out << st.t << ',' << st.s.x << ',' << st.s.y << ',' << st.s.psi << ',' << st.s.vy << ','
          << st.s.vpsi << ',' << st.yTrack << ',' << st.roll << ',' << st.z << ',' << st.impulse
          << ',' << st.fy << ',' << st.mz;
      for (const auto* w : {&st.contact.left, &st.contact.right}) {
        const demo::WheelTotals& tot = w == &st.contact.left ? st.left : st.right;
        out << ',' << tot.force.y() << ',' << tot.force.z() << ',' << w->patches.size();
        for (size_t k2 = 0; k2 < 2; ++k2) {
          if (k2 < w->patches.size()) {
            const PatchResult& p = w->patches[k2];
            out << ',' << zoneName(p.zone) << ',' << p.geometry.rail_file.x() << ','
                << p.geometry.wheel_file.x() << ',' << p.geometry.contact_angle << ','
                << p.normal.fn << ',' << p.fx << ',' << p.fs;
          } else {
            out << ",,,,,,,";
          }
        }
      }
      out << '\n';
    }
    if (!ros::ok()) throw std::runtime_error("interrupted");
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (out.is_open() && !out) throw std::runtime_error("output_dir: write failed");
  const demo::CycleFit f = demo::fitCycle(t, y, c.fitFrom * c.duration);
  const demo::RigidKinematics& kin = ws->kinematics();
  const double lambda = f.ok ? kin.equivalentConicity(f.amplitude) : std::nan("");
  const double klingel = f.ok ? kin.klingelWavelength(f.amplitude) : std::nan("");
  auto g = [](double v) {
    char b[32];
    if (!std::isfinite(v)) return std::string();
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::string(b);
  };
  return model + "," + c.name + "," + g(c.speed) + "," + g(f.ok ? f.amplitude : std::nan("")) +
         "," + g(f.ok ? f.frequency : std::nan("")) + "," +
         g(f.ok ? c.speed / f.frequency : std::nan("")) + "," + g(lambda) + "," + g(klingel) + "," +
         g(maxY) + "," + std::to_string(flangeSteps) + "," + std::to_string(twoPointSteps) + "," +
         std::to_string(rejectedSteps) + "," + g(maxFy) + "," + g(maxFy / set.vehicle.wheelLoad) +
         "," + std::to_string(steps + 1) + "," + g(wall * 1e6 / static_cast<double>(steps + 1));
}

const char* kSummaryHeader =
    "model,case,speed,amplitude,frequency,wavelength,equivalent_conicity,klingel_wavelength,"
    "max_abs_y,flange_steps,two_point_steps,rejected_steps,max_wheel_fy,max_wheel_fy_per_load,"
    "steps,"
    "us_per_step";

/// The profiles and their rigid kinematics, for the plot.
void writeGeometry(const std::string& dir, const WheelsetTrackData& track,
                   const demo::RigidKinematics& kin) {
  std::ofstream p(dir + "/profile_geometry.csv");
  p.precision(9);
  p << "profile,y_file,z_file\n";
  const auto rail = track.rail_right ? track.rail_right : Profile::standardRail();
  const auto wheel = track.wheel_right ? track.wheel_right : Profile::standardWheel();
  for (const auto& pr : {std::make_pair("rail", rail), std::make_pair("wheel", wheel)})
    for (const Eigen::Vector2d& q : pr.second->points()) {
      const Eigen::Vector2d f = pr.second->toFile(q);
      p << pr.first << ',' << f.x() << ',' << f.y() << '\n';
    }
  std::ofstream k(dir + "/profile_kinematics.csv");
  k.precision(9);
  k << "y,roll,z,r_left,r_right,radius_difference,amplitude,equivalent_conicity,"
       "klingel_wavelength\n";
  for (const auto& s : kin.samples()) {
    const double A = std::fabs(s.y);
    k << s.y << ',' << s.roll << ',' << s.z << ',' << s.r_left << ',' << s.r_right << ','
      << s.r_left - s.r_right << ',';
    if (s.y > 0.0)
      k << A << ',' << kin.equivalentConicity(A) << ',' << kin.klingelWavelength(A) << '\n';
    else
      k << ",,\n";
  }
  if (!p || !k) throw std::runtime_error("output_dir: cannot write the geometry files");
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "profile_wheelset_sim");
  ros::NodeHandle pnh("~");
  Settings set;
  try {
    set = readSettings(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("profile_wheelset_sim: invalid parameter %s", e.what());
    return 1;
  }
  try {
    const WheelsetTrackData track;  // S1002 on UIC60 1:40, 1435 mm gauge, 1360 mm flange backs
    const auto t0 = std::chrono::steady_clock::now();
    auto kin = std::make_shared<const demo::RigidKinematics>(track);
    // One table for every model and case, over what the wheelset reaches: flange contact at
    // 6-7 mm with up to 7 mrad of roll; a pose beyond it is answered by the direct search.
    ContactTableOptions to;
    to.max_abs_lateral = 0.012;
    to.max_abs_yaw = 0.01;
    to.yaw_step = 0.005;
    to.max_abs_roll = 0.0075;
    auto table = std::make_shared<const ContactTable>(ContactSearch(track), to);
    std::printf("profile_wheelset_sim: kinematics and contact table in %.1f s wall (%.1f MB)\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                static_cast<double>(table->bytes()) / 1e6);
    if (!set.outputDir.empty()) writeGeometry(set.outputDir, track, *kin);
    std::printf("profile_wheelset_sim: columns %s\n", kSummaryHeader);
    std::fflush(stdout);
    std::vector<std::string> rows;
    for (const auto& model : set.models) {
      ContactParameters cp;
      cp.model = model;
      cp.mu = set.mu;
      WheelsetContactOptions o;
      o.contact_table = table;
      demo::ProfileWheelset ws(set.vehicle, track, kin, cp, o);
      for (const Case& c : set.cases) {
        const ros::WallTime start = ros::WallTime::now();
        rows.push_back(runCase(set, c, model, &ws));
        std::printf("profile_wheelset_sim: result %s  (%.1f s wall)\n", rows.back().c_str(),
                    (ros::WallTime::now() - start).toSec());
        std::fflush(stdout);
      }
    }
    if (!set.outputDir.empty()) {
      const std::string file = set.outputDir + "/profile_summary.csv";
      std::ofstream out(file);
      out << kSummaryHeader << '\n';
      for (const auto& r : rows) out << r << '\n';
      if (!out) throw std::runtime_error("output_dir: cannot write " + file);
    }
  } catch (const std::exception& e) {
    ROS_FATAL("profile_wheelset_sim: %s", e.what());
    return 1;
  }
  return 0;
}
