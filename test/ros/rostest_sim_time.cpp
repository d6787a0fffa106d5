// rostest with /use_sim_time: the test publishes /clock; contact_node's dt comes from the
// creepage stamps (sim time), unstamped loads are taken at the sim time they arrive.
#include <rosgraph_msgs/Clock.h>

#include "rostest_helpers.hpp"

using namespace wrc_test;

TEST(SimTime, StampsAndDtFollowTheSimulatedClock) {
  ros::NodeHandle nh;
  ros::Publisher clock = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  ContactClient c(nh, "sim");
  ASSERT_TRUE(c.connect());
  ASSERT_TRUE(spinUntil([&] { return clock.getNumSubscribers() >= 2; }));  // node and us
  bool useSim = false;
  ASSERT_TRUE(ros::param::get("/use_sim_time", useSim));
  ASSERT_TRUE(useSim);
  auto setClock = [&](double t) {
    rosgraph_msgs::Clock m;
    m.clock = ros::Time(t);
    clock.publish(m);
    return spinUntil([&] { return ros::Time::now() == ros::Time(t); }, 2.0);
  };
  ASSERT_TRUE(setClock(50.0));
  c.load(ros::Time(), 8e4, 0.05);  // unstamped: taken at the node's (sim) now = 50 s
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(setClock(50.0 + 0.01 * k));
    ContactState s;
    ASSERT_TRUE(c.creep(ros::Time::now(), 1e-3, 0, 0, 20.0, &s));
    EXPECT_EQ(s.status, ContactState::STATUS_OK) << s.message;
    EXPECT_EQ(s.header.stamp, ros::Time(50.0 + 0.01 * k));
    EXPECT_NEAR(s.dt, k == 0 ? 0.0 : 0.01, 1e-9);
  }
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "sim_time");
  return RUN_ALL_TESTS();
}
