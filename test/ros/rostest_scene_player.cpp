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
  std::vector<wheel_rail_contact::ScenarioRow> rows;
  std::vector<Row> ref;
  ASSERT_TRUE(sceneAndCliReference(ns, scene, config, &rows, &ref));
  std::vector<ContactState> got;
  ros::Subscriber sub = nh.subscribe<ContactState>(
      ns + "/contact_state", 10000, [&](const ContactState::ConstPtr& m) { got.push_back(*m); });
  const std::string topic = nh.resolveName(ns + "/contact_state");
  ASSERT_TRUE(spinUntil([&] { return publishersConnectedToUs(topic); }, 30.0));
  // scene_player waits for the node's subscriptions itself; it runs to its end here (the outputs
  // queue up in our subscriber meanwhile).
  std::string log;
  const std::string player = std::string(WRC_SCENE_PLAYER) + " __name:=scene_player __ns:=" + ns +
                             " _scene:='" + scene + "' _time_scale:=25 _start_delay:=0" +
                             " _stamp_offset:=" + std::to_string(offset);
  ASSERT_EQ(run(player, &log), 0) << player << "\n" << log;
  ASSERT_TRUE(spinUntil([&] { return got.size() >= rows.size(); }, 40.0))
      << got.size() << " of " << rows.size() << " steps arrived";
  ASSERT_EQ(got.size(), rows.size());
  ASSERT_EQ(ref.size(), rows.size());
  double scale = 0.0;
  for (const auto& r : ref) scale = std::max({scale, std::fabs(r.fx), std::fabs(r.fy)});
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_NEAR(got[k].header.stamp.toSec(), offset + rows[k].t, 1e-6);
    EXPECT_EQ(got[k].fz, rows[k].fz) << "row " << k;
    EXPECT_EQ(got[k].load_match, ContactState::LOAD_SAME_STAMP) << "row " << k;
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
