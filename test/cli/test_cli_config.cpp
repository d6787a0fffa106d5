// contact_cli --config: the node's YAML read by the CLI (same names, same defaults, strict keys).
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <string>

#include "../../src/cli/cli.hpp"
#include "../../src/cli/config_yaml.hpp"
#include "../../src/ros/contact_stepper.hpp"
#include "cli_test_helpers.hpp"

using namespace wheel_rail_contact;

namespace {

std::string errorOf(const std::string& yaml) {
  ContactParameters p;
  try {
    loadConfigYaml(writeTemp("bad.yaml", yaml), &p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

int cli(const std::vector<std::string>& args, std::string* out, std::string* err = nullptr) {
  std::ostringstream o, e;
  const int code = runCli(args, o, e);
  *out = o.str();
  if (err) *err = e.str();
  return code;
}

const std::string kDefaultYaml = std::string(WRC_SOURCE_DIR) + "/config/default.yaml";

}  // namespace

TEST(ConfigYaml, DefaultYamlHoldsTheCliDefaults) {
  ContactParameters p;
  p.G = 1.0;  // every key must be present and overwrite these
  p.nu = 0.1;
  p.mu = 0.9;
  p.a0 = 1.0;
  p.b0 = 1.0;
  p.fz0 = 1.0;
  p.nx = 3;
  p.ny = 3;
  p.model = "x";
  p.mesh = "x";
  p.fz_max = 7.0;
  p.chi_table = "x";
  loadConfigYaml(kDefaultYaml, &p);
  const ContactParameters d;
  EXPECT_EQ(p.G, d.G);
  EXPECT_EQ(p.nu, d.nu);
  EXPECT_EQ(p.mu, d.mu);
  EXPECT_EQ(p.a0, d.a0);
  EXPECT_EQ(p.b0, d.b0);
  EXPECT_EQ(p.fz0, d.fz0);
  EXPECT_EQ(p.nx, d.nx);
  EXPECT_EQ(p.ny, d.ny);
  EXPECT_EQ(p.model, d.model);
  EXPECT_EQ(p.mesh, d.mesh);
  EXPECT_EQ(p.fz_max, d.fz_max);
  EXPECT_EQ(p.chi_table, d.chi_table);
  EXPECT_EQ(p.fastsim, d.fastsim);  // left unset, so that each model runs its own variant
  EXPECT_FALSE(p.fastsim.has_value());
}

TEST(ConfigYaml, DefaultYamlListsEveryParameterWithTheDocumentedDefaults) {
  const YAML::Node root = YAML::LoadFile(kDefaultYaml);
  std::ifstream file(kDefaultYaml);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  for (const auto& d : parameterDocs()) {
    if (d.name == "fastsim") continue;  // below
    EXPECT_TRUE(root[d.name]) << d.name;
  }
  // fastsim has no one default (each model has its own): shown commented out, with both values.
  EXPECT_FALSE(root["fastsim"]) << "a fastsim in default.yaml would give every model one variant";
  EXPECT_NE(text.find("\n# fastsim: calibrated  # calibrated | classic"), std::string::npos);
  // frame_id is left out so that each contact's default comes from its namespace.
  EXPECT_FALSE(root["frame_id"]) << "a frame_id in default.yaml would give every contact one frame";
  for (const auto& d : nodeParameterDocs()) {
    if (d.name == "frame_id") continue;
    ASSERT_TRUE(root[d.name]) << d.name;
    if (d.unit == "s" || d.unit == "-")
      EXPECT_EQ(root[d.name].as<double>(), std::stod(d.default_value)) << d.name;
    else
      EXPECT_EQ(root[d.name].as<std::string>(), d.default_value) << d.name;
  }
  const StepperOptions o;
  EXPECT_EQ(root["max_dt"].as<double>(), o.max_dt);
  EXPECT_EQ(root["time_jump_reset"].as<double>(), o.time_jump_reset);
  EXPECT_EQ(root["max_load_age"].as<double>(), o.max_load_age);
  EXPECT_EQ(root["load_wait"].as<double>(), o.load_wait);
  EXPECT_EQ(root["load_pairing"].as<std::string>(), toString(o.load_pairing));
}

TEST(ConfigYaml, ErrorsNameTheKey) {
  EXPECT_EQ(errorOf("nx: 20\nnxx: 3\n").rfind("nxx: unknown parameter", 0), 0u);
  EXPECT_EQ(errorOf("G: [1, 2]\n").rfind("G: expected a single value", 0), 0u);
  EXPECT_EQ(errorOf("mu: high\n").rfind("mu: expected a finite number", 0), 0u);
  EXPECT_EQ(errorOf("nx: 2.5\n").rfind("nx: expected an integer", 0), 0u);
  EXPECT_EQ(errorOf("G: true\n").rfind("G:", 0), 0u);
  EXPECT_EQ(errorOf("- G\n").rfind("config:", 0), 0u);
  EXPECT_EQ(errorOf("G: [1\n").rfind("config:", 0), 0u);
  EXPECT_EQ(errorOf("fastsim: \"\"\n").rfind("fastsim: must be calibrated or classic", 0), 0u);
  EXPECT_EQ(errorOf("fastsim:\n").rfind("fastsim:", 0), 0u);
  EXPECT_EQ(errorOf("frame_id: wheel\nmax_dt: 0.5\nqueue_size: 5\n"), "(no error)");
  EXPECT_EQ(errorOf(""), "(no error)");
}

TEST(ConfigYaml, CliReadsItAndOptionsOverrideIt) {
  const std::string scenario = writeTemp("s.csv",
                                         "t,V,xi,eta,phi,fz\n0,1,0.001,0,0,400\n"
                                         "0.01,1,0.002,0.001,0.5,450\n");
  const std::string config = writeTemp("c.yaml",
                                       "G: 1.0e+6\nnu: 0.28\nmu: 0.4\na0: 0.02\nb0: 0.02\n"
                                       "fz0: 470.5\nnx: 8\nny: 6\nframe_id: left\n");
  std::string viaConfig, viaOptions, viaOverride, err;
  ASSERT_EQ(cli({"run", "--scenario", scenario, "--config", config}, &viaConfig, &err), 0) << err;
  ASSERT_EQ(cli({"run", "--scenario", scenario, "--G", "1e6", "--mu", "0.4", "--a0", "0.02", "--b0",
                 "0.02", "--fz0", "470.5", "--nx", "8", "--ny", "6"},
                &viaOptions),
            0);
  EXPECT_EQ(viaConfig, viaOptions);
  ASSERT_EQ(cli({"run", "--scenario", scenario, "--nx", "12", "--config", config}, &viaOverride),
            0);
  EXPECT_NE(viaOverride, viaConfig);
  std::string nx12;
  cli({"run", "--scenario", scenario, "--G", "1e6", "--mu", "0.4", "--a0", "0.02", "--b0", "0.02",
       "--fz0", "470.5", "--nx", "12", "--ny", "6"},
      &nx12);
  EXPECT_EQ(viaOverride, nx12);
  const std::string bad = writeTemp("b.yaml", "G: 1e6\nfram_id: x\n");
  EXPECT_EQ(cli({"run", "--scenario", scenario, "--config", bad}, &viaConfig, &err), 1);
  EXPECT_NE(err.find("fram_id: unknown parameter"), std::string::npos) << err;
}

TEST(ConfigYaml, CliRefusesAMissingOrMalformedConfigNamingIt) {
  const std::string scenario = writeTemp("s2.csv", "t,V,xi,eta,phi,fz\n0,1,0.001,0,0,400\n");
  const std::pair<std::string, std::string> cases[] = {
      {"/nonexistent/contact.yaml", "contact_cli: config: cannot read '/nonexistent/contact.yaml'"},
      {writeTemp("m1.yaml", "G: [1\n"), "contact_cli: config: cannot read"},
      {writeTemp("m2.yaml", "G: 1e6\n  nu: 0.3\n"), "contact_cli: config: cannot read"},
      {writeTemp("m3.yaml", "- G\n- nu\n"), "is not a YAML map of name: value"},
      {writeTemp("m4.yaml", "just text\n"), "is not a YAML map of name: value"},
      {writeTemp("m5.yaml", "G: {a: 1}\n"), "contact_cli: G: expected a single value"},
      {writeTemp("m6.yaml", "nx: .nan\n"), "contact_cli: nx: expected an integer, got '.nan'"},
      {writeTemp("m7.yaml", "mu: .inf\n"), "contact_cli: mu: expected a finite number, got '.inf'"},
      {writeTemp("m8.yaml", "model: nss\nchi_table: /nonexistent/chi.csv\n"),
       "contact_cli: chi_table: chi table /nonexistent/chi.csv: cannot open"},
      {writeTemp("m9.yaml", "mesh: auto\n"), "contact_cli: mesh: 'auto' was renamed 'adaptive'"},
      {writeTemp("m10.yaml", "fastsim: ''\n"),
       "contact_cli: fastsim: must be calibrated or classic (leave it out for the model's own: "
       "calibrated for nss and auto, classic for steady and shen-li), got ''"},
      {::testing::TempDir(), "contact_cli: config: cannot read"},
  };
  for (const auto& c : cases) {
    std::string out, err;
    EXPECT_EQ(cli({"run", "--scenario", scenario, "--config", c.first}, &out, &err), 1) << c.first;
    EXPECT_NE(err.find(c.second), std::string::npos) << c.first << ": " << err;
    EXPECT_EQ(out, "") << c.first;  // nothing half-written
  }
}
