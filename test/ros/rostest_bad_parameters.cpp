// rostest: contact_node with an invalid private parameter exits with code 1 after a ROS_FATAL that
// names the parameter; a model this build does not provide is refused the same way. Every
// parameter out of range and of a wrong type (command line, parameter server, YAML through
// rosparam load), a chi table that is missing or malformed, a config file roslaunch cannot read:
// never a crash (exit code 1, not a signal), always the parameter's name in the message.
#include <ros/master.h>

#include <fstream>

#include "rostest_helpers.hpp"
#include "wheel_rail_contact/contact_model.hpp"

using namespace wrc_test;

namespace {

int counter = 0;

/// A fresh node name: no parameter of an earlier case is left under it.
std::string nextName() {
  return "bad_parameters_" + std::to_string(++counter);
}

/// Runs contact_node as `name` with `args`; SIGINT after `seconds`.
int runNode(const std::string& name, const std::string& args, std::string* out,
            double seconds = 20.0) {
  return run("timeout --preserve-status -s INT " + std::to_string(seconds) + " " +
                 WRC_CONTACT_NODE + " __name:=" + name + " " + args,
             out);
}

/// Exit code 1 (the controlled failure; a crash is a signal: -1, or 134/139 via the shell) and a
/// ROS_FATAL "invalid parameter <text>".
void expectFatalAs(const std::string& name, const std::string& args, const std::string& text) {
  std::string out;
  EXPECT_EQ(runNode(name, args, &out), 1) << args << "\n" << out;
  EXPECT_NE(out.find("FATAL"), std::string::npos) << out;
  EXPECT_NE(out.find("invalid parameter " + text), std::string::npos) << args << "\n" << out;
}

void expectFatal(const std::string& args, const std::string& text) {
  expectFatalAs(nextName(), args, text);
}

/// The node started with the private parameter `param` set to `value` on the parameter server.
void expectFatalWith(const std::string& param, const XmlRpc::XmlRpcValue& value,
                     const std::string& text) {
  const std::string name = nextName();
  ros::param::set("/" + name + "/" + param, value);
  expectFatalAs(name, "", text);
}

std::string writeTemp(const std::string& file, const std::string& text) {
  const std::string path = "/tmp/wrc_bad_parameters_" + std::to_string(getpid()) + "_" + file;
  std::ofstream(path) << text;
  return path;
}

XmlRpc::XmlRpcValue list(double a, double b) {
  XmlRpc::XmlRpcValue v;
  v[0] = a;
  v[1] = b;
  return v;
}

}  // namespace

TEST(BadParameters, FatalNamesTheParameter) {
  expectFatal("_nu:=2", "nu: must be in [0, 0.5]");
  expectFatal("_G:=abc", "G: expected a finite number");
  expectFatal("_nxx:=3", "nxx: unknown parameter");
  expectFatal("_model:=foo", "model: must be one of");
  expectFatal("_max_dt:=-1.0", "max_dt:");
  expectFatal("_queue_size:=0", "queue_size:");
  expectFatal("_time_jump_reset:=-2.0", "time_jump_reset:");
}

