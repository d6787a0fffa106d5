#include "wheel_rail_contact/contact_model.hpp"

#include <cmath>
#include <stdexcept>

#include "core/models/auto_model.hpp"
#include "core/models/exact_model.hpp"
#include "core/models/nss_model.hpp"
#include "core/models/steady_model.hpp"

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

std::unique_ptr<ContactModel> makeContactModel(const ContactParameters& p) {
  validate(p);
  if (p.model == "steady") return std::make_unique<SteadyModel>(p);
  if (p.model == "exact") return std::make_unique<ExactModel>(p);
  if (p.model == "shen-li") return std::make_unique<NssModel>(p, ChiTable::uniform({}));
  if (p.model == "nss" || p.model == "auto") {
    ChiTable chi;
    try {
      chi = p.chi_table.empty() ? ChiTable::shipped() : ChiTable::load(p.chi_table);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("chi_table: ") + e.what());
    }
    if (p.model == "auto") return std::make_unique<AutoModel>(p, chi);
    return std::make_unique<NssModel>(p, chi);
  }
  throw std::invalid_argument("model: '" + p.model + "' is not available in this build yet");
}

}  // namespace wheel_rail_contact
