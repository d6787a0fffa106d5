// rostest: vehicle_node with an invalid configuration exits with code 1 after a ROS_FATAL naming
// the parameter (a contact's own parameters as CONTACT/NAME): a missing, empty or malformed contact
// list, a repeated or invalid name, an unknown key (shared or per contact, or under a name that is
// not a contact), values out of range. Never a crash.
#include "rostest_helpers.hpp"

using namespace wrc_test;

namespace {

int counter = 0;

/// vehicle_node as a fresh node with `params`.
void expectFatal(const std::vector<std::pair<std::string, XmlRpc::XmlRpcValue>>& params,
                 const std::string& text) {
  expectFatalParameters(WRC_VEHICLE_NODE, "vehicle_bad_" + std::to_string(++counter), params, text);
}

XmlRpc::XmlRpcValue list(const std::vector<std::string>& names) {
  XmlRpc::XmlRpcValue v;
  v.setSize(static_cast<int>(names.size()));
  for (size_t i = 0; i < names.size(); ++i) v[static_cast<int>(i)] = names[i];
  return v;
}

XmlRpc::XmlRpcValue two() {
  return list({"left", "right"});
}

}  // namespace

TEST(VehicleBadParameters, ContactListErrorsNameIt) {
  expectFatal({}, "contacts: not set");
  expectFatal({{"contacts", list({})}}, "contacts: expected a non-empty list");
  expectFatal({{"contacts", XmlRpc::XmlRpcValue("left")}}, "contacts: expected a non-empty list");
  expectFatal({{"contacts", list({"left", "left"})}}, "contacts: 'left' is listed twice");
  expectFatal({{"contacts", list({"left", "1st"})}}, "contacts: '1st' is not a name");
  expectFatal({{"contacts", list({"left", "a/b"})}}, "contacts: 'a/b' is not a name");
  expectFatal({{"contacts", list({"left", "mu"})}}, "contacts: 'mu' is a parameter's name");
}

TEST(VehicleBadParameters, UnknownKeysFail) {
  expectFatal({{"contacts", two()}, {"mux", XmlRpc::XmlRpcValue(0.3)}}, "mux: unknown parameter");
  expectFatal({{"contacts", two()}, {"left/mux", XmlRpc::XmlRpcValue(0.3)}},
              "left/mux: unknown parameter");
  expectFatal({{"contacts", two()}, {"middle/mu", XmlRpc::XmlRpcValue(0.3)}},
              "middle/mu: unknown parameter (middle is not in ~contacts)");
}

TEST(VehicleBadParameters, ValuesOutOfRangeNameTheContact) {
  expectFatal({{"contacts", two()}, {"right/mu", XmlRpc::XmlRpcValue(-1.0)}}, "right/mu");
  expectFatal({{"contacts", two()}, {"nu", XmlRpc::XmlRpcValue(0.7)}}, "left/nu");
  expectFatal({{"contacts", two()}, {"left/model", XmlRpc::XmlRpcValue("fastest")}}, "left/model");
  expectFatal({{"contacts", two()}, {"left/mesh", XmlRpc::XmlRpcValue("auto")}},
              "left/mesh: 'auto' was renamed 'adaptive'");
  expectFatal({{"contacts", two()}, {"right/fastsim", XmlRpc::XmlRpcValue("")}},
              "right/fastsim: must be calibrated or classic");
  expectFatal({{"contacts", two()}, {"right/max_dt", XmlRpc::XmlRpcValue(0.0)}}, "right/max_dt");
  expectFatal({{"contacts", two()}, {"queue_size", XmlRpc::XmlRpcValue(0)}}, "queue_size");
  expectFatal({{"contacts", two()}, {"diagnostic_period", XmlRpc::XmlRpcValue(-1.0)}},
              "diagnostic_period");
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "vehicle_bad_parameters");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
