// contact_cli's commands, callable in-process so tests drive exactly what users run.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace wheel_rail_contact {

/// Runs contact_cli with `args` (without the program name). Returns the exit code.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace wheel_rail_contact
