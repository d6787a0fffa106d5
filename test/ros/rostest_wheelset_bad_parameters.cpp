// rostest: wheelset_node with an invalid configuration exits with code 1 after a ROS_FATAL naming
// the parameter: a missing or malformed wheelset list, an unknown key, a profile path that is
// relative, in a package that does not exist or not a profile, wheelset data or model parameters
// out of range, a ~cant (each tick carries its own). Never a crash.
#include "rostest_helpers.hpp"

using namespace wrc_test;

namespace {

int counter = 0;

/// wheelset_node as a fresh node with `params` and the direct search (a valid configuration
/// starts at once).
void expectFatal(std::vector<std::pair<std::string, XmlRpc::XmlRpcValue>> params,
                 const std::string& text) {
  params.emplace_back("contact_table", XmlRpc::XmlRpcValue(false));
  expectFatalParameters(WRC_WHEELSET_NODE, "wheelset_bad_" + std::to_string(++counter), params,
                        text);
}

XmlRpc::XmlRpcValue names() {
  XmlRpc::XmlRpcValue v;
  v.setSize(2);
  v[0] = "front";
  v[1] = "rear";
  return v;
}

using P = std::pair<std::string, XmlRpc::XmlRpcValue>;

}  // namespace

TEST(WheelsetBadParameters, WheelsetListErrorsNameIt) {
  expectFatal({}, "wheelsets: not set");
  expectFatal({{"wheelsets", XmlRpc::XmlRpcValue("front")}},
              "wheelsets: expected a non-empty list");
  XmlRpc::XmlRpcValue twice = names();
  twice[1] = "front";
  expectFatal({{"wheelsets", twice}}, "wheelsets: 'front' is listed twice");
  XmlRpc::XmlRpcValue bad = names();
  bad[1] = "a/b";
  expectFatal({{"wheelsets", bad}}, "wheelsets: 'a/b' is not a name");
}

TEST(WheelsetBadParameters, UnknownKeysFail) {
  expectFatal({{"wheelsets", names()}, {"gauge_width", XmlRpc::XmlRpcValue(1.435)}},
              "gauge_width: unknown parameter");
  expectFatal({{"wheelsets", names()}, {"contacts", names()}}, "contacts: unknown parameter");
}

TEST(WheelsetBadParameters, ACantParameterFailsForTheTickCarriesIt) {
  // contact_cli wheelset's cant key (a scenario's default cant) is no parameter of the node: each
  // tick's WheelsetKinematics.cant is the cant; a ~cant, whatever its value, would go unused.
  expectFatal({{"wheelsets", names()}, {"cant", XmlRpc::XmlRpcValue(0.05)}},
              "cant: not a parameter of wheelset_node: each tick's WheelsetKinematics.cant");
  expectFatal({{"wheelsets", names()}, {"cant", XmlRpc::XmlRpcValue("steep")}}, "cant: not a");
}

TEST(WheelsetBadParameters, ProfilePathsNameTheParameter) {
  expectFatal({{"wheelsets", names()}, {"wheel_profile", XmlRpc::XmlRpcValue("profiles/x.prw")}},
              "wheel_profile: 'profiles/x.prw' is neither an absolute path");
  expectFatal(
      {{"wheelsets", names()}, {"rail_profile", XmlRpc::XmlRpcValue("package://no_such_pkg/x")}},
      "rail_profile: package 'no_such_pkg' not found");
  expectFatal({{"wheelsets", names()},
               {"rail_profile", XmlRpc::XmlRpcValue("package://wheel_rail_contact/none.prr")}},
              "rail_profile: ");
}

TEST(WheelsetBadParameters, ValuesOutOfRangeNameTheParameter) {
  expectFatal({{"wheelsets", names()}, {"gauge", XmlRpc::XmlRpcValue(3.0)}},
              "WheelsetTrackData: gauge");
  expectFatal({{"wheelsets", names()}, {"mu", XmlRpc::XmlRpcValue(-1.0)}}, "mu");
  expectFatal({{"wheelsets", names()}, {"model", XmlRpc::XmlRpcValue("fastest")}}, "model");
  expectFatal({{"wheelsets", names()}, {"max_dt", XmlRpc::XmlRpcValue(0.0)}}, "max_dt");
  expectFatal({{"wheelsets", names()}, {"queue_size", XmlRpc::XmlRpcValue(0)}}, "queue_size");
  expectFatal({{"wheelsets", names()}, {"profile_vertical_axis", XmlRpc::XmlRpcValue("left")}},
              "profile_vertical_axis");
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "wheelset_bad_parameters");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
