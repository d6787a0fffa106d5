/// The node's YAML configuration file, read by contact_cli --config (yaml-cpp; never in the core).
/// Keys are exactly the parameter names of ContactParameters (the CLI's options); the node-only
/// keys below are accepted and ignored, so one file serves both tools and typos still fail.
#pragma once

#include <string>
#include <vector>

#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/profiles/profile.hpp"
#include "wheel_rail_contact/profiles/wheelset_track.hpp"
#include "wheel_rail_contact/wheelset/creepages.hpp"

namespace wheel_rail_contact {

/// contact_node's own private parameters (not in ContactParameters), with their defaults.
std::vector<ParameterDoc> nodeParameterDocs();

/// True if `name` is one of nodeParameterDocs().
bool isNodeOnlyParameter(const std::string& name);

/// Applies every key of the YAML map in `file` to *p (via setParameter). Throws
/// std::invalid_argument whose message starts with the offending key (or "config" when the file
/// cannot be read or is not a map).
void loadConfigYaml(const std::string& file, ContactParameters* p);

/// contact_cli wheelset's data besides the model's parameters: the wheelset and track (its
/// profiles are the command's files), how the profile files are read, and the cant of a scenario
/// without a cant column.
struct WheelsetConfig {
  WheelsetTrackData track;
  ProfileReadOptions profile_read;
  /// The track's cant under the wheelset [rad] (WheelsetMotion::cant) for every row of a scenario
  /// that has no cant column; |cant| <= kMaxCant.
  double cant = 0.0;
};

/// The keys of WheelsetConfig, with their defaults (the benchmark's, WheelsetTrackData{}).
std::vector<ParameterDoc> wheelsetParameterDocs();

/// Sets one wheelset key from text. Throws std::invalid_argument naming the key on a value that
/// does not parse; false if `name` is not a wheelset key. Ranges are
/// WheelsetTrackData::validate()'s and Profile::read()'s; cant's, |cant| <= kMaxCant, here.
bool setWheelsetParameter(WheelsetConfig* w, const std::string& name, const std::string& value);

/// As loadConfigYaml, and the keys of wheelsetParameterDocs() go to *w: one file for the model and
/// the wheelset.
void loadWheelsetConfigYaml(const std::string& file, ContactParameters* p, WheelsetConfig* w);

}  // namespace wheel_rail_contact
