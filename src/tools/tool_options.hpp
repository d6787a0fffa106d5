// Command-line options of the offline tools, read by CLI11 (as contact_cli's). A missing value, an
// unknown name, a stray word or an unreadable number is one message naming the option and exit
// code 2; "--help" lists every option with its default and exits 0. So a typo never runs a long
// job with defaults (and overwrites the committed results in doc/data). Past the command line,
// runTool() turns an exception (a value the library refuses, an output that cannot be written)
// into one message and exit code 1 instead of an abort.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheel_rail_contact {
namespace tools {

/// "a, b, c".
inline std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// The option --name into *value, its current value shown as the default; given twice, the last
/// value counts.
template <class T>
CLI::Option* option(CLI::App& app, const std::string& name, T* value, const std::string& help) {
  return app.add_option(name, *value, help)
      ->capture_default_str()
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

/// A list option: one word, comma-separated ("--meshes 5,10"), every item read as a T (an empty
/// one is an error, as a typo); given twice, the last word counts. `allowed`: the values an item
/// may take, if not any. `mayBeEmpty`: an empty word ('') is the empty list, where that means
/// "none" (else it is an error).
template <class T>
CLI::Option* option(CLI::App& app, const std::string& name, std::vector<T>* value,
                    const std::string& help, const std::vector<std::string>& allowed = {},
                    bool mayBeEmpty = false) {
  const CLI::callback_t read = [value, name, allowed, mayBeEmpty](const CLI::results_t& words) {
    if (mayBeEmpty && words.back().empty()) {
      value->clear();
      return true;
    }
    std::vector<T> items;
    std::istringstream in(words.back());
    for (std::string item; std::getline(in, item, ',');) {
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), item) == allowed.end())
        throw CLI::ValidationError(name, "'" + item + "' is not one of " + join(allowed));
      T x{};
      if (item.empty() || !CLI::detail::lexical_cast(item, x))
        throw CLI::ConversionError(name + ": cannot read '" + item + "' in '" + words.back() +
                                   "' as " + CLI::detail::type_name<T>());
      items.push_back(x);
    }
    if (items.empty()) throw CLI::ConversionError(name + ": an empty list");
    *value = items;
    return true;
  };
  std::ostringstream shown;
  for (size_t k = 0; k < value->size(); ++k) shown << (k ? "," : "") << (*value)[k];
  return app.add_option(name, read, help)
      ->type_name(std::string(CLI::detail::type_name<T>()) + ",...")
      ->default_str(shown.str())
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

/// A switch: --name sets *value.
inline CLI::Option* flag(CLI::App& app, const std::string& name, bool* value,
                         const std::string& help) {
  return app.add_flag(name, *value, help);
}

/// Reads argv into app's options. False when the tool must stop with *exitCode: 0 after --help
/// (the help on stdout), 2 after a bad command line (the message on stderr).
inline bool parseOptions(CLI::App& app, int argc, char** argv, int* exitCode) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    *exitCode = 0;
    return false;
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": " << e.what() << "\n"
              << "(" << app.get_name() << " --help: every option)\n";
    *exitCode = 2;
    return false;
  }
  return true;
}

/// The tool's work, body() returning its exit code; an exception ends it with a message, code 1.
template <class Body>
int runTool(const char* tool, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << tool << ": " << e.what() << "\n";
    return 1;
  }
}

/// Fails before a long run, not after it, when its output folder is missing.
inline void requireFolder(const std::string& path) {
  if (!std::filesystem::is_directory(path))
    throw std::runtime_error("output folder " + path + " does not exist");
}

/// A tool's main: addOptions(app, &options) declares its options (and the app's description) on
/// a CLI11 app named `tool`, parseOptions reads them, then run(options) (runTool).
template <class Options, class AddOptions, class Run>
int runMain(const char* tool, int argc, char** argv, AddOptions addOptions, Run run) {
  CLI::App app{"", tool};
  Options o;
  addOptions(app, &o);
  int code = 0;
  if (!parseOptions(app, argc, argv, &code)) return code;
  return runTool(tool, [&] { return run(o); });
}

/// `path` opened for writing, or std::runtime_error naming it.
inline std::ofstream writeFile(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

}  // namespace tools
}  // namespace wheel_rail_contact
