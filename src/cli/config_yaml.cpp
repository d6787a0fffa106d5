#include "config_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

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

void loadConfigYaml(const std::string& file, ContactParameters* p) {
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
      setParameter(p, key, kv.second.Scalar());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + " (in '" + file + "')");
    }
  }
}

}  // namespace wheel_rail_contact
