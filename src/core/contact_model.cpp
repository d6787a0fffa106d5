#include "wheel_rail_contact/contact_model.hpp"

#include <cmath>
#include <stdexcept>

#include "core/models/auto_model.hpp"
#include "core/models/exact_model.hpp"
#include "core/models/nss_model.hpp"
#include "core/models/steady_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

const char* toString(StepStatus s) {
  switch (s) {
    case StepStatus::kOk:
      return "ok";
    case StepStatus::kNoLoad:
      return "no load";
    case StepStatus::kStandstill:
      return "standstill";
    case StepStatus::kRejected:
      return "rejected input";
    case StepStatus::kNotConverged:
      return "not converged";
  }
  return "unknown";
}

namespace {

const char* checkStepGeometry(const StepInput& in) {
  // The ranges validate() accepts for a0, b0, a0/b0 and mu: Kalker's table and the chi table stop
  // at a/b in [0.1, 10], and a patch beyond 1 m or below 1 um is no wheel-rail contact.
  if ((in.a != 0.0) != (in.b != 0.0)) return "a and b must be given together (or both 0)";
  if (in.a != 0.0) {
    if (!(in.a >= 1e-6 && in.a <= 1.0)) return "a must be in [1e-6, 1] m (or 0: not given)";
    if (!(in.b >= 1e-6 && in.b <= 1.0)) return "b must be in [1e-6, 1] m (or 0: not given)";
    const double ab = in.a / in.b;
    if (!in.shape && !(ab >= kKalkerMinAOverB && ab <= kKalkerMaxAOverB))
      return "a/b must be in [0.1, 10] (Kalker's table)";
  }
  if (in.shape) {
    if (in.a == 0.0) return "a shape needs its equivalent ellipse a, b";
    const char* why = checkPatchShape(*in.shape);
    if (*why) return why;
  }
  if (in.mu != 0.0 && !(in.mu >= 1e-6 && in.mu <= 1e3))
    return "mu must be in [1e-6, 1000] (or 0: not given)";
  return "";
}

}  // namespace

const char* checkStepInput(const StepInput& in) {
  if (!std::isfinite(in.dt)) return "dt is not finite";
  if (!std::isfinite(in.V)) return "V is not finite";
  if (!std::isfinite(in.xi)) return "xi is not finite";
  if (!std::isfinite(in.eta)) return "eta is not finite";
  if (!std::isfinite(in.phi)) return "phi is not finite";
  if (!std::isfinite(in.fz)) return "fz is not finite";
  if (in.dt < 0.0) return "dt is negative";
  // Beyond this the FastSim and half-space arithmetic overflows (found by fuzzing): no contact
  // comes near it, so such input is out of range rather than a case to compute.
  for (double v : {in.dt, in.V, in.xi, in.eta, in.phi, in.fz})
    if (std::abs(v) > kMaxInputMagnitude) return "an input exceeds 1e12 in magnitude (SI units)";
  // Absent per-step geometry and friction cost this one branch (NaN != 0 takes it too).
  if (in.a != 0.0 || in.b != 0.0 || in.mu != 0.0 || in.shape) return checkStepGeometry(in);
  return "";
}

bool screenStep(const StepInput& in, StepOutput* out) {
  *out = StepOutput();
  out->message = checkStepInput(in);
  if (*out->message) {
    out->status = StepStatus::kRejected;
    return true;
  }
  if (!(in.fz >= kMinLoad)) {
    out->status = StepStatus::kNoLoad;
    out->message = "fz below 1e-6 N: no contact, history cleared";
    return true;
  }
  return false;
}

namespace {

// The calibrated FastSim's table when p runs it (resolvedFastSim), else empty (classic): the
// parsed shipped table itself, not a copy (each model keeps only its own mesh's part).
const CalibrationTable& steadyCalibration(const ContactParameters& p) {
  static const CalibrationTable classic;
  if (p.model == "exact" || resolvedFastSim(p) == FastSimVariant::kClassic) return classic;
  try {
    return CalibrationTable::shipped();
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(std::string("fastsim: ") + e.what());
  }
}

}  // namespace

std::unique_ptr<ContactModel> makeContactModel(const ContactParameters& given) {
  validate(given);
  ContactParameters p = given;  // what the model runs: fastsim resolved (exact ignores it)
  if (p.model != "exact") p.fastsim = resolvedFastSim(given);
  const CalibrationTable& calibration = steadyCalibration(p);
  if (p.model == "steady")
    return std::make_unique<SteadyModel>(p, SteadyModel::Mesh::kFittedToPatch, calibration);
  if (p.model == "exact") return std::make_unique<ExactModel>(p);
  if (p.model == "shen-li")
    return std::make_unique<NssModel>(p, ChiTable::uniform({}), calibration);
  if (p.model == "nss" || p.model == "auto") {
    ChiTable chi;
    try {
      chi = p.chi_table.empty() ? ChiTable::shipped() : ChiTable::load(p.chi_table);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("chi_table: ") + e.what());
    }
    if (p.model == "auto") return std::make_unique<AutoModel>(p, chi, calibration);
    return std::make_unique<NssModel>(p, chi, calibration);
  }
  throw std::invalid_argument("model: '" + p.model + "' is not available in this build yet");
}

}  // namespace wheel_rail_contact
