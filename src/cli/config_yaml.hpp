/// The node's YAML configuration file, read by contact_cli --config (yaml-cpp; never in the core).
/// Keys are exactly the parameter names of ContactParameters (the CLI's options); the node-only
/// keys below are accepted and ignored, so one file serves both tools and typos still fail.
#pragma once

#include <string>
#include <vector>

#include "wheel_rail_contact/contact_parameters.hpp"

namespace wheel_rail_contact {

/// contact_node's own private parameters (not in ContactParameters), with their defaults.
std::vector<ParameterDoc> nodeParameterDocs();

/// True if `name` is one of nodeParameterDocs().
bool isNodeOnlyParameter(const std::string& name);

/// Applies every key of the YAML map in `file` to *p (via setParameter). Throws
/// std::invalid_argument whose message starts with the offending key (or "config" when the file
/// cannot be read or is not a map).
void loadConfigYaml(const std::string& file, ContactParameters* p);

}  // namespace wheel_rail_contact
