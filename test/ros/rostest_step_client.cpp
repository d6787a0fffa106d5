// rostest: examples/step_client, run as a simulator would run it, against contact_cli. Every step
// it prints (one contact through the step service and the topics, then a two-contact vehicle
// through vehicle_step and vehicle_input) equals contact_cli run on the same inputs with the same
// configuration, to 1e-9 of the largest value.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>

#include "rostest_helpers.hpp"

using namespace wrc_test;

namespace {

struct Line {
  std::string path, name;
  int k = 0;
  double t, xi, eta, phi, V, fz, fx, fy, mz;
  int status = -1;
};

std::vector<Line> lines;
std::string config;

/// contact_cli run on the rows of `name` (in the order printed), configured like `node`.
std::vector<Row> cliReference(const std::string& name, const std::string& node,
                              std::vector<const Line*>* rows) {
  for (const auto& l : lines)
    if (l.name == name) rows->push_back(&l);
  const std::string scene =
      std::string(std::getenv("ROS_HOME") ? std::getenv("ROS_HOME") : "/tmp") + "/step_client_" +
      std::to_string(getpid()) + ".csv";
  std::ofstream f(scene);
  f.precision(17);
  f << "t,V,xi,eta,phi,fz\n";
  for (const Line* l : *rows)
    f << l->t << "," << l->V << "," << l->xi << "," << l->eta << "," << l->phi << "," << l->fz
      << "\n";
  f.close();
  std::string out;
  const std::string command = std::string(WRC_CONTACT_CLI) + " run --scenario '" + scene +
                              "' --config '" + config + "'" + cliOptionsOf(node);
  EXPECT_EQ(run(command, &out), 0) << command << "\n" << out;
  std::remove(scene.c_str());
  return parseCliOutput(out);
}

void expectAsCli(const std::string& name, const std::string& node, size_t expectedRows,
                 const std::vector<std::string>& paths) {
  std::vector<const Line*> rows;
  const std::vector<Row> ref = cliReference(name, node, &rows);
  ASSERT_EQ(rows.size(), expectedRows) << name;
  ASSERT_EQ(ref.size(), rows.size()) << name;
  double scale = 1e-300, length = 0.0;
  for (const auto& r : ref) {
    scale = std::max({scale, std::fabs(r.fx), std::fabs(r.fy)});
    length = std::max(length, r.a);
  }
  std::set<std::string> seen;
  for (size_t k = 0; k < rows.size(); ++k) {
    seen.insert(rows[k]->path);
    EXPECT_EQ(statusText(rows[k]->status), ref[k].status) << name << " row " << k;
    EXPECT_EQ(ref[k].status, "ok") << name << " row " << k;
    EXPECT_NEAR(rows[k]->fx, ref[k].fx, 1e-9 * scale) << name << " row " << k;
    EXPECT_NEAR(rows[k]->fy, ref[k].fy, 1e-9 * scale) << name << " row " << k;
    EXPECT_NEAR(rows[k]->mz, ref[k].mz, 1e-9 * scale * length) << name << " row " << k;
  }
  EXPECT_EQ(seen, std::set<std::string>(paths.begin(), paths.end())) << name;
}

}  // namespace

TEST(StepClient, ContactThroughServiceAndTopicsEqualsContactCli) {
  expectAsCli("/contact", "contact/contact_node", 10, {"step", "topic"});
}

TEST(StepClient, VehicleThroughServiceAndTopicEqualsContactCliPerContact) {
  for (const char* wheel : {"left", "right"})
    expectAsCli(wheel, "vehicle/vehicle_node", 10, {"vehicle_step", "vehicle_topic"});
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "step_client_test");
  ros::NodeHandle("~").getParam("config", config);
  std::string out;
  const std::string command =
      std::string(WRC_STEP_CLIENT) + " _contact:=/contact _vehicle:=/vehicle _steps:=5";
  const int code = run(command, &out);
  std::istringstream in(out);
  std::string text;
  while (std::getline(in, text)) {
    Line l;
    char path[64], name[64];
    if (std::sscanf(text.c_str(), "%63s %63s %d %lf %lf %lf %lf %lf %lf %lf %lf %lf %d", path, name,
                    &l.k, &l.t, &l.xi, &l.eta, &l.phi, &l.V, &l.fz, &l.fx, &l.fy, &l.mz,
                    &l.status) != 13)
      continue;  // ROS log lines
    l.path = path;
    l.name = name;
    lines.push_back(l);
  }
  EXPECT_EQ(code, 0) << out;
  return RUN_ALL_TESTS();
}
