// The offline tools' command line (src/tools/tool_options.hpp, CLI11): a typo or a dangling option
// must stop the tool before it runs for minutes with defaults and overwrites the committed results.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../src/tools/tool_options.hpp"

using namespace wheel_rail_contact;

namespace {

struct Parsed {
  bool run = false;
  int code = -1;
  int grid = 30;
  double tol = 0.1;
  std::vector<int> meshes = {5, 10, 20};
  std::vector<std::string> fastsims = {"classic", "calibrated"};
  std::vector<double> shares = {0.5};  // may be empty
  bool refresh = false;
  std::string out, err;
};

Parsed parse(std::vector<std::string> words) {
  words.insert(words.begin(), "tool");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(&w[0]);
  Parsed p;
  CLI::App app{"A tool.", "tool"};
  tools::option(app, "--grid", &p.grid, "exact grid");
  tools::option(app, "--tol", &p.tol, "tolerance");
  tools::option(app, "--meshes", &p.meshes, "meshes");
  tools::option(app, "--fastsim", &p.fastsims, "variants", {"classic", "calibrated"});
  tools::option(app, "--shares", &p.shares, "shares ('': none)", {}, true);
  tools::flag(app, "--refresh", &p.refresh, "recompute");
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  p.run = tools::parseOptions(app, static_cast<int>(argv.size()), argv.data(), &p.code);
  p.out = testing::internal::GetCapturedStdout();
  p.err = testing::internal::GetCapturedStderr();
  return p;
}

}  // namespace

TEST(ToolOptions, ReadsValuesListsAndSwitches) {
  const Parsed p = parse({"--grid", "40", "--meshes", "5,10", "--refresh", "--tol", "0.05",
                          "--fastsim", "calibrated"});
  ASSERT_TRUE(p.run) << p.err;
  EXPECT_EQ(p.grid, 40);
  EXPECT_EQ(p.meshes, (std::vector<int>{5, 10}));
  EXPECT_EQ(p.fastsims, (std::vector<std::string>{"calibrated"}));
  EXPECT_TRUE(p.refresh);
  EXPECT_DOUBLE_EQ(p.tol, 0.05);
}

TEST(ToolOptions, DefaultsStandAndTheLastValueWins) {
  Parsed p = parse({});
  ASSERT_TRUE(p.run);
  EXPECT_EQ(p.grid, 30);
  EXPECT_EQ(p.meshes, (std::vector<int>{5, 10, 20}));
  EXPECT_FALSE(p.refresh);
  p = parse({"--grid", "40", "--grid", "50", "--meshes", "5,10", "--meshes", "40"});
  ASSERT_TRUE(p.run) << p.err;
  EXPECT_EQ(p.grid, 50);
  EXPECT_EQ(p.meshes, (std::vector<int>{40}));
}

TEST(ToolOptions, AnEmptyWordIsTheEmptyListOnlyWhereThatMeansNone) {
  Parsed p = parse({"--shares", ""});
  ASSERT_TRUE(p.run) << p.err;
  EXPECT_TRUE(p.shares.empty());
  p = parse({"--shares", "0.25,0.75"});
  ASSERT_TRUE(p.run) << p.err;
  EXPECT_EQ(p.shares, (std::vector<double>{0.25, 0.75}));
  for (const char* name : {"--meshes", "--fastsim"}) {
    p = parse({name, ""});
    EXPECT_FALSE(p.run) << name;
    EXPECT_EQ(p.code, 2) << name;
  }
}

TEST(ToolOptions, HelpListsEveryOptionWithItsDefaultAndStopsWithCodeZero) {
  const Parsed p = parse({"--grid", "40", "--help"});
  EXPECT_FALSE(p.run);
  EXPECT_EQ(p.code, 0);
  for (const char* shown : {"--grid INT=30", "--tol FLOAT=0.1", "--meshes INT,...=5,10,20",
                            "--fastsim TEXT,...=classic,calibrated", "--refresh"})
    EXPECT_NE(p.out.find(shown), std::string::npos) << shown << "\n" << p.out;
}

TEST(ToolOptions, BadCommandLinesStopWithCodeTwoNamingTheOption) {
  const struct {
    std::vector<std::string> words;
    const char* mention;
  } cases[] = {
      {{"--grid"}, "--grid"},
      {{"--grid", "4x"}, "--grid"},
      {{"--grid", "99999999999"}, "--grid"},
      {{"--meshes", "5,,10"}, "--meshes"},  // an empty item: a typo
      {{"--meshes", "5,x"}, "--meshes"},
      {{"--meshes", "5", "10"}, "10"},  // a list is one word
      {{"--tol", "abc"}, "--tol"},
      {{"--fastsim", "fast"}, "--fastsim"},
      {{"--bogus", "1"}, "--bogus"},
      {{"40"}, "40"},
  };
  for (const auto& c : cases) {
    const Parsed p = parse(c.words);
    EXPECT_FALSE(p.run) << c.words[0];
    EXPECT_EQ(p.code, 2) << c.words[0];
    EXPECT_EQ(p.err.rfind("tool: ", 0), 0u) << p.err;
    EXPECT_NE(p.err.find(c.mention), std::string::npos) << p.err;
  }
}

TEST(ToolOptions, RunToolTurnsAnExceptionIntoCodeOne) {
  EXPECT_EQ(tools::runTool("tool", [] { return 0; }), 0);
  EXPECT_EQ(tools::runTool("tool", []() -> int { throw std::invalid_argument("nx must be >= 2"); }),
            1);
  EXPECT_THROW(tools::requireFolder("/nonexistent/folder"), std::runtime_error);
}
