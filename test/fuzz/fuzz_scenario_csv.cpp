// libFuzzer target: contact_cli's scenario reader (scenario.hpp) on arbitrary text. Findings: a
// crash or sanitizer report; an exception other than ScenarioError; an accepted scenario with a
// non-finite value or a time that does not increase strictly. Accepted rows are then replayed,
// as contact_cli run does (dt = t minus the previous row's t), through a small steady model that
// must keep contact_model.hpp's output contract for whatever finite values the text held.
#include <cmath>
#include <exception>
#include <sstream>
#include <string>

#include "fuzz_checks.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/scenario.hpp"

using namespace wheel_rail_contact;
using namespace wheel_rail_contact::fuzz;

namespace {

constexpr size_t kMaxReplayedRows = 64;  // keeps one input cheap; the step fuzzer covers models

std::vector<ScenarioRow> read(const std::string& text, bool* ok) {
  std::istringstream in(text);
  *ok = true;
  try {
    return readScenario(in, "fuzz.csv");
  } catch (const ScenarioError&) {
    *ok = false;  // a malformed scenario is allowed to throw exactly this
  } catch (const std::exception& e) {
    finding(std::string("readScenario threw something else: ") + e.what());
  }
  return {};
}

void checkRows(const std::vector<ScenarioRow>& rows) {
  for (size_t k = 0; k < rows.size(); ++k) {
    const ScenarioRow& r = rows[k];
    for (double v : {r.t, r.V, r.xi, r.eta, r.phi, r.fz, r.a, r.b, r.mu})
      if (!std::isfinite(v)) finding("accepted a non-finite value in row " + std::to_string(k));
    if (k > 0 && !(r.t > rows[k - 1].t))
      finding("accepted a time that does not increase, row " + std::to_string(k));
  }
}

void replay(const std::vector<ScenarioRow>& rows) {
  ContactParameters p;
  p.model = "steady";  // the scenario parser is the target: the cheapest model
  p.nx = 6;
  p.ny = 5;
  const auto model = makeContactModel(p);
  for (size_t k = 0; k < rows.size() && k < kMaxReplayedRows; ++k) {
    const StepInput in = stepInputAt(rows, k);
    StepOutput out;
    try {
      out = model->step(in);
    } catch (const std::exception& e) {
      finding(std::string("step() threw: ") + e.what() + "\n  in: " + describe(in));
    }
    checkOutputContract(in, out, "replayed row " + std::to_string(k));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bool ok = false;
  const auto rows = read(std::string(reinterpret_cast<const char*>(data), size), &ok);
  if (!ok) return 0;
  checkRows(rows);
  replay(rows);
  return 0;
}
