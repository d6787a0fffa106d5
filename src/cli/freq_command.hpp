// contact_cli freq: a model's non-steady creep coefficient against lambda/a (usage in cli.cpp).
#pragma once

#include <iosfwd>
#include <string>

#include "wheel_rail_contact/contact_parameters.hpp"

namespace wheel_rail_contact {

/// freq with the parameters p (validated) and its options' text (--kind, --ab, --lambda-over-a).
/// Writes the CSV to `out`; throws std::invalid_argument naming the option on bad input or for a
/// model without a frequency response.
int freqCommand(const ContactParameters& p, const std::string& kind, const std::string& ab,
                const std::string& lambdaOverA, std::ostream& out);

}  // namespace wheel_rail_contact
