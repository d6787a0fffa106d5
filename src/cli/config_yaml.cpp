#include "config_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace wheel_rail_contact {

std::vector<ParameterDoc> nodeParameterDocs() {
  return {
      {"frame_id", "", "<namespace>_contact",
       "frame_id of the outputs (the contact frame); default from the namespace, e.g. "
       "/bogie1/wheelset1/left -> bogie1_wheelset1_left_contact"},
      {"load_pairing", "", "stamp",
       "stamp (a creepage steps with the normal load of its stamp) | latest (the latest load)"},
      {"load_wait", "s", "0.1",
       "stamp pairing: longest wall time a creepage waits for its load, [0, 60]; then the latest "
       "load is used and flagged"},
      {"queue_size", "-", "100", "subscriber queue length of creepage and normal_load (>= 1)"},
      {"publish_queue_size", "-", "100", "publisher queue length of the outputs (>= 1)"},
      {"max_dt", "s", "1", "a creepage stamp more than this after the previous one is rejected"},
      {"time_jump_reset", "s", "0",
       "a stamp this far behind the previous one resets the state; 0 = off (rejected instead)"},
      {"max_load_age", "s", "1", "warn when the latest normal load is older than this; 0 = off"},
      {"diagnostic_period", "s", "1", "period of the diagnostics on /diagnostics"},
  };
}

bool isNodeOnlyParameter(const std::string& name) {
  for (const auto& d : nodeParameterDocs())
    if (d.name == name) return true;
  return false;
}

namespace {

// Every key of the YAML map in `file`, with its scalar value, to `apply` (which throws
// std::invalid_argument naming the key); the file is named in every message.
void forEachKey(const std::string& file,
                const std::function<void(const std::string&, const std::string&)>& apply) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const std::exception& e) {  // YAML::Exception, or std::ios_base::failure (a directory)
    throw std::invalid_argument("config: cannot read '" + file + "': " + e.what());
  }
  if (root.IsNull()) return;  // an empty file: all defaults
  if (!root.IsMap())
    throw std::invalid_argument("config: '" + file + "' is not a YAML map of name: value");
  for (const auto& kv : root) {
    if (!kv.first.IsScalar())
      throw std::invalid_argument("config: '" + file + "' has a key that is not a name");
    const std::string key = kv.first.Scalar();
    if (!kv.second.IsScalar())
      throw std::invalid_argument(key + ": expected a single value (in '" + file + "')");
    if (isNodeOnlyParameter(key)) continue;
    try {
      apply(key, kv.second.Scalar());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + " (in '" + file + "')");
    }
  }
}

double number(const std::string& name, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(v))
    throw std::invalid_argument(name + ": expected a finite number, got '" + value + "'");
  return v;
}

}  // namespace

void loadConfigYaml(const std::string& file, ContactParameters* p) {
  forEachKey(
      file, [p](const std::string& key, const std::string& value) { setParameter(p, key, value); });
}

std::vector<ParameterDoc> wheelsetParameterDocs() {
  const WheelsetTrackData d;
  const auto text = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  return {
      {"nominal_radius", "m", text(d.nominal_radius),
       "rolling radius where the wheel profile file has z = 0"},
      {"flange_back_distance", "m", text(d.flange_back_distance),
       "distance between the two wheels' flange backs"},
      {"flange_back_position", "m", text(d.flange_back_position),
       "lateral coordinate of the flange back in the wheel profile file's own coordinates"},
      {"gauge", "m", text(d.gauge), "track gauge, between the gauge faces at gauge_depth"},
      {"gauge_depth", "m", text(d.gauge_depth), "depth below the rails' top of the gauge points"},
      {"rail_inclination", "-", text(d.rail_inclination),
       "tilt of the rail profiles toward the centre (tangent, 0.025 = 1:40); 0: as read"},
      {"cant", "rad", text(WheelsetConfig{}.cant),
       "track's cant under the wheelset where the scenario has no cant column; positive raises "
       "the left rail"},
      {"profile_length_unit", "m", "file",
       "metres per profile file unit (0.001, or mm / m); default: the file says"},
      {"profile_lateral_axis", "", "toward_field",
       "profile files' first column: toward_field (Simpack, CONTACT) | toward_gauge"},
      {"profile_vertical_axis", "", "down", "profile files' second column: down | up"},
      {"profile_smoothing_length", "m", text(kDefaultProfileSmoothingLength),
       "smoothing spline's length L of the profiles (0 interpolates)"},
  };
}

bool setWheelsetParameter(WheelsetConfig* w, const std::string& name, const std::string& value) {
  static const std::pair<const char*, double WheelsetTrackData::*> kTrackNumbers[] = {
      {"nominal_radius", &WheelsetTrackData::nominal_radius},
      {"flange_back_distance", &WheelsetTrackData::flange_back_distance},
      {"flange_back_position", &WheelsetTrackData::flange_back_position},
      {"gauge", &WheelsetTrackData::gauge},
      {"gauge_depth", &WheelsetTrackData::gauge_depth},
      {"rail_inclination", &WheelsetTrackData::rail_inclination}};
  for (const auto& [key, field] : kTrackNumbers)
    if (name == key) {
      w->track.*field = number(name, value);
      return true;
    }
  ProfileReadOptions& r = w->profile_read;
  if (name == "cant") {
    w->cant = number(name, value);
    if (!(std::abs(w->cant) <= kMaxCant)) {
      std::ostringstream m;
      m << name << ": must be within +-" << kMaxCant << " rad, got '" << value << "'";
      throw std::invalid_argument(m.str());
    }
  } else if (name == "profile_length_unit") {
    r.length_unit = value == "mm" ? 1e-3 : value == "m" ? 1.0 : number(name, value);
    if (!(r.length_unit > 0.0))
      throw std::invalid_argument(name + ": must be > 0 (metres per file unit), got '" + value +
                                  "'");
  } else if (name == "profile_lateral_axis") {
    if (value == "toward_field")
      r.lateral = LateralAxis::kTowardField;
    else if (value == "toward_gauge")
      r.lateral = LateralAxis::kTowardGauge;
    else
      throw std::invalid_argument(name + ": toward_field or toward_gauge, got '" + value + "'");
  } else if (name == "profile_vertical_axis") {
    if (value == "down")
      r.vertical = VerticalAxis::kDown;
    else if (value == "up")
      r.vertical = VerticalAxis::kUp;
    else
      throw std::invalid_argument(name + ": down or up, got '" + value + "'");
  } else if (name == "profile_smoothing_length") {
    r.smoothing_length = number(name, value);
    if (!(r.smoothing_length >= 0.0))
      throw std::invalid_argument(name + ": must be >= 0 m, got '" + value + "'");
  } else {
    return false;
  }
  return true;
}

void loadWheelsetConfigYaml(const std::string& file, ContactParameters* p, WheelsetConfig* w) {
  forEachKey(file, [p, w](const std::string& key, const std::string& value) {
    if (!setWheelsetParameter(w, key, value)) setParameter(p, key, value);
  });
}

}  // namespace wheel_rail_contact
