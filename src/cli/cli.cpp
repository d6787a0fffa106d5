#include "cli.hpp"

#include "config_yaml.hpp"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include "freq_command.hpp"

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/scenario.hpp"

namespace wheel_rail_contact {

namespace {

struct Options {
  std::string command;
  std::map<std::string, std::string> values;  // --name value, in order of appearance
  std::vector<std::string> names;
};

const char* kUsage =
    "usage: contact_cli run --scenario FILE.csv [--config FILE.yaml] [--model M] [--OPTION VALUE]\n"
    "       contact_cli freq --model M --kind {xi,eta,phi} --ab R --lambda-over-a L1,L2,...\n"
    "                  [--nu NU] [--nx N --ny N]\n"
    "       contact_cli --help\n"
    "\n"
    "run: replays a scenario CSV (header t,V,xi,eta,phi,fz in s, m/s, -, -, 1/m, N; one row per\n"
    "     time step, t strictly increasing) through one model and writes CSV to stdout:\n"
    "     t,fx,fy,mz,fz,a,b,adhesion_fraction,status (N, N, N m, N, m, m, -, text).\n"
    "     dt of a row is its t minus the previous row's; the first row starts from zero\n"
    "     traction history. The patch follows a = a0 (fz/fz0)^(1/3), b = b0 (fz/fz0)^(1/3),\n"
    "     unless the optional columns a,b (m, both or neither) give it per row; the optional\n"
    "     column mu gives the friction per row (0 in a row: the parameters apply; an empty\n"
    "     cell or an unknown column is an error; doc/varying_geometry.md).\n"
    "     Rows the model refuses (e.g. fz above fz_max with --model exact) are written with zero\n"
    "     forces and their status, the reason on stderr; so is an ok row's note (the fixed mesh\n"
    "     grew to hold the patch, or the patch covers few of its nodes) where it begins.\n"
    "     V < 0 rolls backwards (every model; doc/conventions.md).\n"
    "     --model exact steps internally by one grid element (dq = dx = 2.2 a_max/nx, inputs\n"
    "     interpolated linearly between rows, the remainder carried over) and still writes one\n"
    "     row per scenario row, at its t (the state after the last internal step).\n"
    "\n"
    "freq: non-steady creep coefficient C11 (xi), C22 (eta) or C23 (phi) at each lambda/a, for\n"
    "     a/b = R, one small harmonic creepage cos(2 pi q/lambda) in full adhesion at periodic\n"
    "     steady state; C = -F^/(G a b) (G (ab)^1.5 for phi), Im C < 0 a lag. CSV to stdout:\n"
    "     lambda_over_a,c_real,c_imag,magnitude,phase_deg,c_steady,magnitude_over_steady\n"
    "     (c_steady: the same model's steady coefficient on the same grid). For exact, --nx/--ny\n"
    "     are the grid MX x MY over [-1.1a, 1.1a] x [-1.1b, 1.1b]. For steady, shen-li and nss:\n"
    "     the FastSim mesh nx x ny, the exact linear response of the model's space\n"
    "     discretisation in the continuous-time limit (nss with the chi table at a/b).\n";

Options parse(const std::vector<std::string>& args) {
  Options o;
  size_t k = 0;
  if (k < args.size() && args[k].rfind("--", 0) != 0) o.command = args[k++];
  for (; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--help" || a == "-h") {
      o.command = "help";
      return o;
    }
    if (a.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument '" + a + "'");
    if (k + 1 >= args.size()) throw std::invalid_argument(a + ": missing value");
    const std::string name = a.substr(2);
    if (!o.values.count(name)) o.names.push_back(name);
    o.values[name] = args[++k];
  }
  return o;
}

void printHelp(std::ostream& out) {
  out << kUsage << "\noptions (shared with contact_node's private parameters):\n";
  out << "  --scenario FILE   scenario CSV (run)\n";
  out << "  --config FILE     contact_node's YAML (keys = these names; its node-only keys are\n"
         "                    ignored); options given on the command line override it\n";
  for (const auto& d : parameterDocs()) {
    char line[200];
    std::snprintf(line, sizeof line, "  --%-10s %-4s default %-10s %s\n", d.name.c_str(),
                  d.unit.c_str(), d.default_value.c_str(), d.meaning.c_str());
    out << line;
  }
}

ContactParameters parametersFrom(const Options& o) {
  ContactParameters p;
  if (o.values.count("config")) loadConfigYaml(o.values.at("config"), &p);
  for (const auto& name : o.names)
    if (name != "scenario" && name != "config") setParameter(&p, name, o.values.at(name));
  validate(p);
  return p;
}

void writeRow(std::ostream& out, double t, const StepOutput& s) {
  char line[512];
  std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s\n", t, s.fx,
                s.fy, s.mz, s.fz, s.a, s.b, s.adhesionFraction, toString(s.status));
  out << line;
}

int runCommand(const Options& o, std::ostream& out, std::ostream& err) {
  const ContactParameters p = parametersFrom(o);
  if (!o.values.count("scenario")) throw std::invalid_argument("run: --scenario FILE is required");
  const std::string file = o.values.at("scenario");
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

}  // namespace

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    const Options o = parse(args);
    if (o.command == "help") {
      printHelp(out);
      return 0;
    }
    if (o.command == "run") return runCommand(o, out, err);
    if (o.command == "freq") return freqCommand(o.values, o.names, out);
    err << "contact_cli: "
        << (o.command.empty() ? "missing command" : "unknown command '" + o.command + "'") << "\n"
        << kUsage;
    return 2;
  } catch (const std::exception& e) {
    err << "contact_cli: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace wheel_rail_contact
