/// Shared by the fuzz targets: how a finding is reported, and the per-step output contract of
/// contact_model.hpp checked on every step. Units as in contact_model.hpp.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "wheel_rail_contact/contact_model.hpp"

namespace wheel_rail_contact::fuzz {

/// A finding: print why and abort, so that libFuzzer saves the input as a crash artifact.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline std::string describe(const StepInput& in) {
  char s[400];
  std::snprintf(s, sizeof s,
                "dt=%.17g V=%.17g xi=%.17g eta=%.17g phi=%.17g fz=%.17g a=%.17g b=%.17g mu=%.17g",
                in.dt, in.V, in.xi, in.eta, in.phi, in.fz, in.a, in.b, in.mu);
  return s;
}

inline std::string describe(const StepOutput& o) {
  char s[320];
  std::snprintf(
      s, sizeof s, "status=%s fx=%.17g fy=%.17g mz=%.17g fz=%.17g a=%.17g b=%.17g adh=%.17g (%s)",
      toString(o.status), o.fx, o.fy, o.mz, o.fz, o.a, o.b, o.adhesionFraction, o.message);
  return s;
}

/// Every numeric output field finite, zero forces whenever the step was screened out, the status
/// screenStep prescribes, and the adhesion fraction a fraction.
inline void checkOutputContract(const StepInput& in, const StepOutput& out,
                                const std::string& where) {
  const auto fail = [&](const char* why) {
    finding(where + ": " + why + "\n  in:  " + describe(in) + "\n  out: " + describe(out));
  };
  for (double v : {out.fx, out.fy, out.mz, out.fz, out.a, out.b, out.adhesionFraction})
    if (!std::isfinite(v)) fail("non-finite output field");
  StepOutput screened;
  if (screenStep(in, &screened)) {
    if (out.status != screened.status) fail("status differs from screenStep's");
    if (out.fx != 0.0 || out.fy != 0.0 || out.mz != 0.0) fail("screened step with a force");
  } else if (out.status == StepStatus::kRejected || out.status == StepStatus::kNoLoad) {
    // The exact model alone rejects a load above fz_max (its grid must cover the patch).
    if (out.fx != 0.0 || out.fy != 0.0 || out.mz != 0.0) fail("rejected step with a force");
  }
  if (!(out.adhesionFraction >= 0.0 && out.adhesionFraction <= 1.0))
    fail("adhesion fraction outside [0, 1]");
}

/// |t| <= bound (1 + rel): Coulomb with room for the rounding of the saturation's rescale.
inline bool withinBound(double tx, double ty, double bound, double rel) {
  return std::hypot(tx, ty) <= bound * (1.0 + rel);
}

}  // namespace wheel_rail_contact::fuzz
