#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/cli/cli.hpp"
#include "cli_test_helpers.hpp"
#include "csv_rows.hpp"
#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::istringstream in(text);
  return csvRows(in);
}

}  // namespace

TEST(ContactCli, RunSteadyReproducesLinearTheoryAndSaturation) {
  const std::string f = writeTemp("lin.csv",
                                  "t,V,xi,eta,phi,fz\n0,20,1e-7,0,0,8e4\n0.001,20,0,1e-7,0,8e4\n"
                                  "0.002,20,0.5,0,0,6.4e5\n");
  const CliResult r = cli({"run", "--scenario", f, "--model", "steady"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = parseCsv(r.out);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0][0] + "," + rows[0][1] + "," + rows[0][2] + "," + rows[0][3] + "," + rows[0][4] +
                "," + rows[0][5] + "," + rows[0][6] + "," + rows[0][7],
            "t,fx,fy,mz,fz,a,b,adhesion_fraction");
  const CreepCoefficients c = kalkerCoefficients(1.5, 0.28);
  const double Gab = 8.2e10 * 6e-3 * 4e-3;
  EXPECT_NEAR(std::stod(rows[1][1]), -Gab * c.c11 * 1e-7, 0.005 * Gab * c.c11 * 1e-7);
  EXPECT_NEAR(std::stod(rows[2][2]), -Gab * c.c22 * 1e-7, 0.005 * Gab * c.c22 * 1e-7);
  EXPECT_NEAR(std::stod(rows[3][1]), -0.3 * 6.4e5, 1e-6 * 0.3 * 6.4e5);
  EXPECT_NEAR(std::stod(rows[3][5]), 12e-3, 1e-12);  // a = a0 (fz/fz0)^(1/3)
}

TEST(ContactCli, HelpDocumentsEveryOptionDefault) {
  const CliResult r = cli({"--help"});
  EXPECT_EQ(r.code, 0);
  for (const char* opt : {"--G ", "--nu ", "--mu ", "--a0 ", "--b0 ", "--fz0 ", "--nx ", "--ny ",
                          "--model ", "--scenario "})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  EXPECT_NE(r.out.find("default 8.2e+10"), std::string::npos);
}

TEST(ContactCli, BadOptionsExitNonZeroNamingTheOption) {
  const std::string f = writeTemp("ok.csv", "t,V,xi,eta,phi,fz\n0,20,1e-3,0,0,8e4\n");
  const struct {
    std::vector<std::string> args;
    std::string mention;
  } cases[] = {
      {{"run", "--scenario", f, "--a0", "-1"}, "a0: must be in [1e-06, 1] m"},
      {{"run", "--scenario", f, "--a0", "0"}, "a0: must be in [1e-06, 1] m"},
      {{"run", "--scenario", f, "--mu", "-0.1"}, "mu: must be in [1e-06, 1000]"},
      {{"run", "--scenario", f, "--mu", "1e-200"}, "mu: must be in [1e-06, 1000]"},
      {{"run", "--scenario", f, "--G", "1e200"}, "G: must be in [1000, 1e+13] Pa"},
      {{"run", "--scenario", f, "--nx", "1"}, "nx: must be in [2, 400]"},
      {{"run", "--scenario", f, "--ny", "x"}, "ny: expected an integer"},
      {{"run", "--scenario", f, "--G", "abc"}, "G: expected a finite number"},
      {{"run", "--scenario", f, "--model", "magic"}, "model: must be one of"},
      {{"run", "--scenario", f, "--mesh", "auto"}, "mesh: 'auto' was renamed 'adaptive'"},
      {{"run", "--scenario", f, "--mesh", "moving"}, "mesh: must be fixed or adaptive"},
      {{"run", "--scenario", f, "--fastsim", ""}, "fastsim: must be calibrated or classic"},
      {{"run", "--scenario", f, "--fastsim", "fast"}, "fastsim: must be calibrated or classic"},
      {{"run", "--scenario", f, "--bogus", "1"}, "bogus: unknown parameter"},
      {{"run", "--scenario", f, "--nu"}, "--nu: missing value"},
      {{"run"}, "--scenario FILE is required"},
      {{"run", "--scenario", "/nonexistent/x.csv"}, "cannot open"},
      {{"fly"}, "unknown command 'fly'"},
  };
  for (const auto& c : cases) {
    const CliResult r = cli(c.args);
    EXPECT_NE(r.code, 0) << c.mention;
    EXPECT_NE(r.err.find(c.mention), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty() || r.out.find("nan") == std::string::npos);
  }
}

