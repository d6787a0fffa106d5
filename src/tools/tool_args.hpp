// The offline tools' former option reader, "--name value" pairs and bare switches walked by hand.
// Kept only for identify_calibration, which has not moved to CLI11 yet; every other tool reads its
// options with CLI11 (tool_options.hpp), and so should identify_calibration, after which this
// header goes. The same rules: a missing value, an unknown name or an unreadable number is one
// message naming the option and exit code 2; "--help" prints the tool's usage and exits 0.
#pragma once

#include <cstddef>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "tool_options.hpp"  // runTool, requireFolder, writeFile

namespace wheel_rail_contact {
namespace tools {

/// The options of one command line, walked name by name.
class Args {
 public:
  Args(int argc, char** argv) : words_(argv + 1, argv + argc) {}
  /// Moves to the next option name; false after the last.
  bool next() {
    if (k_ >= words_.size()) return false;
    name_ = words_[k_++];
    return true;
  }
  bool is(const char* name) const { return name_ == name; }
  const std::string& name() const { return name_; }
  /// The current option's value (consumed).
  std::string text() {
    if (k_ >= words_.size()) throw std::invalid_argument("option " + name_ + " needs a value");
    return words_[k_++];
  }
  int integer() { return number<int>(text()); }
  double real() { return number<double>(text()); }
  /// A comma-separated list as the current option's value.
  std::vector<int> integers() { return list<int>(); }
  std::vector<double> reals() { return list<double>(); }
  [[noreturn]] void unknown() const { throw std::invalid_argument("unknown option " + name_); }

 private:
  template <class T>
  T number(const std::string& v) const {
    try {
      size_t used = 0;
      const T x = std::is_integral<T>::value ? T(std::stoi(v, &used)) : T(std::stod(v, &used));
      if (used == v.size()) return x;
    } catch (const std::exception&) {  // stoi/stod: invalid_argument or out_of_range
    }
    throw std::invalid_argument("option " + name_ + ": not a number: '" + v + "'");
  }
  template <class T>
  std::vector<T> list() {
    std::vector<T> out;
    std::string item;
    for (std::istringstream items(text()); std::getline(items, item, ',');)
      out.push_back(number<T>(item));
    return out;
  }

  std::vector<std::string> words_;
  size_t k_ = 0;
  std::string name_;
};

/// Walks argv, calling option(args) at each name (it reads its value or calls args.unknown()).
/// False when the tool must stop with *exitCode: 0 after --help, 2 after a bad option.
template <class Option>
bool parseArgs(const char* tool, const char* usage, int argc, char** argv, Option option,
               int* exitCode) {
  Args args(argc, argv);
  try {
    while (args.next()) {
      if (args.is("--help") || args.is("-h")) {
        std::cout << usage;
        *exitCode = 0;
        return false;
      }
      option(args);
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << tool << ": " << e.what() << "\n" << usage;
    *exitCode = 2;
    return false;
  }
  return true;
}

/// A tool's main: its Options read from argv by read(args, &options) (parseArgs), then
/// run(options) (runTool).
template <class Options, class Read, class Run>
int runMain(const char* tool, const char* usage, int argc, char** argv, Read read, Run run) {
  Options o;
  int code = 0;
  if (!parseArgs(
          tool, usage, argc, argv, [&](Args& a) { read(a, &o); }, &code))
    return code;
  return runTool(tool, [&] { return run(o); });
}

}  // namespace tools
}  // namespace wheel_rail_contact
