// rostest with /use_sim_time: the test publishes /clock; contact_node's dt comes from the
// creepage stamps (sim time), loads pair by stamp, and the load wait runs on the wall clock, so a
// creepage without its load is answered while sim time stands still.
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
    return spinUntil([&] { return ros::Time::now() == ros::Time(t); }, 5.0);
  };
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(setClock(50.0 + 0.01 * k));
    ContactState s;
    c.load(ros::Time::now(), 8e4);
    ASSERT_TRUE(c.creep(ros::Time::now(), 1e-3, 0, 0, 20.0, &s));
    EXPECT_EQ(s.status, ContactState::STATUS_OK) << s.message;
    EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP) << s.message;
    EXPECT_EQ(s.header.stamp, ros::Time(50.0 + 0.01 * k));
    EXPECT_EQ(s.header.frame_id, "sim_contact");  // the default: from the namespace
    EXPECT_NEAR(s.dt, k == 0 ? 0.0 : 0.01, 1e-9);
  }
  // An unstamped load does not stand for "now": the next stamped creepage waits for a stamped
  // load, then (load_wait on the wall clock, sim time paused) takes the unstamped one, flagged.
  c.load(ros::Time(), 7e4);
  ASSERT_TRUE(setClock(50.1));
  ContactState s;
  ASSERT_TRUE(c.creep(ros::Time::now(), 1e-3, 0, 0, 20.0, &s));
  EXPECT_EQ(ros::Time::now(), ros::Time(50.1));  // answered with the clock standing still
  EXPECT_EQ(s.status, ContactState::STATUS_OK) << s.message;
  EXPECT_EQ(s.fz, 7e4);
  EXPECT_EQ(s.load_match, ContactState::LOAD_UNMATCHED);
  EXPECT_TRUE(s.load_stamp.isZero());
  // ... and does not poison the stamped stream: the next stamped load is taken.
  ASSERT_TRUE(setClock(50.11));
  c.load(ros::Time::now(), 8.5e4);
  ASSERT_TRUE(c.creep(ros::Time::now(), 1e-3, 0, 0, 20.0, &s));
  EXPECT_EQ(s.fz, 8.5e4);
  EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "sim_time");
  return RUN_ALL_TESTS();
}
