// rostest: launch/vehicle.launch's four contacts run side by side under their namespaces, each with
// its own state, frame and services; each gives what the core model gives for its own inputs.
#include <algorithm>

#include "rostest_helpers.hpp"
#include "wheel_rail_contact/contact_model.hpp"

using namespace wrc_test;

namespace {
const char* kContacts[] = {"bogie1/wheelset1/left", "bogie1/wheelset1/right",
                           "bogie1/wheelset2/left", "bogie1/wheelset2/right"};
}

TEST(MultiContact, FourNamespacedContactsAreIndependent) {
  ros::NodeHandle nh;
  std::vector<std::unique_ptr<ContactClient>> c;
  for (const char* ns : kContacts) {
    c.push_back(std::make_unique<ContactClient>(nh, ns));
    ASSERT_TRUE(c.back()->connect()) << ns;
  }
  // The launch uses config/default.yaml: the defaults of ContactParameters.
  const wheel_rail_contact::ContactParameters p;
  // The loads pair with the creepages by stamp: no wait for them to arrive first.
  for (size_t i = 0; i < c.size(); ++i) c[i]->load(ros::Time(5.0), 6e4 + 1e4 * i);
  for (size_t i = 0; i < c.size(); ++i) {
    const double xi = 1e-4 * (i + 1), eta = -2e-4 * i;
    ContactState s;
    ASSERT_TRUE(c[i]->creep(ros::Time(5.0), xi, eta, 0.5, 20.0, &s)) << kContacts[i];
    auto model = wheel_rail_contact::makeContactModel(p);
    const auto e = model->step({0.0, 20.0, xi, eta, 0.5, 6e4 + 1e4 * i});
    EXPECT_EQ(s.status, ContactState::STATUS_OK) << kContacts[i] << ": " << s.message;
    EXPECT_NEAR(s.fx, e.fx, 1e-9 * std::fabs(e.fx)) << kContacts[i];
    EXPECT_NEAR(s.fy, e.fy, 1e-9 * std::fabs(e.fy)) << kContacts[i];
    EXPECT_EQ(s.fz, 6e4 + 1e4 * i);
    std::string frame = kContacts[i];
    std::replace(frame.begin(), frame.end(), '/', '_');
    EXPECT_EQ(c[i]->forces.back().header.frame_id, frame + "_contact");
    EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP);
    EXPECT_EQ(c[i]->states.size(), 1u) << "another contact's output leaked in";
  }
  // Resetting one contact leaves the others as they were.
  ASSERT_TRUE(c[0]->reset());
  ContactState s0, s1;
  ASSERT_TRUE(c[0]->creep(ros::Time(5.1), 1e-4, 0, 0, 20.0, &s0));  // answered after load_wait
  c[1]->load(ros::Time(5.1), 6.5e4);
  ASSERT_TRUE(c[1]->creep(ros::Time(5.1), 1e-4, 0, 0, 20.0, &s1));
  EXPECT_EQ(s0.status, ContactState::STATUS_NO_LOAD);  // the reset cleared its load
  EXPECT_EQ(s0.load_match, ContactState::LOAD_NONE);
  EXPECT_EQ(s1.status, ContactState::STATUS_OK);
  EXPECT_NEAR(s1.dt, 0.1, 1e-9);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "multi_contact");
  return RUN_ALL_TESTS();
}
