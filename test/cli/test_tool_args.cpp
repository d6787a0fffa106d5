// identify_calibration's command line (src/tools/tool_args.hpp; the other tools read theirs with
// CLI11, test_tool_options.cpp): a typo or a dangling option must stop the tool before it runs for
// minutes with defaults and overwrites the committed results.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../src/tools/tool_args.hpp"

using namespace wheel_rail_contact;

namespace {

struct Parsed {
  bool run = false;
  int code = -1;
  int grid = 30;
  double tol = 0.1;
  std::vector<int> meshes;
  bool refresh = false;
};

Parsed parse(std::vector<std::string> words) {
  words.insert(words.begin(), "tool");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(&w[0]);
  Parsed p;
  auto option = [&](tools::Args& a) {
    if (a.is("--grid"))
      p.grid = a.integer();
    else if (a.is("--tol"))
      p.tol = a.real();
    else if (a.is("--meshes"))
      p.meshes = a.integers();
    else if (a.is("--refresh"))
      p.refresh = true;
    else
      a.unknown();
  };
  p.run = tools::parseArgs("tool", "usage: tool\n", static_cast<int>(argv.size()), argv.data(),
                           option, &p.code);
  return p;
}

}  // namespace

TEST(ToolArgs, ReadsValuesListsAndSwitches) {
  const Parsed p = parse({"--grid", "40", "--meshes", "5,10", "--refresh", "--tol", "0.05"});
  ASSERT_TRUE(p.run);
  EXPECT_EQ(p.grid, 40);
  EXPECT_EQ(p.meshes, (std::vector<int>{5, 10}));
  EXPECT_TRUE(p.refresh);
  EXPECT_DOUBLE_EQ(p.tol, 0.05);
}

TEST(ToolArgs, HelpStopsWithCodeZero) {
  const Parsed p = parse({"--grid", "40", "--help"});
  EXPECT_FALSE(p.run);
  EXPECT_EQ(p.code, 0);
}

TEST(ToolArgs, BadCommandLinesStopWithCodeTwo) {
  for (const auto& words : std::vector<std::vector<std::string>>{{"--grid"},
                                                                 {"--grid", "4x"},
                                                                 {"--grid", "99999999999"},
                                                                 {"--meshes", "5,,x"},
                                                                 {"--tol", "abc"},
                                                                 {"--bogus", "1"},
                                                                 {"40"}}) {
    const Parsed p = parse(words);
    EXPECT_FALSE(p.run) << words[0];
    EXPECT_EQ(p.code, 2) << words[0];
  }
}