TEST(ContactCli, HelpListsEveryParameterWithItsDefault) {
  // The options are made from parameterDocs(): a parameter added there is an option, documented.
  const CliResult r = cli({"run", "--help"});  // after a command too: the whole help
  EXPECT_EQ(r.code, 0);
  for (const auto& d : parameterDocs()) {
    const size_t at = r.out.find("\n  --" + d.name + " ");
    ASSERT_NE(at, std::string::npos) << d.name << "\n" << r.out;
    const std::string line = r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1);
    EXPECT_NE(line.find("default " + d.default_value), std::string::npos) << line;
    EXPECT_NE(line.find(d.meaning), std::string::npos) << line;
  }
  for (const char* opt : {"--config ", "--kind ", "--ab ", "--lambda-over-a "})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(ContactCli, CommandLineErrorsExitTwoRefusedValuesOne) {
  const std::string f = writeTemp("ok2.csv", "t,V,xi,eta,phi,fz\n0,20,1e-3,0,0,8e4\n");
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"run", "--scenario", f, "--bogus", "1"},
                                             {"run", "--scenario", f, "--nu"},
                                             {"run", "--scenario", f, "stray"},
                                             {"run"},
                                             {"freq", "--kind", "xi", "--ab", "1"},
                                             {"fly"},
                                             {}})
    EXPECT_EQ(cli(args).code, 2) << (args.empty() ? "(none)" : args.back());
  for (const auto& args :
       std::vector<std::vector<std::string>>{{"run", "--scenario", f, "--nu", "0.7"},
                                             {"run", "--scenario", f, "--mesh", "auto"},
                                             {"run", "--scenario", f, "--fastsim", ""},
                                             {"run", "--scenario", "/nonexistent/x.csv"}})
    EXPECT_EQ(cli(args).code, 1) << args.back();
  // Given twice, an option's last value counts; --name=value reads as --name value.
  const CliResult twice = cli({"run", "--scenario", f, "--model", "exact", "--model", "steady"});
  const CliResult once = cli({"run", "--scenario=" + f, "--model=steady"});
  ASSERT_EQ(twice.code, 0) << twice.err;
  EXPECT_EQ(twice.out, once.out);
}

TEST(ContactCli, BadScenarioExitsNonZeroNamingLineAndField) {
  const std::string missing = writeTemp("m.csv", "t,V,xi,eta,phi\n0,20,0,0,0\n");
  CliResult r = cli({"run", "--scenario", missing});
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("m.csv:1: missing column 'fz'"), std::string::npos) << r.err;
  const std::string bad =
      writeTemp("b.csv", "t,V,xi,eta,phi,fz\n0,20,0,0,0,1e4\n1,20,zz,0,0,1e4\n");
  r = cli({"run", "--scenario", bad});
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("b.csv:3: field 'xi': not a number ('zz')"), std::string::npos) << r.err;
}

TEST(ContactCli, RefusedRowsAreWrittenWithStatusNotNaN) {
  // The exact model refuses a load above fz_max (its fixed grid must cover the patch).
  const std::string f =
      writeTemp("big.csv", "t,V,xi,eta,phi,fz\n0,20,1e-3,0,0,1e6\n1,20,1e-3,0,0,0\n");
  const CliResult r = cli({"run", "--scenario", f, "--model", "exact", "--nx", "8", "--ny", "8"});
  EXPECT_EQ(r.code, 0);
  const auto rows = parseCsv(r.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][8], "rejected input");
  EXPECT_EQ(rows[2][8], "no load");
  EXPECT_EQ(std::stod(rows[1][1]), 0.0);
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  EXPECT_NE(r.err.find("fz above fz_max"), std::string::npos) << r.err;
}

