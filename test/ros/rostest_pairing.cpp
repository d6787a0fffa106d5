// rostest (pairing.test): a creepage steps with the normal load of its stamp whatever the arrival
// order. The paper's varying-load scene (a new load every row) through contact_node
//  - with loads and creepages published in shuffled order and with delays,
//  - as a bag (written here with rosbag_storage, loads and creepages interleaved as a recorder on
//    two connections would see them) played twice with `rosbag play` into the reset node,
// gives contact_cli's forces to 1e-9, every step paired by stamp, and the two plays agree bit for
// bit. Per-step geometry and friction reach the model (plumbing: the node's output equals the
// core model's for the same inputs, whatever the model does with them).
#include <rosbag/bag.h>

#include <fstream>
#include <random>

#include "rostest_helpers.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"
#include "wheel_rail_contact/scenario.hpp"

using namespace wrc_test;

namespace {

SceneUnderTest sut(2000.0);

void expectCli(const std::vector<ContactState>& out, const char* what) {
  ASSERT_EQ(out.size(), sut.reference.size()) << what;
  for (size_t k = 0; k < out.size(); ++k) {
    const Row& r = sut.reference[k];
    const ContactState& s = out[k];
    EXPECT_EQ(s.header.stamp, sut.stampOf(sut.rows[k].t)) << what << " row " << k;
    EXPECT_EQ(s.load_match, ContactState::LOAD_SAME_STAMP) << what << " row " << k << s.message;
    EXPECT_EQ(s.fz, sut.rows[k].fz) << what << " row " << k;
    EXPECT_NEAR(s.fx, r.fx, 1e-9 * largest(sut.reference, &Row::fx)) << what << " row " << k;
    EXPECT_NEAR(s.fy, r.fy, 1e-9 * largest(sut.reference, &Row::fy)) << what << " row " << k;
    EXPECT_NEAR(s.a, r.a, 1e-9 * largest(sut.reference, &Row::a)) << what << " row " << k;
    EXPECT_NEAR(s.adhesion_fraction, r.adhesion, 1e-9) << what << " row " << k;
    EXPECT_EQ(statusText(s.status), r.status) << what << " row " << k;
  }
}

/// One input of the scene: row k's load or creepage.
struct Input {
  size_t row;
  bool load;
};

/// The scene's inputs in an arrival order a simulator on two connections may produce: per row
/// load first or creepage first at random, and now and then up to five rows' creepages ahead of
/// their loads. Loads stay in stamp order among themselves, creepages too (one connection each).
std::vector<Input> shuffledOrder(std::mt19937& rng) {
  std::vector<Input> order;
  std::uniform_int_distribution<int> pattern(0, 5), ahead(2, 5);
  for (size_t k = 0; k < sut.rows.size();) {
    const int p = pattern(rng);
    if (p == 0) {  // several creepages, then their loads
      const size_t n = std::min<size_t>(ahead(rng), sut.rows.size() - k);
      for (size_t j = 0; j < n; ++j) order.push_back({k + j, false});
      for (size_t j = 0; j < n; ++j) order.push_back({k + j, true});
      k += n;
    } else {
      order.push_back({k, p % 2 == 0});
      order.push_back({k, p % 2 != 0});
      ++k;
    }
  }
  return order;
}

wheel_rail_contact::Creepage creepageOf(size_t k) {
  wheel_rail_contact::Creepage m;
  m.header.stamp = sut.stampOf(sut.rows[k].t);
  m.longitudinal = sut.rows[k].xi;
  m.lateral = sut.rows[k].eta;
  m.spin = sut.rows[k].phi;
  m.velocity = sut.rows[k].V;
  return m;
}

wheel_rail_contact::NormalLoad loadOf(size_t k) {
  wheel_rail_contact::NormalLoad m;
  m.header.stamp = sut.stampOf(sut.rows[k].t);
  m.force = sut.rows[k].fz;
  return m;
}

class Pairing : public ::testing::Test {
 protected:
  void SetUp() override {
    client = std::make_unique<ContactClient>(nh, sut.ns);
    ASSERT_TRUE(client->connect()) << "contact_node under " << sut.ns << " not reachable";
    ASSERT_TRUE(client->reset());
  }
  /// Waits for `n` outputs after index `from`, returns them.
  std::vector<ContactState> outputs(size_t from, size_t n) {
    EXPECT_TRUE(spinUntil([&] { return client->states.size() >= from + n; }, 60.0))
        << client->states.size() - from << " of " << n << " outputs";
    return {client->states.begin() + static_cast<long>(std::min(from, client->states.size())),
            client->states.end()};
  }
  ros::NodeHandle nh;
  std::unique_ptr<ContactClient> client;
};

}  // namespace

TEST_F(Pairing, ShuffledArrivalWithDelaysGivesContactCliForces) {
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> delay(0.0, 0.002);
  std::bernoulli_distribution pause(0.2);
  for (int run = 0; run < 2; ++run) {
    ASSERT_TRUE(client->reset());
    const size_t from = client->states.size();
    for (const Input& in : shuffledOrder(rng)) {
      const auto& r = sut.rows[in.row];
      if (in.load)
        client->load(sut.stampOf(r.t), r.fz);
      else
        client->publishCreepage(sut.stampOf(r.t), r.xi, r.eta, r.phi, r.V);
      if (pause(rng)) spinFor(delay(rng));  // a deliberate gap in the stream, not a wait
    }
    expectCli(outputs(from, sut.rows.size()), run == 0 ? "shuffled run 1" : "shuffled run 2");
  }
  EXPECT_TRUE(client->oneOutputPerInput());
}

