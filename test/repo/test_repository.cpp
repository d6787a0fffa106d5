// The repository's own tooling: C++ style, self-containment, and the build scripts' retry after a
// compiler crash.
#include <fnmatch.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

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

// The repository's files, relative to its root, as `git ls-files -co --exclude-standard` lists them
// (tracked, or untracked and not ignored), by a walk of the tree rather than git: a clone on a
// machine without git, or an unpacked tarball without .git, is checked the same. Skips .git and
// what .gitignore names; its patterns as git reads them: a trailing / names directories only, a
// leading or inner / anchors the pattern at the root, otherwise it matches a name anywhere.
std::vector<std::string> repositoryFiles() {
  namespace fs = std::filesystem;
  const fs::path root = WRC_SOURCE_DIR;
  std::vector<std::string> patterns;
  std::ifstream gitignore(root / ".gitignore");
  for (std::string line; std::getline(gitignore, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '!') ADD_FAILURE() << "repositoryFiles() does not read .gitignore's " << line;
    patterns.push_back(line);
  }
  const auto ignored = [&](const fs::path& relative, bool directory) {
    for (std::string pattern : patterns) {
      if (pattern.back() == '/') {
        if (!directory) continue;
        pattern.pop_back();
      }
      const bool anchored = pattern.find('/') != std::string::npos;
      if (pattern[0] == '/') pattern.erase(0, 1);
      const std::string name = anchored ? relative.generic_string() : relative.filename().string();
      if (fnmatch(pattern.c_str(), name.c_str(), FNM_PATHNAME) == 0) return true;
    }
    return false;
  };
  std::vector<std::string> files;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path relative = it->path().lexically_relative(root);
    if (relative == ".git" || ignored(relative, it->is_directory())) {
      it.disable_recursion_pending();
    } else if (it->is_regular_file()) {
      files.push_back(relative.generic_string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

TEST(RepositoryFiles, ListsWhatGitWouldAndNothingIgnored) {
  const std::vector<std::string> files = repositoryFiles();
  const auto listed = [&](const std::string& f) {
    return std::binary_search(files.begin(), files.end(), f);
  };
  EXPECT_TRUE(listed("CMakeLists.txt"));
  EXPECT_TRUE(listed(".gitignore"));
  EXPECT_TRUE(listed("test/repo/test_repository.cpp"));
  for (const std::string& f : files) {
    EXPECT_NE(f.rfind(".git/", 0), 0u) << f;
    EXPECT_NE(f.rfind("build/", 0), 0u) << f;
    EXPECT_FALSE(endsWith(f, ".pyc")) << f;
  }
  // In a git checkout, where git is installed: the very list git gives.
  const std::string gitList = ::testing::TempDir() + "git_ls_files";
  if (shell(std::string("cd ") + WRC_SOURCE_DIR + " && test -e .git && (git ls-files -co " +
            "--exclude-standard > " + gitList + ")") == 0) {
    std::vector<std::string> fromGit;
    std::ifstream in(gitList);
    for (std::string line; std::getline(in, line);) fromGit.push_back(line);
    std::sort(fromGit.begin(), fromGit.end());
    EXPECT_EQ(files, fromGit);
  }
}

TEST(Style, ClangFormatClean) {
  if (shell("command -v clang-format") != 0) FAIL() << "clang-format missing";
  const std::string list = ::testing::TempDir() + "clang_format_files";
  std::ofstream out(list);
  int count = 0;
  for (const std::string& f : repositoryFiles()) {
    if (endsWith(f, ".cpp") || endsWith(f, ".hpp")) {
      out << f << '\n';
      ++count;
    }
  }
  out.close();
  ASSERT_GT(count, 0);
  const std::string cmd = std::string("cd ") + WRC_SOURCE_DIR + " && xargs -d '\\n' -r -a " + list +
                          " clang-format --dry-run --Werror";
  EXPECT_EQ(shell(cmd), 0) << "run: clang-format -i on the files in " << list;
}

TEST(SelfContained, NothingNamesAPathOutsideTheRepository) {
  // A clone alone builds and passes: no source, script, build file or doc reaches a sibling
  // directory (the team's shared material) or cites notes that are not in the repository. (Each
  // needle is split here so that this file does not name it.)
  const std::vector<std::string> needles = {
      "../"
      "shared",
      "shared/"
      "reference",
      "shared/"
      "docs",
      "method-"
      "notes"};
  for (const std::string& f : repositoryFiles()) {
    if (f == "CHANGELOG.rst") continue;
    std::ifstream in(std::string(WRC_SOURCE_DIR) + "/" + f, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    for (const std::string& needle : needles) {
      EXPECT_EQ(text.find(needle), std::string::npos) << f << " names " << needle;
    }
  }
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
