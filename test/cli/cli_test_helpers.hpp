// What the contact_cli tests share: running the CLI in-process and writing input files (tests
// only).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/cli/cli.hpp"

namespace wheel_rail_contact {

/// A file of the given text in gtest's temporary folder; returns its path.
inline std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// One run of contact_cli: its exit code and what it wrote to stdout and stderr.
struct CliResult {
  int code;
  std::string out, err;
};

inline CliResult cli(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace wheel_rail_contact