TEST_F(Pairing, ARecordedBagPlayedTwiceGivesBitIdenticalContactCliForces) {
  const char* home = std::getenv("ROS_HOME");
  const std::string path = std::string(home ? home : "/tmp") + "/pairing_" +
                           std::to_string(static_cast<long>(getpid())) + ".bag";
  {
    // Receive times as a recorder sees two connections: 1 ms per row, the second message of a
    // pair 0-0.3 ms after the first, in shuffled order.
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> jitter(0.0, 0.0003);
    const ros::Time t0(1.0);
    double t = 0.0;
    for (const Input& in : shuffledOrder(rng)) {
      t = std::max(t, 0.001 * static_cast<double>(in.row)) + jitter(rng);
      if (in.load)
        bag.write("/" + sut.ns + "/normal_load", t0 + ros::Duration(t), loadOf(in.row));
      else
        bag.write("/" + sut.ns + "/creepage", t0 + ros::Duration(t), creepageOf(in.row));
    }
  }
  std::vector<std::vector<ContactState>> plays;
  for (int play = 0; play < 2; ++play) {
    ASSERT_TRUE(client->reset());
    const size_t from = client->states.size();
    // --wait-for-subscribers: rosbag starts once the node is subscribed to both topics.
    std::string log;
    ASSERT_EQ(run("rosbag play --wait-for-subscribers -q '" + path + "'", &log), 0) << log;
    plays.push_back(outputs(from, sut.rows.size()));
    expectCli(plays.back(), play == 0 ? "bag play 1" : "bag play 2");
  }
  std::remove(path.c_str());
  ASSERT_EQ(plays[0].size(), plays[1].size());
  for (size_t k = 0; k < plays[0].size(); ++k)
    EXPECT_TRUE(sameBits(plays[0][k], plays[1][k])) << "row " << k;
}

TEST_F(Pairing, PerStepGeometryAndFrictionReachTheModel) {
  // The node's model, rebuilt here from its parameters, fed what the node must pass it.
  const wheel_rail_contact::ContactParameters p = parametersOf(sut.ns + "/contact_node");
  auto model = wheel_rail_contact::makeContactModel(p);
  const double fz = 500.0, V = 0.025, xi = 0.01, eta = 0.004, phi = 0.5;
  // Step 1 (topics): a, b and mu given; the load comes after the creepage.
  wheel_rail_contact::Creepage g;
  g.a = 0.021;
  g.b = 0.017;
  g.mu = 0.35;
  const size_t from = client->states.size();
  client->publishCreepage(sut.stampOf(0.0), xi, eta, phi, V, g);
  client->load(sut.stampOf(0.0), fz);
  const auto out = outputs(from, 1);
  ASSERT_EQ(out.size(), 1u);
  wheel_rail_contact::StepInput in{0.0, V, xi, eta, phi, fz};
  in.a = 0.021;
  in.b = 0.017;
  in.mu = 0.35;
  const auto e1 = model->step(in);
  EXPECT_EQ(out[0].status, ContactState::STATUS_OK) << out[0].message;
  EXPECT_EQ(out[0].fx, e1.fx);
  EXPECT_EQ(out[0].fy, e1.fy);
  EXPECT_EQ(out[0].a, e1.a);
  EXPECT_EQ(out[0].b, e1.b);
  // Step 2 (Step service): curvatures and mu; Hertz makes a, b from this step's load.
  wheel_rail_contact::Step::Request req;
  req.curvature_x = 4.0;
  req.curvature_y = 6.0;
  req.mu = 0.2;
  wheel_rail_contact::Step::Response res;
  ASSERT_TRUE(client->step(sut.stampOf(0.01), xi, eta, phi, V, 1.2 * fz, &res, req));
  const auto e = wheel_rail_contact::hertzFromCurvatures(1.2 * fz, 4.0, 6.0, p.G, p.nu);
  in = {0.01, V, xi, eta, phi, 1.2 * fz};
  in.a = e.a;
  in.b = e.b;
  in.mu = 0.2;
  const auto e2 = model->step(in);
  EXPECT_EQ(res.status, ContactState::STATUS_OK) << res.message;
  EXPECT_EQ(res.fx, e2.fx);
  EXPECT_EQ(res.fy, e2.fy);
  EXPECT_EQ(res.a, e2.a);
  EXPECT_EQ(res.b, e2.b);
  // A conflicting request is rejected with its reason and holds step 2's output.
  req.a = 0.02;
  req.b = 0.02;
  ASSERT_TRUE(client->step(sut.stampOf(0.02), xi, eta, phi, V, fz, &res, req));
  EXPECT_EQ(res.status, ContactState::STATUS_REJECTED);
  EXPECT_NE(res.message.find("both"), std::string::npos) << res.message;
  EXPECT_TRUE(res.held);
  EXPECT_EQ(res.fx, e2.fx);
  EXPECT_TRUE(client->oneOutputPerInput());
}

int main(int argc, char** argv) {
  return runSceneTests(argc, argv, "pairing", &sut);
}