TEST(ContactCli, AnOkRowsNoteGoesToStderrWhereItBegins) {
  // Rows 2-4 give a patch twice a0, b0: the fixed mesh grows on row 2 (its note), and rows 3-4
  // have nothing to say; the rows' status stays ok.
  const std::string f =
      writeTemp("grow.csv",
                "t,V,xi,eta,phi,fz,a,b\n0,20,1e-5,0,0,8e4,6e-3,4e-3\n"
                "1e-4,20,1e-5,0,0,8e4,12e-3,8e-3\n2e-4,20,1e-5,0,0,8e4,12e-3,8e-3\n"
                "3e-4,20,1e-5,0,0,8e4,12e-3,8e-3\n");
  const CliResult r = cli({"run", "--scenario", f, "--model", "nss"});
  EXPECT_EQ(r.code, 0);
  const auto rows = parseCsv(r.out);
  ASSERT_EQ(rows.size(), 5u);
  for (size_t k = 1; k < rows.size(); ++k) EXPECT_EQ(rows[k][8], "ok") << k;
  EXPECT_EQ(r.err.find(f + ": row at t = 0.0001: the step's patch exceeds the fixed mesh"), 0u)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(ContactCli, BackwardsRowsRollBackwards) {
  // Every model, the exact one included (its first row, from rest, has rolled nothing yet).
  const std::string f =
      writeTemp("back.csv", "t,V,xi,eta,phi,fz\n0,-20,1e-3,0,0,8e4\n0.001,-20,1e-3,0,0,8e4\n");
  for (const char* model : {"steady", "shen-li", "nss", "exact"}) {
    const CliResult r = cli({"run", "--scenario", f, "--model", model, "--nx", "8", "--ny", "8"});
    EXPECT_EQ(r.code, 0) << model;
    const auto rows = parseCsv(r.out);
    ASSERT_EQ(rows.size(), 3u) << model;
    EXPECT_EQ(rows[2][8], "ok") << model;
    EXPECT_GT(std::stod(rows[2][1]), 0.0) << model;  // V xi < 0: the force on the wheel is positive
  }
}

TEST(ContactCli, ExecutableRunsTheShippedDemoScenario) {
  const std::string cmd = std::string(WRC_CONTACT_CLI) + " run --scenario " + WRC_SOURCE_DIR +
                          "/scenes/demo.csv --model steady";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buf[4096];
  std::string out;
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  EXPECT_EQ(pclose(pipe), 0);
  EXPECT_GT(parseCsv(out).size(), 10u);
  EXPECT_EQ(out.find("nan"), std::string::npos);
}

TEST(ContactCli, FreqForEveryFastSimModel) {
  for (const char* model : {"steady", "shen-li", "nss"}) {
    const CliResult r = cli({"freq", "--model", model, "--kind", "eta", "--ab", "1",
                             "--lambda-over-a", "3,30", "--nx", "16", "--ny", "16"});
    ASSERT_EQ(r.code, 0) << model << r.err;
    const auto rows = parseCsv(r.out);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0][0] + "," + rows[0][1] + "," + rows[0][2] + "," + rows[0][3] + "," +
                  rows[0][4] + "," + rows[0][5],
              "lambda_over_a,c_real,c_imag,magnitude,phase_deg,c_steady");
    const double steady = std::stod(rows[1][5]);
    EXPECT_NEAR(steady, kalkerCoefficients(1.0, 0.28).c22, 0.01 * steady);
    if (std::string(model) == "steady")
      EXPECT_EQ(std::stod(rows[1][2]), 0.0);
    else
      EXPECT_LT(std::stod(rows[1][2]), 0.0);                          // a lag at lambda/a = 3
    EXPECT_LT(std::stod(rows[1][3]), std::stod(rows[2][3]) + 1e-12);  // shorter wave, smaller |C|
  }
}

TEST(ContactCli, RunHonoursTheOptionalGeometryAndFrictionColumns) {
  // Row 1: the parameters; row 2: a round patch of its own, linear theory at a/b = 1; row 3:
  // mu = 0.1 saturated; row 4: a negative a, rejected with its reason on stderr.
  const std::string f = writeTemp("geom.csv",
                                  "t,V,xi,eta,phi,fz,a,b,mu\n0,20,1e-7,0,0,8e4,0,0,0\n"
                                  "0.001,20,1e-7,0,0,8e4,5e-3,5e-3,0\n"
                                  "0.002,20,0.5,0,0,8e4,0,0,0.1\n"
                                  "0.003,20,0.5,0,0,8e4,-5e-3,5e-3,0\n");
  for (const char* model : {"steady", "nss"}) {
    const CliResult r = cli({"run", "--scenario", f, "--model", model, "--mesh", "adaptive"});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto rows = parseCsv(r.out);
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_EQ(std::stod(rows[1][5]), 6e-3) << model;
    EXPECT_EQ(std::stod(rows[2][5]), 5e-3) << model;
    EXPECT_EQ(std::stod(rows[2][6]), 5e-3) << model;
    if (std::string(model) == "steady") {
      const double Gab = 8.2e10 * 5e-3 * 5e-3, c11 = kalkerCoefficients(1.0, 0.28).c11;
      EXPECT_NEAR(std::stod(rows[2][1]), -Gab * c11 * 1e-7, 0.005 * Gab * c11 * 1e-7);
      EXPECT_NEAR(std::stod(rows[3][1]), -0.1 * 8e4, 1e-6 * 0.1 * 8e4);
    }
    EXPECT_EQ(rows[4][8], "rejected input") << model;
    EXPECT_NE(r.err.find("a must be in [1e-6, 1] m"), std::string::npos) << r.err;
  }
}
