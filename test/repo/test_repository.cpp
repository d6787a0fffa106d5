// The repository's own tooling: C++ style, self-containment, and the build scripts' retry after a
// compiler crash.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace {

int shell(const std::string& cmd) {
  return std::system((cmd + " > /dev/null 2>&1").c_str());
}

// Runs make_retry with a fake `make` that prints `message` and fails on its first `failures` calls
// (as GCC's crash did in CI, or as a plain compile error); returns make_retry's exit status and how
// many times make ran.
std::pair<int, int> fakeMakeRetry(int failures, const std::string& message) {
  const std::string dir = ::testing::TempDir() + "make_retry";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/make") << "#!/bin/sh\nn=$(($(cat calls 2>/dev/null || echo 0) + 1))\n"
                               << "echo $n > calls\n[ $n -gt " << failures << " ] && exit 0\n"
                               << "echo '" << message << "'\nexit 2\n";
  std::filesystem::permissions(dir + "/make", std::filesystem::perms::owner_all);
  const int status = shell("cd " + dir + " && PATH=$PWD:$PATH bash -c '. " + WRC_SOURCE_DIR +
                           "/scripts/make_retry.sh && make_retry log all'");
  int calls = 0;
  std::ifstream(dir + "/calls") >> calls;
  return {status, calls};
}

}  // namespace

TEST(Style, ClangFormatClean) {
  if (shell("command -v clang-format") != 0) FAIL() << "clang-format missing";
  const std::string cmd = std::string("cd ") + WRC_SOURCE_DIR +
                          " && git ls-files -co --exclude-standard '*.cpp' '*.hpp' | "
                          "xargs -r clang-format --dry-run --Werror";
  EXPECT_EQ(shell(cmd), 0) << "run: clang-format -i $(git ls-files '*.cpp' '*.hpp')";
}

TEST(SelfContained, NothingNamesAPathOutsideTheRepository) {
  // A clone alone builds and passes: no source, script, build file or doc reaches a sibling
  // directory (the team's shared material) or cites notes that are not in the repository.
  const std::string cmd = std::string("cd ") + WRC_SOURCE_DIR +
                          " && git ls-files -co --exclude-standard | grep -v '^CHANGELOG.rst$' | "
                          "xargs -r grep -l -e '\\.\\./[s]hared' -e 'shared/[r]eference' -e "
                          "'shared/[d]ocs' -e 'method-[n]otes'";
  EXPECT_NE(shell(cmd), 0) << "run: " << cmd;
}

TEST(BuildScripts, MakeRetryRetriesOnceAfterACompilerCrash) {
  const auto [status, calls] =
      fakeMakeRetry(1, "x.cpp:1: internal compiler error: Segmentation fault");
  EXPECT_EQ(status, 0);
  EXPECT_EQ(calls, 2);
}

TEST(BuildScripts, MakeRetryGivesUpAfterASecondCrash) {
  const auto [status, calls] = fakeMakeRetry(2, "internal compiler error");
  EXPECT_NE(status, 0);
  EXPECT_EQ(calls, 2);
}

TEST(BuildScripts, MakeRetryDoesNotRetryACompileError) {
  const auto [status, calls] = fakeMakeRetry(1, "x.cpp:1: error: expected ; before }");
  EXPECT_NE(status, 0);
  EXPECT_EQ(calls, 1);
}

TEST(BuildScripts, JunitOfAFailedRunStaysReadableWithAColouredLog) {
  // A sanitized rostest's log carries rosconsole's colour codes (ESC [ 0 m): written into the
  // failure text as they were, they made sanitizers.xml unreadable XML, and CI counted an
  // unreadable file instead of the failed test.
  const std::string dir = ::testing::TempDir() + "write_junit";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/run.log") << "\x1b[33m[ WARN] stamp rejected\x1b[0m\x01\nFAILED\n";
  ASSERT_EQ(shell("/usr/bin/python3 " + std::string(WRC_SOURCE_DIR) + "/scripts/write_junit.py s " +
                  dir + "/out.xml 'run|3|exit code 1|" + dir + "/run.log' 'ok|1|passed|'"),
            0);
  EXPECT_EQ(shell("/usr/bin/python3 -c \"import xml.etree.ElementTree as E; "
                  "r = E.parse('" +
                  dir +
                  "/out.xml').getroot(); "
                  "f = r.find('testcase/failure'); "
                  "assert len(r) == 2 and 'stamp rejected' in f.text and 'FAILED' in f.text\""),
            0);
}
