// contact_cli freq: a model's non-steady creep coefficient against lambda/a (usage in cli.cpp).
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace wheel_rail_contact {

/// Options as parsed by contact_cli (--name value, names in order). Writes the CSV to `out`;
/// throws std::invalid_argument naming the option on bad input or for a model without a
/// frequency response.
int freqCommand(const std::map<std::string, std::string>& values,
                const std::vector<std::string>& names, std::ostream& out);

}  // namespace wheel_rail_contact
