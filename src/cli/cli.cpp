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
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"
#include "wheel_rail_contact/wheelset/wheelset_scenario.hpp"

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
const char* const kWheelsetHelp =
    "A wheelset on its track, from a wheel and a rail profile (the right side's; the left ones\n"
    "mirrored): replays a wheelset scenario CSV (SI, REP 103 track axes, any column order)\n"
    "t,y,yaw,roll,V,omega,fz (s, m, rad, rad, m/s, rad/s, N; omega the pitch rate about the\n"
    "axle, about V/r0 > 0 rolling forward; fz the vertical load per wheel), or fz_left,fz_right\n"
    "instead of fz, and optionally vy,yaw_rate,curvature (m/s, rad/s, 1/m, positive for a curve\n"
    "to the left), cant (rad, the track's under the wheelset, positive raises the left rail;\n"
    "without the column --config's cant, default 0), vz,roll_rate (m/s, rad/s). Writes CSV to\n"
    "stdout, one row per contact patch:\n"
    "t,wheel,patch,y_rail,z_rail,y_wheel,contact_angle,rolling_radius,xi,eta,phi,fn,fx,fs,mz,\n"
    "a,b,pmax,status (wheel left|right; patch its zone tread|gauge_corner|flange, _2 for a\n"
    "second one; y_rail,z_rail,y_wheel the contact point in the profile files' own coordinates,\n"
    "m; fx,fs,mz on the wheel in the patch's contact plane; a,b the equivalent ellipse; pmax Pa).\n"
    "fx,fs,mz come from --model run with the patch's fn and creepages on its strips (a\n"
    "non-Hertzian, blended or flange patch) or its ellipse (a Hertz patch), one model per\n"
    "wheel and patch slot (doc/true_patch.md). A wheel without a patch: one row with\n"
    "patch none and its status (no_contact, no_load, invalid_input, ...), geometry and\n"
    "creepages empty, forces zero. --config: the model's parameters and the wheelset and\n"
    "track data (nominal_radius, flange_back_distance, flange_back_position, gauge,\n"
    "gauge_depth, rail_inclination; profile_length_unit, profile_lateral_axis,\n"
    "profile_vertical_axis, profile_smoothing_length), defaults the Manchester benchmark's,\n"
    "and cant, the scenario's cant where it has no cant column (doc/wheelset.md).";
