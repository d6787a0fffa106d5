// rostest: a scene through contact_node (topics, Step service, both mixed, after resets) gives the
// forces `contact_cli run` gives for the same scenario, model, mesh and parameters, to 1e-9.
// Private parameters: ns (the contact's namespace), scene (scenario CSV), config (the node's YAML).
#include <fstream>

#include "../../src/ros/contact_stepper.hpp"
#include "rostest_helpers.hpp"
#include "wheel_rail_contact/scenario.hpp"

using namespace wrc_test;

namespace {

SceneUnderTest sut(1000.0);

double scaleOf(double Row::*field) {
  return largest(sut.reference, field);
}

/// The node's k-th step against contact_cli's k-th row, each field to 1e-9 of its largest value.
template <class Out>
void expectMatches(size_t k, const Out& o) {
  const Row& r = sut.reference[k];
  const double rel = 1e-9;
  EXPECT_NEAR(o.fx, r.fx, rel * scaleOf(&Row::fx)) << "row " << k;
  EXPECT_NEAR(o.fy, r.fy, rel * scaleOf(&Row::fy)) << "row " << k;
  // A moment's scale is at least force x patch length: where Mz is rounding noise around zero
  // (pure xi), nss's dt from ROS stamps (ns resolution) moves it by ~1e-17 N m.
  const double mzScale = std::max(
      scaleOf(&Row::mz), scaleOf(&Row::a) * std::max(scaleOf(&Row::fx), scaleOf(&Row::fy)));
  EXPECT_NEAR(o.mz, r.mz, rel * mzScale) << "row " << k;
  EXPECT_NEAR(o.fz, r.fz, rel * scaleOf(&Row::fz)) << "row " << k;
  EXPECT_NEAR(o.a, r.a, rel * scaleOf(&Row::a)) << "row " << k;
  EXPECT_NEAR(o.b, r.b, rel * scaleOf(&Row::b)) << "row " << k;
  EXPECT_NEAR(o.adhesion_fraction, r.adhesion, 1e-9) << "row " << k;
  EXPECT_EQ(statusText(o.status), r.status) << "row " << k;
}

/// Rows [0, n) through the topics after a reset, each row's load and creepage with the same stamp,
/// published in alternating order (load first, then creepage first): the node pairs them by stamp.
std::vector<ContactState> viaTopics(ContactClient& c, size_t n) {
  std::vector<ContactState> out;
  EXPECT_TRUE(c.oneOutputPerInput());  // earlier Step calls' outputs are all in
  EXPECT_TRUE(c.reset());
  for (size_t k = 0; k < n; ++k) {
    const auto& row = sut.rows[k];
    ContactState s;
    if (k % 2 == 0) {
      c.load(sut.stampOf(row.t), row.fz);
      EXPECT_TRUE(c.creep(sut.stampOf(row.t), row.xi, row.eta, row.phi, row.V, &s));
    } else {
      const size_t before = c.states.size();
      c.publishCreepage(sut.stampOf(row.t), row.xi, row.eta, row.phi, row.V);
      c.load(sut.stampOf(row.t), row.fz);
      EXPECT_TRUE(spinUntil([&] { return c.states.size() > before; }, 20.0)) << "row " << k;
      if (c.states.size() > before) s = c.states.back();
    }
    EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP) << "row " << k << ": " << s.message;
    EXPECT_EQ(s.fz, row.fz) << "row " << k;
    out.push_back(s);
  }
  for (size_t k = 0; k < out.size(); ++k) expectMatches(k, out[k]);
  return out;
}

