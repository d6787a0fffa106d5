/// The text of the standard profile files shipped inside the library (Profile::standardWheel(),
/// Profile::standardRail()): config/profiles/, compiled in as they are (shipped_tables.hpp).
#pragma once

#include <string_view>

namespace wheel_rail_contact {

std::string_view standardWheelProfileText();  ///< MBench_S1002_v3.prw, verbatim
std::string_view standardRailProfileText();   ///< MBench_UIC60_v3.prr, verbatim

}  // namespace wheel_rail_contact
