// The standard profiles: the Manchester contact benchmark's S1002 wheel and UIC60 rail (1:40
// inclination built in), config/profiles/ (their provenance: config/profiles/README.md). Shipped in
// the library so that the defaults need no data file once installed.
#include "core/profiles/standard_profiles.hpp"

#include "wheel_rail_contact/shipped_tables.hpp"

namespace wheel_rail_contact {

std::string_view standardWheelProfileText() {
  return shippedTable("profiles/MBench_S1002_v3.prw");
}

std::string_view standardRailProfileText() {
  return shippedTable("profiles/MBench_UIC60_v3.prr");
}

}  // namespace wheel_rail_contact
