/// Scenario files: the input histories contact_cli replays, one row per time step.
/// CSV with a header naming t,V,xi,eta,phi,fz (s, m/s, -, -, 1/m, N) and optionally a,b (m, both
/// or neither) and mu (-), the per-step geometry and friction of StepInput (0 in a row: not given,
/// the parameters apply); any column order; an unknown or repeated column is an error; '#' lines
/// are comments.
#pragma once

#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"

namespace wheel_rail_contact {

struct ScenarioRow {
  double t = 0.0;    ///< [s]
  double V = 0.0;    ///< [m/s]
  double xi = 0.0;   ///< [-]
  double eta = 0.0;  ///< [-]
  double phi = 0.0;  ///< [1/m]
  double fz = 0.0;   ///< [N]
  double a = 0.0;    ///< [m]; 0: not given (no column, or 0 in the row)
  double b = 0.0;    ///< [m]; 0: not given
  double mu = 0.0;   ///< [-]; 0: not given
};

/// A malformed scenario: what() names the source, line and field.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a whole scenario. Every value must be a finite number and t must increase strictly.
/// `source` names the input in messages. Throws ScenarioError.
std::vector<ScenarioRow> readScenario(std::istream& in, const std::string& source);

/// The step of row k: dt from the previous row's time, 0 for the first (as contact_cli runs it).
StepInput stepInputAt(const std::vector<ScenarioRow>& rows, size_t k);

}  // namespace wheel_rail_contact
