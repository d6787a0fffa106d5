/// The text of the standard profile files compiled into the library (Profile::standardWheel(),
/// Profile::standardRail()).
#pragma once

namespace wheel_rail_contact {

const char* standardWheelProfileText();  ///< MBench_S1002_v3.prw, verbatim
const char* standardRailProfileText();   ///< MBench_UIC60_v3.prr, verbatim

}  // namespace wheel_rail_contact
