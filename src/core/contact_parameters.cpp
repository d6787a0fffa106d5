#include "wheel_rail_contact/contact_parameters.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& why) {
  throw std::invalid_argument(name + ": " + why);
}

double parseDouble(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    fail(name, "expected a finite number, got '" + text + "'");
  return v;
}

int parseInt(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || v < -1000000 || v > 1000000)
    fail(name, "expected an integer, got '" + text + "'");
  return static_cast<int>(v);
}

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::vector<ParameterDoc> parameterDocs() {
  const ContactParameters d;
  return {
      {"G", "Pa", str(d.G), "shear modulus of wheel and rail, [1e3, 1e13]"},
      {"nu", "-", str(d.nu), "Poisson ratio, [0, 0.5]"},
      {"mu", "-", str(d.mu), "Coulomb friction coefficient, 0 or [1e-6, 1e3]"},
      {"a0", "m", str(d.a0), "reference semi-axis along the rolling direction at fz0, [1e-6, 1]"},
      {"b0", "m", str(d.b0), "reference lateral semi-axis at fz0, [1e-6, 1]; a0/b0 in [0.1, 10]"},
      {"fz0", "N", str(d.fz0), "reference normal load, [1e-6, 1e9]; a, b scale as (fz/fz0)^(1/3)"},
      {"nx", "-", std::to_string(d.nx),
       "FastSim nodes per strip (exact: elements along x), [2, 400]"},
      {"ny", "-", std::to_string(d.ny), "FastSim strips (exact: elements along y), [1, 400]"},
      {"model", "", d.model,
       "nss (NSS-FastSim) | steady | shen-li | exact | auto (steady or nss, as needed)"},
      {"mesh", "", d.mesh, "fixed (grid for fz_max) | adaptive (grid follows the patch)"},
      {"tolerance", "-", str(d.tolerance),
       "model auto: force error allowed, fraction of the peak force, (0, 1)"},
      {"fz_max", "N", str(d.fz_max), "largest load the fixed mesh covers; 0 = 1.5 fz0"},
      {"chi_table", "", "(shipped)",
       "chi table CSV for nss; empty = the shipped config/chi_table.csv"},
      {"fastsim", "", "(per model)",
       "calibrated | classic (Kalker 1982): FastSim's steady part; default calibrated for nss "
       "and auto, classic for steady and shen-li"},
  };
}

namespace {

FastSimVariant parseFastSim(const std::string& text) {
  if (text == "calibrated") return FastSimVariant::kCalibrated;
  if (text == "classic") return FastSimVariant::kClassic;
  // An empty value used to mean the model's own variant: now the parameter is left out for that.
  fail("fastsim",
       "must be calibrated or classic (leave it out for the model's own: calibrated "
       "for nss and auto, classic for steady and shen-li), got '" +
           text + "'");
}

// A physical range, wide enough for any wheel-rail or laboratory contact; beyond it (e.g. a
// subnormal mu, G = 1e200 Pa) the solvers' arithmetic under- or overflows into NaN.
void requireIn(const char* name, double v, double lo, double hi, const char* unit) {
  if (!(v >= lo && v <= hi) || !std::isfinite(v))
    fail(name, "must be in [" + str(lo) + ", " + str(hi) + "]" + unit + ", got " + str(v));
}

}  // namespace

void validate(const ContactParameters& p) {
  requireIn("G", p.G, 1e3, 1e13, " Pa");
  if (!(p.nu >= 0.0 && p.nu <= 0.5)) fail("nu", "must be in [0, 0.5], got " + str(p.nu));
  if (p.mu != 0.0) requireIn("mu", p.mu, 1e-6, 1e3, " (or 0: frictionless)");
  requireIn("a0", p.a0, 1e-6, 1.0, " m");
  requireIn("b0", p.b0, 1e-6, 1.0, " m");
  requireIn("fz0", p.fz0, 1e-6, 1e9, " N");
  const double ab = p.a0 / p.b0;
  if (!(ab >= kKalkerMinAOverB && ab <= kKalkerMaxAOverB))
    fail("b0", "a0/b0 = " + str(ab) + " is outside Kalker's table [0.1, 10]");
  if (p.nx < 2 || p.nx > 400) fail("nx", "must be in [2, 400], got " + std::to_string(p.nx));
  if (p.ny < 1 || p.ny > 400) fail("ny", "must be in [1, 400], got " + std::to_string(p.ny));
  if (p.model != "steady" && p.model != "shen-li" && p.model != "nss" && p.model != "exact" &&
      p.model != "auto")
    fail("model", "must be one of steady, shen-li, nss, exact, auto; got '" + p.model + "'");
  // The adaptive mesh's old name, refused with its new one (it read like model auto).
  if (p.mesh == "auto") fail("mesh", "'auto' was renamed 'adaptive'");
  if (p.mesh != "fixed" && p.mesh != "adaptive")
    fail("mesh", "must be fixed or adaptive, got '" + p.mesh + "'");
  if (!(p.tolerance > 0.0 && p.tolerance < 1.0))
    fail("tolerance", "must be in (0, 1), got " + str(p.tolerance));
  if (!(p.fz_max >= 0.0) || !std::isfinite(p.fz_max))
    fail("fz_max", "must be >= 0 (0 = 1.5 fz0), got " + str(p.fz_max));
}

void setParameter(ContactParameters* p, const std::string& name, const std::string& value) {
  if (name == "G")
    p->G = parseDouble(name, value);
  else if (name == "nu")
    p->nu = parseDouble(name, value);
  else if (name == "mu")
    p->mu = parseDouble(name, value);
  else if (name == "a0")
    p->a0 = parseDouble(name, value);
  else if (name == "b0")
    p->b0 = parseDouble(name, value);
  else if (name == "fz0")
    p->fz0 = parseDouble(name, value);
  else if (name == "nx")
    p->nx = parseInt(name, value);
  else if (name == "ny")
    p->ny = parseInt(name, value);
  else if (name == "model")
    p->model = value;
  else if (name == "mesh")
    p->mesh = value;
  else if (name == "tolerance")
    p->tolerance = parseDouble(name, value);
  else if (name == "fz_max")
    p->fz_max = parseDouble(name, value);
  else if (name == "chi_table")
    p->chi_table = value;
  else if (name == "fastsim")
    p->fastsim = parseFastSim(value);
  else
    fail(name, "unknown parameter");
}

double effectiveFzMax(const ContactParameters& p) {
  return p.fz_max > 0.0 ? p.fz_max : 1.5 * p.fz0;
}

const char* toString(FastSimVariant v) {
  return v == FastSimVariant::kCalibrated ? "calibrated" : "classic";
}

FastSimVariant resolvedFastSim(const ContactParameters& p) {
  if (p.fastsim) return *p.fastsim;
  // The model's own: calibrated for the transient models the package recommends (nss, auto),
  // classic for steady and shen-li, the baselines every chart compares against (Kalker's FastSim
  // and Shen-Li as published).
  return p.model == "nss" || p.model == "auto" ? FastSimVariant::kCalibrated
                                               : FastSimVariant::kClassic;
}

const char* fastsimVariantName(const ContactParameters& p) {
  if (p.model == "exact") return "no FastSim";
  return resolvedFastSim(p) == FastSimVariant::kCalibrated ? "calibrated FastSim"
                                                           : "classic FastSim";
}

}  // namespace wheel_rail_contact
