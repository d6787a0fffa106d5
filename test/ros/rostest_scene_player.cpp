// rostest: scene_player (the simulator stand-in) -> contact_node gives, row by row, the forces of
// `contact_cli run` on the same scene file with the node's parameters, to 1e-9; stamps = offset +
// t. Private parameters: ns, scene, config, stamp_offset, rows (expected count).
#include <fstream>

#include "rostest_helpers.hpp"
#include "wheel_rail_contact/scenario.hpp"

using namespace wrc_test;

TEST(ScenePlayer, ThePlayedSceneGivesContactCliForces) {
  ros::NodeHandle nh, pnh("~");
  std::string ns, scene, config;
  double offset = 0.0;
  ASSERT_TRUE(pnh.getParam("ns", ns) && pnh.getParam("scene", scene) &&
              pnh.getParam("config", config) && pnh.getParam("stamp_offset", offset));
  std::ifstream in(scene);
  const auto rows = wheel_rail_contact::readScenario(in, scene);
  std::vector<ContactState> got;
  ros::Subscriber sub = nh.subscribe<ContactState>(
      ns + "/contact_state", 10000, [&](const ContactState::ConstPtr& m) { got.push_back(*m); });
  ASSERT_TRUE(spinUntil([&] { return got.size() >= rows.size(); }, 40.0))
      << got.size() << " of " << rows.size() << " steps arrived";
  spinFor(0.2);
  ASSERT_EQ(got.size(), rows.size());
  std::string out;
  const std::string command = std::string(WRC_CONTACT_CLI) + " run --scenario '" + scene +
                              "' --config '" + config + "'" + cliOptionsOf(ns + "/contact_node");
  ASSERT_EQ(run(command, &out), 0) << command << "\n" << out;
  const auto ref = parseCliOutput(out);
  ASSERT_EQ(ref.size(), rows.size());
  double scale = 0.0;
  for (const auto& r : ref) scale = std::max({scale, std::fabs(r.fx), std::fabs(r.fy)});
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_NEAR(got[k].header.stamp.toSec(), offset + rows[k].t, 1e-6);
    EXPECT_EQ(got[k].fz, rows[k].fz) << "row " << k;
    EXPECT_NEAR(got[k].fx, ref[k].fx, 1e-9 * scale) << "row " << k;
    EXPECT_NEAR(got[k].fy, ref[k].fy, 1e-9 * scale) << "row " << k;
    EXPECT_EQ(statusText(got[k].status), ref[k].status) << "row " << k;
  }
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "scene_player_test");
  return RUN_ALL_TESTS();
}