TEST(BadParameters, EveryParameterOutOfRange) {
  expectFatal("_G:=0", "G: must be in [1000, 1e+13] Pa, got 0");
  expectFatal("_G:=1e200", "G: must be in [1000, 1e+13] Pa, got 1e+200");
  expectFatal("_G:=nan", "G: expected a finite number, got 'nan'");
  expectFatal("_nu:=-0.1", "nu: must be in [0, 0.5]");
  expectFatal("_mu:=-0.3", "mu: must be in [1e-06, 1000] (or 0: frictionless), got -0.3");
  expectFatal("_mu:=1e-200", "mu: must be in [1e-06, 1000] (or 0: frictionless), got 1e-200");
  expectFatal("_a0:=0", "a0: must be in [1e-06, 1] m, got 0");
  expectFatal("_b0:=-1e-3", "b0: must be in [1e-06, 1] m, got -0.001");
  expectFatal("_a0:=0.1 _b0:=0.001", "b0: a0/b0 = 100 is outside Kalker's table");
  expectFatal("_fz0:=-5", "fz0: must be in [1e-06, 1e+09] N, got -5");
  expectFatal("_nx:=1", "nx: must be in [2, 400], got 1");
  expectFatal("_nx:=401", "nx: must be in [2, 400], got 401");
  expectFatal("_ny:=0", "ny: must be in [1, 400], got 0");
  expectFatal("_ny:=10000000", "ny: expected an integer, got '10000000'");
  expectFatal("_mesh:=moving", "mesh: must be fixed or adaptive, got 'moving'");
  expectFatal("_mesh:=auto", "mesh: 'auto' was renamed 'adaptive'");
  expectFatal("_fastsim:=''",
              "fastsim: must be calibrated or classic (leave it out for the model's own: "
              "calibrated for nss and auto, classic for steady and shen-li), got ''");
  expectFatal("_fastsim:=fast", "fastsim: must be calibrated or classic");
  expectFatal("_tolerance:=0", "tolerance: must be in (0, 1), got 0");
  expectFatal("_tolerance:=1.5", "tolerance: must be in (0, 1), got 1.5");
  expectFatal("_fz_max:=-1", "fz_max: must be >= 0");
  expectFatal("_publish_queue_size:=-3", "publish_queue_size: must be an integer in [1, 1000000]");
  expectFatal("_queue_size:=2000000", "queue_size: must be an integer in [1, 1000000]");
  expectFatal("_max_dt:=0", "max_dt: must be a finite number > 0 s, got 0");
  expectFatal("_max_dt:=inf", "max_dt: must be a finite number > 0 s, got inf");
  expectFatal("_max_load_age:=-1",
              "max_load_age: must be a finite number >= 0 s (0 = off), got -1");
  expectFatal("_time_jump_reset:=nan",
              "time_jump_reset: must be a finite number >= 0 s (0 = off), got nan");
  expectFatal("_load_wait:=-0.1", "load_wait: must be in [0, 60] s, got -0.1");
  expectFatal("_load_wait:=nan", "load_wait: must be in [0, 60] s, got nan");
  expectFatal("_load_pairing:=nearest", "load_pairing: must be stamp or latest, got 'nearest'");
  expectFatal("_frame_id:=''", "frame_id: must not be empty");
  expectFatal("_diagnostic_period:=0", "diagnostic_period: must be in (0, 86400] s, got 0");
  // Once crashed: diagnostic_updater's constructor, before the checks, threw from ros::Duration.
  expectFatal("_diagnostic_period:=1e10", "diagnostic_period: must be in (0, 86400] s, got 1e+10");
  expectFatal("_diagnostic_period:=inf", "diagnostic_period: must be in (0, 86400] s, got inf");
  expectFatal("_diagnostic_period:=nan", "diagnostic_period: must be in (0, 86400] s, got nan");
}

TEST(BadParameters, EveryParameterOfAWrongType) {
  // Strings where a number is expected (rosrun's _x:=v types the value as YAML does).
  expectFatal("_nu:=low", "nu: expected a finite number, got 'low'");
  expectFatal("_mu:=high", "mu: expected a finite number, got 'high'");
  expectFatal("_a0:=6mm", "a0: expected a finite number, got '6mm'");
  expectFatal("_b0:=''", "b0: expected a finite number, got ''");
  expectFatal("_fz0:=heavy", "fz0: expected a finite number, got 'heavy'");
  expectFatal("_fz_max:=none", "fz_max: expected a finite number, got 'none'");
  expectFatal("_nx:=twenty", "nx: expected an integer, got 'twenty'");
  expectFatal("_ny:=2.5", "ny: expected an integer, got '2.5'");
  expectFatal("_queue_size:=many", "queue_size: expected a number, got 'many'");
  expectFatal("_publish_queue_size:=1.5", "publish_queue_size: must be an integer in [1, 1000000]");
  expectFatal("_max_dt:=abc", "max_dt: expected a number, got 'abc'");
  expectFatal("_time_jump_reset:=never", "time_jump_reset: expected a number, got 'never'");
  expectFatal("_max_load_age:=old", "max_load_age: expected a number, got 'old'");
  expectFatal("_diagnostic_period:=fast", "diagnostic_period: expected a number, got 'fast'");
  expectFatal("_load_wait:=long", "load_wait: expected a number, got 'long'");
  expectFatalWith("load_pairing", list(1, 2), "load_pairing: expected a number or a name");
  expectFatal("_model:=3", "model: must be one of steady, shen-li, nss, exact, auto; got '3'");
  expectFatal("_tolerance:=tight", "tolerance: expected a finite number, got 'tight'");
  // Booleans, lists and maps (YAML in a launch file, rosparam set) for every kind of parameter.
  expectFatal("_G:=true", "G: expected a number or a name, got <value><boolean>1</boolean>");
  expectFatalWith("nx", list(1, 2), "nx: expected a number or a name, got <value><array>");
  expectFatalWith("model", list(1, 2), "model: expected a number or a name");
  expectFatalWith("chi_table", list(1, 2), "chi_table: expected a number or a name");
  expectFatalWith("frame_id", list(1, 2), "frame_id: expected a number or a name");
  expectFatalWith("max_dt", XmlRpc::XmlRpcValue(false), "max_dt: expected a number or a name");
  expectFatalWith("queue_size", list(1, 2), "queue_size: expected a number or a name");
  XmlRpc::XmlRpcValue map;
  map["x"] = 1.0;
  expectFatalWith("mu", map, "mu: expected a number or a name, got <value><struct>");
  expectFatalWith("diagnostic_period", map, "diagnostic_period: expected a number or a name");
}

