// Fails on any C++ file that differs from .clang-format's style.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

TEST(Style, ClangFormatClean) {
  if (std::system("command -v clang-format > /dev/null 2>&1") != 0)
    FAIL() << "clang-format missing";
  const std::string cmd = std::string("cd ") + WRC_SOURCE_DIR +
                          " && git ls-files -co --exclude-standard '*.cpp' '*.hpp' | "
                          "xargs -r clang-format --dry-run --Werror 2>&1";
  EXPECT_EQ(std::system((cmd + " > /dev/null").c_str()), 0)
      << "run: clang-format -i $(git ls-files '*.cpp' '*.hpp')";
}
