#include "cli.hpp"

#include "config_yaml.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>

#include "freq_command.hpp"

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/scenario.hpp"

namespace wheel_rail_contact {

namespace {

// The commands' descriptions (--help).
const char* const kRunHelp =
    "Replays a scenario CSV (header t,V,xi,eta,phi,fz in s, m/s, -, -, 1/m, N; one row per\n"
    "time step, t strictly increasing) through one model and writes CSV to stdout:\n"
    "t,fx,fy,mz,fz,a,b,adhesion_fraction,status (N, N, N m, N, m, m, -, text).\n"
    "dt of a row is its t minus the previous row's; the first row starts from zero\n"
    "traction history. The patch follows a = a0 (fz/fz0)^(1/3), b = b0 (fz/fz0)^(1/3),\n"
    "unless the optional columns a,b (m, both or neither) give it per row; the optional\n"
    "column mu gives the friction per row (0 in a row: the parameters apply; an empty\n"
    "cell or an unknown column is an error; doc/varying_geometry.md).\n"
    "Rows the model refuses (e.g. fz above fz_max with --model exact) are written with zero\n"
    "forces and their status, the reason on stderr; so is an ok row's note (the fixed mesh grew\n"
    "to hold the patch, or the patch covers few of its nodes) where it begins.\n"
    "V < 0 rolls backwards (every model; doc/conventions.md).\n"
    "--model exact steps internally by one grid element (dq = dx = 2.2 a_max/nx, inputs\n"
    "interpolated linearly between rows, the remainder carried over) and still writes one\n"
    "row per scenario row, at its t (the state after the last internal step).";
const char* const kFreqHelp =
    "Non-steady creep coefficient C11 (xi), C22 (eta) or C23 (phi) at each lambda/a, for\n"
    "a/b = R, one small harmonic creepage cos(2 pi q/lambda) in full adhesion at periodic\n"
    "steady state; C = -F^/(G a b) (G (ab)^1.5 for phi), Im C < 0 a lag. CSV to stdout:\n"
    "lambda_over_a,c_real,c_imag,magnitude,phase_deg,c_steady,magnitude_over_steady\n"
    "(c_steady: the same model's steady coefficient on the same grid). For exact, --nx/--ny\n"
    "are the grid MX x MY over [-1.1a, 1.1a] x [-1.1b, 1.1b]. For steady, shen-li and nss:\n"
    "the FastSim mesh nx x ny, the exact linear response of the model's space\n"
    "discretisation in the continuous-time limit (nss with the chi table at a/b).";
const char* const kUsage =
    "usage: contact_cli run --scenario FILE.csv [--config FILE.yaml] [--model M] [--PARAMETER V]\n"
    "       contact_cli freq --model M --kind {xi,eta,phi} --ab R --lambda-over-a L1,L2,...\n"
    "                  [--nu NU] [--nx N --ny N]\n"
    "       contact_cli --help\n";

// A command line contact_cli cannot take (an unknown command or option, a missing value or
// option): exit code 2, as the tools. A value the parameters refuse is exit code 1.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The command line as CLI11 reads it. The parameters' options are made from parameterDocs() (one
// name, one default, one rule with the node and the YAML): their text goes to setParameter, so
// an option and a YAML key are read, and refused, alike. They belong to the top level, where
// both commands fall through to them.
struct CommandLine {
  CLI::App app{"contact_cli: one wheel-rail contact model offline.", "contact_cli"};
  CLI::App* run = nullptr;
  CLI::App* freq = nullptr;
  bool help = false;
  std::string scenario, config, kind, ab, lambdaOverA;
  CLI::Option* configOption = nullptr;
  std::map<std::string, std::string> parameters;  // text of each parameter option given