void viaStep(ContactClient& c, size_t from, size_t to) {
  const size_t published = c.states.size();
  for (size_t k = from; k < to; ++k) {
    const auto& row = sut.rows[k];
    wheel_rail_contact::Step::Response res;
    ASSERT_TRUE(c.step(sut.stampOf(row.t), row.xi, row.eta, row.phi, row.V, row.fz, &res));
    expectMatches(k, res);
    EXPECT_EQ(res.dt, k == from && from == 0 ? 0.0 : res.dt);
    // Each step's publication arrives before the next step, as a simulator's loop takes it: a
    // burst of service calls faster than a loaded machine delivers would overrun the node's
    // publisher queue (publish_queue_size), which is the configuration's limit, not the node's.
    const size_t expected = published + (k - from + 1);
    ASSERT_TRUE(spinUntil([&] { return c.states.size() >= expected; }, 10.0))
        << "step " << k << ": contact_state not published";
  }
}

class NodeVsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    client = std::make_unique<ContactClient>(nh, sut.ns);
    ASSERT_TRUE(client->connect()) << "contact_node under " << sut.ns << " not reachable";
    ASSERT_TRUE(client->reset());
  }
  void TearDown() override {
    if (client) {
      EXPECT_TRUE(client->oneOutputPerInput());
    }
  }
  ros::NodeHandle nh;
  std::unique_ptr<ContactClient> client;
};

}  // namespace

TEST_F(NodeVsCli, ContactCliReadsTheNodeConfiguration) {
  ASSERT_FALSE(sut.rows.empty());
  ASSERT_EQ(sut.reference.size(), sut.rows.size());
  std::string model;
  ASSERT_TRUE(ros::param::get(sut.ns + "/contact_node/model", model));
  for (const auto& r : sut.reference) EXPECT_EQ(r.status, "ok");
}

TEST_F(NodeVsCli, TopicsGiveContactCliForces) {
  const auto out = viaTopics(*client, sut.rows.size());
  ASSERT_EQ(out.size(), sut.rows.size());
  std::string frame = wheel_rail_contact::frameIdForNamespace(ros::names::resolve(sut.ns));
  ros::param::get(sut.ns + "/contact_node/frame_id", frame);  // an explicit one overrides
  EXPECT_EQ(client->forces.back().header.frame_id, frame);
  EXPECT_EQ(out[0].dt, 0.0);
  EXPECT_NEAR(out[1].dt, sut.rows[1].t - sut.rows[0].t, 1e-9);
}

TEST_F(NodeVsCli, StepServiceGivesContactCliForcesAndPublishesThem) {
  viaStep(*client, 0, sut.rows.size());
  // Service steps are published too (connect() made sure none can be lost).
  spinUntil([&] { return client->states.size() >= sut.rows.size(); }, 20.0);
  EXPECT_EQ(client->states.size(), sut.rows.size());
}

TEST_F(NodeVsCli, TopicsAndStepServiceMixInOneTimeLine) {
  const size_t half = sut.rows.size() / 2;
  ASSERT_EQ(viaTopics(*client, half).size(), half);
  viaStep(*client, half, sut.rows.size());
}

TEST_F(NodeVsCli, ResetRestoresFreshStartOutputs) {
  const size_t n = std::min<size_t>(sut.rows.size(), 40);
  const auto first = viaTopics(*client, n);
  // Leave every piece of state dirty: history, a later time base, another load.
  wheel_rail_contact::Step::Response res;
  for (int k = 0; k < 5; ++k)
    ASSERT_TRUE(client->step(sut.stampOf(1e3 + k), 0.03, -0.02, 1.0, sut.rows[0].V,
                             0.7 * sut.rows[0].fz, &res));
  const auto second = viaTopics(*client, n);  // starts with a reset
  ASSERT_EQ(first.size(), n);
  ASSERT_EQ(second.size(), n);
  for (size_t k = 0; k < n; ++k) {
    const ContactState &a = first[k], &b = second[k];
    EXPECT_EQ(a.fx, b.fx);
    EXPECT_EQ(a.fy, b.fy);
    EXPECT_EQ(a.mz, b.mz);
    EXPECT_EQ(a.dt, b.dt);
    EXPECT_EQ(a.status, b.status);
  }
}

int main(int argc, char** argv) {
  return runSceneTests(argc, argv, "node_vs_cli", &sut);
}