const char* const kUsage =
    "usage: contact_cli run --scenario FILE.csv [--config FILE.yaml] [--model M] [--PARAMETER V]\n"
    "       contact_cli wheelset --wheel-profile FILE --rail-profile FILE --scenario FILE.csv\n"
    "                  [--config FILE.yaml] [--model M] [--PARAMETER V] [--contact-table]\n"
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
  CLI::App* wheelset = nullptr;
  bool help = false, contactTable = false;
  std::string scenario, config, kind, ab, lambdaOverA, wheelProfile, railProfile;
  CLI::Option* configOption = nullptr;
  CLI::Option* wheelsetConfigOption = nullptr;
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
    wheelset = app.add_subcommand("wheelset", kWheelsetHelp)->fallthrough()->allow_extras();
    wheelset->add_option("--wheel-profile", wheelProfile, "wheel profile file (right wheel)")
        ->option_text("FILE")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    wheelset->add_option("--rail-profile", railProfile, "rail profile file (right rail)")
        ->option_text("FILE")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    wheelset->add_option("--scenario", scenario, "wheelset scenario CSV")
        ->option_text("FILE")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    wheelsetConfigOption =
        wheelset
            ->add_option("--config", config,
                         "YAML: the parameters (as run's) and the wheelset and track data; "
                         "options given on the command line override it")
            ->option_text("FILE")
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    wheelset->add_flag("--contact-table", contactTable,
                       "search through a contact table built once (interpolated) instead of the "
                       "direct search");
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
    const bool command = run->parsed() || freq->parsed() || wheelset->parsed();
    for (const CLI::App* a : std::initializer_list<const CLI::App*>{&app, run, freq, wheelset})
      for (const std::string& word : a->remaining()) {
        if (word.rfind("--", 0) == 0)
          throw UsageError(word.substr(2, word.find('=') - 2) + ": unknown parameter");
        if (a == &app && !command) throw UsageError("unknown command '" + word + "'");
        throw UsageError("unexpected argument '" + word + "'");
      }
    if (!command) throw UsageError("missing command");
  }

  std::string helpText() const {
    return app.get_formatter()->make_help(&app, "contact_cli", CLI::AppFormatMode::All);
  }

  // The parameters: the defaults, then --config's file, then the options in the order given.
  // With `w` (the wheelset command), --config's wheelset and track keys go to *w.
  ContactParameters contactParameters(WheelsetConfig* w = nullptr) const {
    ContactParameters p;
    if (w && wheelsetConfigOption->count() > 0) loadWheelsetConfigYaml(config, &p, w);
    if (!w && configOption->count() > 0) loadConfigYaml(config, &p);
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

// One number of the wheelset command's output.
std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The status column of a patch: the wheel's when it has none, else the tangential model's.
const char* patchStatus(const PatchResult& p) {
  if (p.creepages.status == CreepageStatus::kInvalidInput) return "creepages_invalid";
  switch (p.tangential_status) {
    case StepStatus::kOk:
      return "ok";
    case StepStatus::kNoLoad:
      return "tangential_no_load";
    case StepStatus::kStandstill:
      return "standstill";
    case StepStatus::kRejected:
      return "tangential_rejected";
    case StepStatus::kNotConverged:
      return "tangential_not_converged";
  }
  return "unknown";
}

// Each slot's last note (an ok step's message: the fixed mesh grew, a coarse patch), so that a
// note goes to stderr where it begins, once for a run of rows that repeat it, as run does.
using Notes = std::map<std::string, std::string>;

void writeWheel(std::ostream& out, std::ostream& err, const std::string& file, double t,
                const WheelResult& w, Notes* notes) {
  const char* wheel = w.side == WheelSide::kLeft ? "left" : "right";
  if (w.patches.empty()) {
    // No patch: its geometry and creepages do not exist (empty), its forces are zero.
    out << num(t) << "," << wheel << ",none,,,,,,,,,0,0,0,0,0,0,0," << toString(w.status) << "\n";
    if (!w.message.empty())
      err << file << ": row at t = " << t << ": " << wheel << " wheel: " << w.message << "\n";
    return;
  }
  for (const PatchResult& p : w.patches) {
    const ContactCandidate& g = p.geometry;
    out << num(t) << "," << wheel << "," << p.slot << "," << num(g.rail_file.x()) << ","
        << num(g.rail_file.y()) << "," << num(g.wheel_file.x()) << "," << num(g.contact_angle)
        << "," << num(g.rolling_radius) << "," << num(p.creepages.xi) << "," << num(p.creepages.eta)
        << "," << num(p.creepages.phi) << "," << num(p.normal.fn) << "," << num(p.fx) << ","
        << num(p.fs) << "," << num(p.mz) << "," << num(p.normal.a) << "," << num(p.normal.b) << ","
        << num(p.normal.pmax) << "," << patchStatus(p) << "\n";
    const bool ok = p.tangential_status == StepStatus::kOk;
    std::string& note = (*notes)[std::string(wheel) + " " + p.slot];
    if ((!ok && !p.message.empty()) || (ok && !p.message.empty() && p.message != note))
      err << file << ": row at t = " << t << ": " << wheel << " " << p.slot << ": " << p.message
          << "\n";
    if (ok) note = p.message;
  }
}

int runWheelset(const CommandLine& c, std::ostream& out, std::ostream& err) {
  for (const char* required : {"--wheel-profile", "--rail-profile", "--scenario"})
    if (c.wheelset->count(required) == 0)
      throw UsageError(std::string("wheelset: ") + required + " FILE is required");
  WheelsetConfig w;
  const ContactParameters p = c.contactParameters(&w);
  w.track.wheel_right = std::make_shared<const Profile>(
      Profile::read(c.wheelProfile, ProfileKind::kWheel, w.profile_read));
  w.track.rail_right = std::make_shared<const Profile>(
      Profile::read(c.railProfile, ProfileKind::kRail, w.profile_read));
  const std::string& file = c.scenario;
  std::ifstream in(file);
  if (!in) throw std::invalid_argument("scenario: cannot open '" + file + "'");
  const std::vector<WheelsetScenarioRow> rows = readWheelsetScenario(in, file);
  WheelsetContactOptions options;
  options.use_contact_table = c.contactTable;
  WheelsetContact contact(w.track, p, options);
  out << "t,wheel,patch,y_rail,z_rail,y_wheel,contact_angle,rolling_radius,xi,eta,phi,fn,fx,fs,"
         "mz,a,b,pmax,status\n";
  Notes notes;
  for (size_t k = 0; k < rows.size(); ++k) {
    const WheelsetScenarioRow& r = rows[k];
    WheelsetState s;
    s.pose.y = r.y;
    s.pose.yaw = r.yaw;
    s.pose.roll = r.roll;
    s.motion.V = r.V;
    s.motion.omega = r.omega;
    s.motion.vy = r.vy;
    s.motion.yaw_rate = r.yaw_rate;
    s.motion.curvature = r.curvature;
    s.motion.cant = r.cant.value_or(w.cant);
    s.motion.vz = r.vz;
    s.motion.roll_rate = r.roll_rate;
    s.fz_left = r.fz_left;
    s.fz_right = r.fz_right;
    const WheelsetResult res = contact.step(s, k == 0 ? 0.0 : r.t - rows[k - 1].t);
    writeWheel(out, err, file, r.t, res.left, &notes);
    writeWheel(out, err, file, r.t, res.right, &notes);
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
    if (c.wheelset->parsed()) return runWheelset(c, out, err);
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