  CommandLine() {
    app.set_help_flag();  // ours: the whole help, whichever command it follows
    app.add_flag("-h,--help", help, "this help, every command's options with their defaults");
    app.allow_extras();            // unknown options and stray words: our own messages, below
    app.require_subcommand(0, 1);  // a second command word is a stray word
    app.footer(std::string("\n") + kUsage);
    app.get_formatter()->column_width(34);
    for (const auto& d : parameterDocs()) {
      const std::string unit = d.unit.empty() || d.unit == "-" ? "" : d.unit + ", ";
      app.add_option("--" + d.name, parameters[d.name], d.meaning)
          ->option_text(unit + "default " + d.default_value)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
          ->group("Parameters (contact_node's private parameters too)");
    }
    run = app.add_subcommand("run", kRunHelp)->fallthrough()->allow_extras();
    run->add_option("--scenario", scenario, "scenario CSV")
        ->option_text("FILE")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    configOption =
        run->add_option("--config", config,
                        "contact_node's YAML (keys = the parameters' names; its node-only keys "
                        "are ignored); options given on the command line override it")
            ->option_text("FILE")
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    freq = app.add_subcommand("freq", kFreqHelp)->fallthrough()->allow_extras();
    freq->add_option("--kind", kind, "creepage: xi, eta or phi")
        ->option_text("KIND")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    freq->add_option("--ab", ab, "a/b of the patch, [0.05, 20]")
        ->option_text("R")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    freq->add_option("--lambda-over-a", lambdaOverA, "wavelengths lambda/a, comma-separated")
        ->option_text("L1,L2,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }

  void parse(const std::vector<std::string>& args) {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them reversed
    try {
      app.parse(reversed);
    } catch (const CLI::ArgumentMismatch& e) {  // "--nu: 1 required TEXT missing"
      const std::string what = e.what();
      throw UsageError(what.substr(0, what.find(':')) + ": missing value");
    } catch (const CLI::ParseError& e) {
      throw UsageError(e.what());
    }
    if (help) return;
    // What CLI11 left: an unknown option (named as setParameter names an unknown parameter,
    // without its dashes) or a word that is neither a command nor a value.
    for (const CLI::App* a : std::initializer_list<const CLI::App*>{&app, run, freq})
      for (const std::string& word : a->remaining()) {
        if (word.rfind("--", 0) == 0)
          throw UsageError(word.substr(2, word.find('=') - 2) + ": unknown parameter");
        if (a == &app && !run->parsed() && !freq->parsed())
          throw UsageError("unknown command '" + word + "'");
        throw UsageError("unexpected argument '" + word + "'");
      }
    if (!run->parsed() && !freq->parsed()) throw UsageError("missing command");
  }

  std::string helpText() const {
    return app.get_formatter()->make_help(&app, "contact_cli", CLI::AppFormatMode::All);
  }

  // The parameters: the defaults, then --config's file, then the options in the order given.
  ContactParameters contactParameters() const {
    ContactParameters p;
    if (configOption->count() > 0) loadConfigYaml(config, &p);
    std::set<std::string> done;
    for (const CLI::Option* o : app.parse_order()) {
      const std::string name = o->get_name().substr(2);
      if (parameters.count(name) && done.insert(name).second)
        setParameter(&p, name, parameters.at(name));
    }
    validate(p);
    return p;
  }
};

void writeRow(std::ostream& out, double t, const StepOutput& s) {
  char line[512];
  std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s\n", t, s.fx,
                s.fy, s.mz, s.fz, s.a, s.b, s.adhesionFraction, toString(s.status));
  out << line;
}

int runScenario(const CommandLine& c, std::ostream& out, std::ostream& err) {
  if (c.run->count("--scenario") == 0) throw UsageError("run: --scenario FILE is required");
  const ContactParameters p = c.contactParameters();
  const std::string& file = c.scenario;
  std::ifstream in(file);
  if (!in) throw std::invalid_argument("scenario: cannot open '" + file + "'");
  const std::vector<ScenarioRow> rows = readScenario(in, file);
  auto model = makeContactModel(p);
  out << "t,fx,fy,mz,fz,a,b,adhesion_fraction,status\n";
  // An ok row's note (the fixed mesh grew, a coarse patch) has no column: it goes to stderr where
  // it begins, once for a run of rows that repeat it.
  const char* note = "";
  for (size_t k = 0; k < rows.size(); ++k) {
    const ScenarioRow& r = rows[k];
    const StepOutput s = model->step(stepInputAt(rows, k));
    const bool ok = s.status == StepStatus::kOk;
    if (s.status == StepStatus::kRejected || (ok && *s.message && std::strcmp(s.message, note)))
      err << file << ": row at t = " << r.t << ": " << s.message << "\n";
    if (ok) note = s.message;
    writeRow(out, r.t, s);
  }
  return 0;
}

int runFreq(const CommandLine& c, std::ostream& out) {
  for (const char* required : {"--kind", "--ab", "--lambda-over-a"})
    if (c.freq->count(required) == 0)
      throw UsageError(std::string("freq: ") + required + " is required");
  return freqCommand(c.contactParameters(), c.kind, c.ab, c.lambdaOverA, out);
}

}  // namespace

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CommandLine c;
  try {
    c.parse(args);
    if (c.help) {
      out << c.helpText();
      return 0;
    }
    return c.run->parsed() ? runScenario(c, out, err) : runFreq(c, out);
  } catch (const UsageError& e) {
    err << "contact_cli: " << e.what() << "\n" << kUsage << "(contact_cli --help: every option)\n";
    return 2;
  } catch (const std::exception& e) {
    err << "contact_cli: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace wheel_rail_contact