TEST(BadParameters, YamlLoadedWithRosparamIsCheckedTheSameWay) {
  const std::pair<std::string, std::string> cases[] = {
      {"G: [1.0e+6, 2.0e+6]\n", "G: expected a number or a name"},
      {"nx: {a: 1}\n", "nx: expected a number or a name"},
      {"mu: .inf\n", "mu: expected a finite number, got 'inf'"},
      {"model: nss\nmesh: yes\n", "mesh: expected a number or a name"},
      {"model: steady\nnxx: 3\n", "nxx: unknown parameter"},
      {"model: auto\nmesh: auto\n", "mesh: 'auto' was renamed 'adaptive'"},
      {"model: nss\nfastsim: ''\n", "fastsim: must be calibrated or classic"},
      {"max_dt: '0.5 s'\n", "max_dt: expected a number, got '0.5 s'"},
  };
  for (const auto& c : cases) {
    const std::string name = nextName(), file = writeTemp("case.yaml", c.first);
    std::string out;
    ASSERT_EQ(run("rosparam load " + file + " /" + name, &out), 0) << out;
    expectFatalAs(name, "", c.second);
  }
}

TEST(BadParameters, MissingOrMalformedChiTableIsFatalNamingTheFileAndLine) {
  const std::string header = "a_over_b,kind,chi1,chi2,chi3\n";
  const std::string kinds = "1,22,0.2,0.9,0.3\n1,23,0.1,0.8,0.1\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", ":0: empty: no header"},
      {"a;kind;chi1\n", ":1: expected header a_over_b,kind,chi1,chi2,chi3"},
      {header, ":1: no rows for kind 11"},
      {header + "1,11,nan,1,1\n" + kinds, ":2: field 3 is not a finite number"},
      {header + "1,11,0.1,1\n" + kinds, ":2: expected 5 fields"},
      {"a_over_b,kind,chi1,chi2,chi3,error\n" + kinds, ":1: column 'error' unknown or repeated"},
      {header + "2,11,0.1,1,1\n1,11,0.1,1,1\n" + kinds,
       ":3: a_over_b must increase within kind 11, got 1 after 2"},
      {header + "1,11,0.1,1,-1\n" + kinds, ":2: chi3 must be > 0"},
  };
  for (const auto& c : cases) {
    const std::string file = writeTemp("chi.csv", c.first);
    expectFatal("_model:=nss _chi_table:=" + file, "chi_table: chi table " + file + c.second);
  }
  expectFatal("_model:=nss _chi_table:=/nonexistent/chi.csv",
              "chi_table: chi table /nonexistent/chi.csv: cannot open");
  expectFatal("_model:=nss _chi_table:=/tmp", "chi_table: chi table /tmp:0: read error");
}

TEST(BadParameters, LaunchRefusesAMissingOrMalformedConfigNamingTheFile) {
  // roslaunch reads the YAML (rosparam load in launch/contact.launch) before any node starts and
  // exits 1 naming the file; no contact_node is left running.
  const std::string launch =
      "timeout -s INT 30 roslaunch wheel_rail_contact contact.launch ns:=missing_config config:=";
  std::string out;
  EXPECT_EQ(run(launch + "/nonexistent/contact.yaml", &out), 1) << out;
  EXPECT_NE(out.find("file does not exist [/nonexistent/contact.yaml]"), std::string::npos) << out;
  const std::string bad = writeTemp("malformed.yaml", "G: [1\nnu: 0.3\n");
  EXPECT_EQ(run(launch + bad, &out), 1) << out;
  EXPECT_NE(out.find("file " + bad + " contains invalid YAML"), std::string::npos) << out;
  std::vector<std::string> nodes;
  ASSERT_TRUE(ros::master::getNodes(nodes));
  for (const auto& n : nodes) EXPECT_EQ(n.find("missing_config"), std::string::npos) << n;
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bad_parameters");
  return RUN_ALL_TESTS();
}
